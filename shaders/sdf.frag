// Every distance-field program's image, the fragment path: a full-screen triangle whose fragments each
// take one sample (common/sdf_main.glsl). Target 0 accumulates by additive blending; the first
// sample of an image also writes the AOVs (app/gpu/render.c sets the draw buffers).
#include "common/contract.glsl"
#include "common/sdf_main.glsl"

layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oNormalDepth;
layout(location = 2) out vec4 oAux;
layout(location = 3) out vec4 oSquares; // the radiance squared: with target 0's sum, the variance AOV
layout(location = 4) out vec4 oAlbedo;  // the first hit's material colour (the albedo AOV)

void main()
{
    if (uAdaptive != 0 && texelFetch(uEdgeMask, ivec2(gl_FragCoord.xy), 0).r < 0.5)
        discard; // adaptive sampling: the centre sample is this pixel's mean already
    renderPixel(gl_FragCoord.xy, oColor, oNormalDepth, oAux, oAlbedo);
    oSquares = vec4(oColor.rgb * oColor.rgb, sampleGrazed ? 1.0 : 0.0); // alpha: the samples that passed by
}
