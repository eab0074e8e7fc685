// Accumulated linear radiance → display: average the samples, expose, tone-map, encode sRGB.
// Tone curve: K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2015), a fit of the ACES RRT+ODT.
uniform sampler2D uAccum;
uniform float uInvSamples;
uniform float uExposure;
out vec4 oColor;

vec3 acesFit(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

vec3 linearToSrgb(vec3 c)
{
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main()
{
    vec3 c = texelFetch(uAccum, ivec2(gl_FragCoord.xy), 0).rgb * uInvSamples;
    oColor = vec4(linearToSrgb(acesFit(c * uExposure)), 1.0);
}
