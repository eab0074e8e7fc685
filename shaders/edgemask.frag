// Adaptive sampling's mask (app/gpu/render.c): after the first sample (the pixel centres), a pixel gets
// further, jittered samples only where a neighbour in its 3×3 block differs: in displayed colour by
// more than EDGE_COLOR (tone-mapped, so a difference in the dark counts as it is seen), in depth by
// more than EDGE_DEPTH of the nearer, in hit/miss, or in normal by more than ~25°. Elsewhere the
// centre sample already is the pixel's mean (shading is deterministic; only the sub-pixel position
// varies between samples), so further samples would only repeat it.
uniform sampler2D uAccum;       // target 0 after one sample: linear radiance
uniform sampler2D uNormalDepth; // target 1: normal, depth (−1: a miss)
uniform float uExposure;
uniform ivec2 uSize;            // the active image
out vec4 oMask;

const float EDGE_COLOR = 0.05, EDGE_DEPTH = 0.02, EDGE_NORMAL = 0.9;

vec3 shown(ivec2 p) // tone-mapped as display.frag does (ACES fit), before sRGB encoding
{
    vec3 x = texelFetch(uAccum, p, 0).rgb * uExposure;
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = shown(p);
    vec4 nd = texelFetch(uNormalDepth, p, 0);
    bool edge = false;
    for (int dy = -1; dy <= 1 && !edge; dy++)
        for (int dx = -1; dx <= 1 && !edge; dx++) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), uSize - 1);
            vec4 n = texelFetch(uNormalDepth, q, 0);
            bool hitP = nd.w >= 0.0, hitQ = n.w >= 0.0;
            edge = any(greaterThan(abs(shown(q) - c), vec3(EDGE_COLOR))) || hitP != hitQ ||
                   (hitP && hitQ && (abs(n.w - nd.w) > EDGE_DEPTH * min(n.w, nd.w) || dot(n.xyz, nd.xyz) < EDGE_NORMAL));
        }
    oMask = vec4(edge ? 1.0 : 0.0);
}
