// Accumulated linear radiance → display: average the samples, expose, tone-map, encode sRGB.
// Tone curve: K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2015), a fit of the ACES RRT+ODT.
// View 1 shows the primary ray's march steps instead (a heat map: blue few … red MAX_STEPS);
// view 2 the difference to a grabbed reference frame (a heat map: blue same … red 1/8 off).
uniform sampler2D uAccum;
uniform sampler2D uAux; // target 2: steps, exit direction
uniform sampler2D uReference;
uniform sampler2D uNormalDepth; // target 1: depth in w (−1: a miss)
uniform int uEdgeAware;         // 1: a stretched image does not blend across depth edges
uniform sampler2D uPreview;     // the last moving image (render_keep_preview), bottom-left corner
uniform vec2 uPreviewSize;      // its size; 0: none
uniform float uInvRefSamples;
uniform float uExposure;
uniform int uPost;     // 1: a Fragmentarium fragment's own post (fractal.look = fragment) instead of ACES + sRGB
uniform int uPostTone; // its ToneMapping: 1 linear, 2 exponential, 3 filmic, 4 Reinhard, 5 sigmoid
uniform vec4 uPostGEBC; // its Gamma, Exposure, Brightness, Contrast
uniform float uPostSaturation;
uniform int uView;
uniform float uMaxSteps;
uniform vec2 uSrcSize; // the active image in the targets (bottom-left corner)
uniform vec2 uDstSize; // the output
out vec4 oColor;

// The output pixel's centre in the active image's texel coordinates (texel centres at integers).
vec2 srcPos() { return gl_FragCoord.xy * uSrcSize / uDstSize - 0.5; }

ivec2 nearestTexel() { return clamp(ivec2(floor(srcPos() + 0.5)), ivec2(0), ivec2(uSrcSize) - 1); }

// Bilinear from the four nearest texels (the targets are NEAREST-filtered float textures); exactly the
// texel when the sizes are equal.
vec4 bilinear4(sampler2D t)
{
    vec2 p = srcPos();
    ivec2 i = ivec2(floor(p)), hi = ivec2(uSrcSize) - 1;
    vec2 f = p - vec2(i);
    vec4 a = texelFetch(t, clamp(i, ivec2(0), hi), 0), b = texelFetch(t, clamp(i + ivec2(1, 0), ivec2(0), hi), 0);
    vec4 c = texelFetch(t, clamp(i + ivec2(0, 1), ivec2(0), hi), 0), d = texelFetch(t, clamp(i + ivec2(1, 1), ivec2(0), hi), 0);
    // each texel as its mean (alpha counts its samples), so texels with different counts mix right
    a /= max(a.a, 1e-6), b /= max(b.a, 1e-6), c /= max(c.a, 1e-6), d /= max(d.a, 1e-6);
    vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    if (uEdgeAware != 0 && uSrcSize != uDstSize) {
        // Depth-aware upsampling (after Kopf et al. 2007, "Joint Bilateral Upsampling", with the
        // low-resolution depth as its own guide): the taps whose depth differs from the nearest
        // tap's by more than a few percent (the other side of a silhouette) are left out, so edges
        // stay sharp instead of blending foreground into background.
        vec4 z = vec4(texelFetch(uNormalDepth, clamp(i, ivec2(0), hi), 0).w,
                      texelFetch(uNormalDepth, clamp(i + ivec2(1, 0), ivec2(0), hi), 0).w,
                      texelFetch(uNormalDepth, clamp(i + ivec2(0, 1), ivec2(0), hi), 0).w,
                      texelFetch(uNormalDepth, clamp(i + ivec2(1, 1), ivec2(0), hi), 0).w);
        z = mix(z, vec4(1e30), lessThan(z, vec4(0.0))); // a miss: infinitely far
        int near = f.x < 0.5 ? (f.y < 0.5 ? 0 : 2) : (f.y < 0.5 ? 1 : 3);
        float zn = z[near];
        const float DEPTH_EDGE = 0.05;
        vec4 keep = vec4(lessThanEqual(abs(z - zn), vec4(DEPTH_EDGE * min(zn, 1e29))));
        w *= keep;
        w /= max(w.x + w.y + w.z + w.w, 1e-6);
    }
    return a * w.x + b * w.y + c * w.z + d * w.w;
}

vec3 heat(float x)
{
    x = clamp(x, 0.0, 1.0);
    return clamp(vec3(1.5 - abs(4.0 * x - 3.0), 1.5 - abs(4.0 * x - 2.0), 1.5 - abs(4.0 * x - 1.0)), 0.0, 1.0);
}

vec3 acesFit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

