// Evaluates the scene's map() at the points in uPoints (one per texel): the distance estimate as the
// shader computes it, for tests and for the window's distance-driven flying speed.
#include "common/contract.glsl"

uniform sampler2D uPoints;
out vec4 oDistance;

void main()
{
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    oDistance = vec4(map(p), 0.0, 1.0);
#ifdef PROBE_LOOPS
    // z: how many iterations a loop run after map() gets before the driver's limiter ends it (a
    // driver without one: all PROBE_LOOPS), so map()'s own loops ran PROBE_LOOPS − z (check-formula)
    int spare = 0;
    for (int i = 0; i < PROBE_LOOPS; i++)
        spare++;
    oDistance.z = float(spare);
#endif
}
