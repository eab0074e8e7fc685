// Every distance-field program's image, the compute path: the same sample as sdf.frag (the same
// renderPixel, common/sdf_main.glsl), one invocation a pixel, for GPUs whose fragment pipeline is a
// small part of the chip (a datacenter GPU runs pixel shaders on 2 of its TPCs). Each invocation owns
// its pixel, so target 0's accumulation is a plain read, add and write: what additive blending does on
// the fragment path. app/gpu/render.c dispatches the rows of a band in tiles (uRect).
#include "common/contract.glsl"
#include "common/sdf_main.glsl"

layout(local_size_x = 8, local_size_y = 8) in; // 64 invocations: two NVIDIA warps, one AMD wave64

layout(rgba32f) uniform image2D uAccum;       // target 0: accumulated radiance, alpha counts samples
layout(rgba32f) uniform image2D uNormalDepth; // target 1
layout(rgba32f) uniform image2D uAux;         // target 2
layout(rgba32f) uniform image2D uSquares;     // target 3: the radiance squared, summed (the variance AOV)
layout(rgba32f) uniform image2D uAlbedo;      // target 4: the first hit's material colour
uniform ivec4 uRect;       // the pixels of this dispatch: x, y (GL rows, from the bottom), width, height
uniform int uFirstSample;  // 1: the image's first sample, which also writes the AOVs

void main()
{
    ivec2 px = uRect.xy + ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(px, uRect.xy + uRect.zw));
    if (uAdaptive != 0 && texelFetch(uEdgeMask, px, 0).r < 0.5)
        return; // adaptive sampling: the centre sample is this pixel's mean already
    vec4 color, normalDepth, aux, albedo;
    renderPixel(vec2(px) + 0.5, color, normalDepth, aux, albedo);
    if (!inside)
        return;
    if (uFirstSample != 0) {
        imageStore(uAccum, px, color);
        imageStore(uNormalDepth, px, normalDepth);
        imageStore(uAux, px, aux);
        imageStore(uSquares, px, vec4(color.rgb * color.rgb, sampleGrazed ? 1.0 : 0.0));
        imageStore(uAlbedo, px, albedo);
    } else {
        imageStore(uAccum, px, imageLoad(uAccum, px) + color);
        imageStore(uSquares, px, imageLoad(uSquares, px) + vec4(color.rgb * color.rgb, sampleGrazed ? 1.0 : 0.0));
    }
}
