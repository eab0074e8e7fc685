// Evaluates the fog's optical depth for (ray origin y, ray direction y, length) triples in uPoints:
// the function rendering uses, for tests against quadrature in double.
#include "common/fog.glsl"

uniform sampler2D uPoints;
out vec4 oDistance;

void main()
{
    vec3 q = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    oDistance = vec4(fogOpticalDepth(q.x, q.y, q.z), 0.0, 0.0, 1.0);
}
