// Per-frame inputs shared by every scene program. Set by app/gpu/render.c.
// World: right-handed, Y up, metres. Rays: see app/view/camera.h for the pixel → direction convention.
uniform vec2 uResolution;   // pixels of the whole image
uniform vec2 uTileOffset;   // where this render target's pixel (0,0) sits in it (bands of big shots)
uniform vec3 uCamPos;
uniform vec3 uCamForward, uCamRight, uCamUp; // orthonormal basis
uniform float uTanHalfFov;  // tan(vertical fov / 2)
uniform float uPixelAngle;  // 2 tan(fov/2) / height: the angle one pixel spans (camera_pixel_angle)
uniform float uFootprintT0; // 0, or orthographic: a pixel is uPixelAngle · (t + uFootprintT0) wide at t
uniform int uProjection;    // app/view/camera.h's camera_projection
uniform int uStereo;        // camera_stereo: 0 none, 1 side by side, 2 top-bottom
uniform float uEyeSeparation, uFocus, uLensRadius; // world units
uniform vec2 uLensSample;   // this sample's point of the unit square for the lens (Halton 5, 7)
// A pixel's width at distance t along its ray: hit thresholds and levels of detail scale with it.
float footprintAt(float t) { return uPixelAngle * (t + uFootprintT0); }
uniform int uAdaptive;          // 1: only pixels the edge mask keeps take this sample (app/gpu/render.c)
uniform sampler2D uEdgeMask;
uniform vec2 uJitter;       // sub-pixel offset of this sample, pixels; (0,0) for the first

// A deep zoom (PRECISION_DOUBLE: fractal/common.glsl): positions here are relative to the eye, whose
// world position is a double (uOrigin, read by the formula); uCamPos is then 0. worldApprox() brings
// a position back to the world where a float's accuracy is plenty (point lights, height fog), and
// uOriginFloor is the double origin's own resolution (hit thresholds never go below it).
#ifdef PRECISION_DOUBLE
uniform vec3 uOriginApprox;
uniform float uOriginFloor;
vec3 worldApprox(vec3 p) { return p + uOriginApprox; }
#else
vec3 worldApprox(vec3 p) { return p; }
#endif

// Run-time switches for the compiled-in effects (bit FX_NAME_BIT), all on unless the bench measures
// what an effect costs when compiled in but switched off.
uniform uint uFxRuntime;
bool fxOn(uint bit) { return (uFxRuntime & bit) != 0u; }
