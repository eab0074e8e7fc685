// Parallax occlusion mapping: a heightmap carved into a planar face, found with the height-field
// lab's search (common/heightsearch.glsl) run in the face's tangent space. The face's frame is its
// dominant world axis (as the triplanar textures use); the layer lies between the face (heightmap
// white) and relief_depth below it (black). Self-shadowing inside the layer is not simulated.
uniform int uMatRelief[NUM_MATERIALS];         // heightmap texture index, −1 none
uniform float uMatReliefDepth[NUM_MATERIALS];   // metres below the surface that its black lies
uniform float uMatReliefTexels[NUM_MATERIALS];  // heightmap width in texels

struct ReliefFrame {
    vec3 T, B, N;
    int tex;
    float depth, scale;
};
ReliefFrame gRelief; // the face being searched (GLSL has no closures)

float reliefHeight(vec2 uv)
{
    vec2 st = uv * gRelief.scale;
    if (gRelief.tex == 0) return textureLod(uTex0, st, 0.0).r;
    if (gRelief.tex == 1) return textureLod(uTex1, st, 0.0).r;
    if (gRelief.tex == 2) return textureLod(uTex2, st, 0.0).r;
    return textureLod(uTex3, st, 0.0).r;
}

// tangent space: horizontal (x, z) = (along T, along B), vertical y = along N (0 at the face)
float hsSurfaceY(vec2 xz) { return -gRelief.depth * (1.0 - reliefHeight(xz)); }
#include "common/heightsearch.glsl"

// p, n: the hit on the face; rd: the ray. Moves p to where the ray meets the relief and returns its
// normal (n unchanged where the material has no relief); steps counts height samples.
vec3 applyRelief(int mat, inout vec3 p, vec3 n, vec3 rd, inout int steps)
{
    int tex = uMatRelief[mat];
    if (tex < 0 || !fxOn(FX_RELIEF_BIT))
        return n;
    vec3 a = abs(n);
    int axis = a.x > a.y && a.x > a.z ? 0 : (a.y > a.z ? 1 : 2);
    gRelief.N = axis == 0 ? vec3(sign(n.x), 0, 0) : axis == 1 ? vec3(0, sign(n.y), 0) : vec3(0, 0, sign(n.z));
    gRelief.T = axis == 0 ? vec3(0, 0, 1) : vec3(1, 0, 0);
    gRelief.B = cross(gRelief.N, gRelief.T);
    gRelief.tex = tex;
    gRelief.depth = uMatReliefDepth[mat];
    gRelief.scale = uMatUvScale[mat]; // repeats per metre
    vec3 ro = vec3(dot(p, gRelief.T), 0.0, dot(p, gRelief.B));
    vec3 d = vec3(dot(rd, gRelief.T), dot(rd, gRelief.N), dot(rd, gRelief.B));
    if (d.y >= -1e-4)
        return n; // leaving the face, or along it: nothing to look into
    float texel = 1.0 / (gRelief.scale * uMatReliefTexels[mat]);
    float t1 = gRelief.depth / -d.y;
    float dt = float(LINEAR_STEP) * texel / max(length(d.xz), 1e-3);
    float t = heightSearch(ro, d, 0.0, t1, min(dt, t1), steps);
    if (t < 0.0)
        t = t1;
    p += rd * t;
    vec2 uv = (ro + d * t).xz;
    float e = texel;
    float hx = reliefHeight(uv + vec2(e, 0.0)) - reliefHeight(uv - vec2(e, 0.0));
    float hz = reliefHeight(uv + vec2(0.0, e)) - reliefHeight(uv - vec2(0.0, e));
    vec3 nt = normalize(vec3(-gRelief.depth * hx / (2.0 * e), 1.0, -gRelief.depth * hz / (2.0 * e)));
    return normalize(nt.x * gRelief.T + nt.y * gRelief.N + nt.z * gRelief.B);
}