vec3 linearToSrgb(vec3 c)
{
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The heat map's legend, a bar along the bottom-left corner (the window labels it): the same heat()
// as the image, so its colours cannot drift from the map's.
const vec2 LEGEND_AT = vec2(16.0, 16.0), LEGEND_SIZE = vec2(256.0, 12.0);
bool legend(out vec4 c)
{
    vec2 p = (gl_FragCoord.xy - LEGEND_AT) / LEGEND_SIZE;
    c = vec4(p.x <= 1.0 ? heat(p.x) : vec3(1.0, 0.0, 1.0), 1.0); // then a magenta patch: out of steps
    return p.y >= 0.0 && p.y <= 1.0 && p.x >= 0.0 && p.x <= 1.1;
}

// Fragmentarium's post of the mean sample (its BufferShader, with the controls of its 3D include):
// exposure and one of five tone curves, brightness, saturation and contrast about mid-grey (the luminance
// weights of Rec. 709), then 1/Gamma. The filmic curve is Hable's fit of Haarm-Pieter Duiker's (J. Hable,
// "Filmic tonemapping operators", 2010), which holds a gamma of 2.2 of its own: taken back out before 1/Gamma.
vec3 bcs(vec3 c)
{
    c *= uPostGEBC.z;
    vec3 grey = vec3(dot(c, vec3(0.2125, 0.7154, 0.0721)));
    return mix(vec3(0.5), mix(grey, c, uPostSaturation), uPostGEBC.w);
}
float sigmoid(float t)
{
    float k = 1.0 - 1.0 / (1.0 + exp(-0.5 * uPostGEBC.w * 5.0));
    return (1.0 / (1.0 + exp(-(t - 0.5) * uPostGEBC.w * 5.0)) - k) / (1.0 - 2.0 * k);
}
vec3 fragmentPost(vec3 c)
{
    c *= uPostGEBC.y;
    if (uPostTone == 1) {
        c = bcs(c);
    } else if (uPostTone == 2) {
        c = bcs(vec3(1.0) - exp(-c));
    } else if (uPostTone == 3) {
        vec3 x = max(vec3(0.0), c - vec3(0.004));
        c = bcs(pow((x * (6.2 * x + 0.5)) / (x * (6.2 * x + 1.7) + 0.06), vec3(2.2)));
    } else if (uPostTone == 4) {
        c = bcs(c / (1.0 + c));
    } else {
        c += vec3(uPostGEBC.z - 1.0);
        c = vec3(sigmoid(c.x), sigmoid(c.y), sigmoid(c.z));
    }
    return clamp(pow(max(c, vec3(0.0)), vec3(1.0 / uPostGEBC.x)), 0.0, 1.0);
}

void main()
{
    if (uView == 1) {
        if (uDstSize.x > 2.0 * LEGEND_SIZE.x && legend(oColor))
            return;
        float steps = texelFetch(uAux, nearestTexel(), 0).x;
        const vec3 OUT_OF_STEPS = vec3(1.0, 0.0, 1.0); // magenta: the step budget ran out here
        oColor = vec4(steps < 0.0 ? OUT_OF_STEPS : heat(steps / uMaxSteps), 1.0);
        return;
    }
    if (uView == 2) {
        const float DIFF_GAIN = 8.0;
        vec4 acc = texelFetch(uAccum, nearestTexel(), 0);
        vec3 now = acesFit(acc.rgb / max(acc.a, 1e-6) * uExposure);
        vec3 ref = acesFit(texelFetch(uReference, nearestTexel(), 0).rgb * uInvRefSamples * uExposure);
        oColor = vec4(heat(length(now - ref) * DIFF_GAIN), 1.0);
        return;
    }
    vec4 a = bilinear4(uAccum);
    if (texelFetch(uAccum, nearestTexel(), 0).a == 0.0 && uPreviewSize.x > 0.0) {
        // a still image whose first sample has not reached this row yet: the last moving image
        vec2 p = gl_FragCoord.xy * uPreviewSize / uDstSize - 0.5;
        ivec2 i = ivec2(floor(p)), hi = ivec2(uPreviewSize) - 1;
        vec2 f = p - vec2(i);
        vec4 t00 = texelFetch(uPreview, clamp(i, ivec2(0), hi), 0), t10 = texelFetch(uPreview, clamp(i + ivec2(1, 0), ivec2(0), hi), 0);
        vec4 t01 = texelFetch(uPreview, clamp(i + ivec2(0, 1), ivec2(0), hi), 0), t11 = texelFetch(uPreview, clamp(i + ivec2(1, 1), ivec2(0), hi), 0);
        a = mix(mix(t00 / max(t00.a, 1e-6), t10 / max(t10.a, 1e-6), f.x), mix(t01 / max(t01.a, 1e-6), t11 / max(t11.a, 1e-6), f.x), f.y);
    }
    vec3 c = a.rgb / max(a.a, 1e-6); // alpha counts each pixel's own samples (adaptive sampling)
    oColor = vec4(uPost != 0 ? fragmentPost(c * uExposure) : linearToSrgb(acesFit(c * uExposure)), 1.0);
}
