#info The power-8 Mandelbulb (White and Nylander, 2009): fathom's test of Fragmentarium's hit rule (tests/fractal/test_frag_rule.c holds the same estimate in C)
#include "DE-Raytracer.frag"
#group Mandelbulb
uniform int Iterations; slider[1,10,30]
uniform float Power; slider[2,8,12]
uniform float Bailout; slider[1,4,16]

// z -> z^Power + p in spherical coordinates; the estimate 0.5 ln r · r / dr (Hart's, with dr the
// running derivative |dz/dp|)
float DE(vec3 p)
{
    vec3 z = p;
    float dr = 1.0, r = length(z);
    for (int i = 0; i < Iterations && r < Bailout; i++) {
        float theta = acos(clamp(z.z / r, -1.0, 1.0)) * Power, phi = atan(z.y, z.x) * Power;
        dr = Power * pow(r, Power - 1.0) * dr + 1.0;
        float rp = pow(r, Power);
        z = rp * vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)) + p;
        r = length(z);
        orbitTrap = min(orbitTrap, abs(vec4(z, r * r)));
    }
    return 0.5 * log(r) * r / dr;
}

#preset Default
FOV = 0.4
Eye = 0.3,2.2,-2.1
Target = 0,0,0
Up = 0,1,0
Detail = -2.8
#endpreset

#preset Near
FOV = 0.6
Eye = 0.15,1.08,-0.45
Target = 0,0.9,0
Up = 0,1,0
Detail = -2
MaxRaySteps = 200
#endpreset
