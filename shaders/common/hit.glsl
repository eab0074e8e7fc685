#ifndef HIT_GLSL // included by the contract and by marchers
#define HIT_GLSL
// What a ray march returns (common/march.glsl, or a program's own castRay).
struct Hit {
    bool hit;
    float t;        // distance along the ray from its origin
    float mat;      // material index
    int steps;
    bool exhausted; // unresolved: the step budget and its tail (common/march.glsl) ran out; not a hit
    int boundSteps; // of `steps`, those taken on a bound (MATERIAL_BOUND): not near the shape
};

// map() may return this material for a conservative bound that is not a surface (the fractals'
// bounding sphere): marchers step by its distance but never stop on it.
const float MATERIAL_BOUND = -1.0;
bool isBound(vec2 d) { return d.y < -0.5; }

// A terrain's water (terrain.water, terrain/terrain.glsl) is a surface of its own material: hits on it say so.
#if FX_WATER
uniform int uWaterMaterial;
bool isWater(float mat) { return int(mat + 0.5) == uWaterMaterial; }
#else
bool isWater(float mat) { return false; }
#endif

// Adaptive sampling's pass-by flag (shaders/errormask.frag): set when a ray of this sample passed
// within GRAZE_FOOTPRINTS pixel footprints of a surface (or a droplet) it did not hit. Whatever lies
// inside a pixel's cone is that close to every ray of the pixel, so a pixel none of whose samples
// passed anything by cannot be hiding a feature between them; one that did takes more samples.
#define GRAZE_FOOTPRINTS 1.5
bool sampleGrazed = false;
#endif
