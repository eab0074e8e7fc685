#info The Menger sponge as a fold, scale and shift (Knighty's KIFS form, 2010): fathom's test of Fragmentarium's hit rule (tests/fractal/test_frag_rule.c holds the same estimate in C)
#include "DE-Raytracer.frag"
#group Menger
uniform int Iterations; slider[1,6,12]
uniform float Scale; slider[2,3,4]

// each level: |z| sorted so x >= y >= z, scaled about the corner (1, 1, 1), the middle slab folded
// back; the distance to the unit box shrinks by Scale a level
float DE(vec3 p)
{
    vec3 z = p;
    float s = 1.0;
    for (int i = 0; i < Iterations; i++) {
        z = abs(z);
        if (z.x < z.y) z.xy = z.yx;
        if (z.x < z.z) z.xz = z.zx;
        if (z.y < z.z) z.yz = z.zy;
        z = Scale * z - (Scale - 1.0) * vec3(1.0);
        if (z.z < -0.5 * (Scale - 1.0)) z.z += Scale - 1.0;
        s *= Scale;
        orbitTrap = min(orbitTrap, abs(vec4(z, dot(z, z))));
    }
    vec3 q = abs(z) - vec3(1.0);
    return (length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0)) / s;
}

#preset Default
FOV = 0.5
Eye = 2.6,1.9,-3.4
Target = 0,0,0
Up = 0,1,0
#endpreset

#preset Few
FOV = 0.5
Eye = 2.6,1.9,-3.4
Target = 0,0,0
Up = 0,1,0
FudgeFactor = 0.7
MaxRaySteps = 24
Detail = -3
#endpreset
