#info The Mandelbox (T. Lowe, 2010) as a Fragmentarium fragment: box fold, sphere fold, scale (fathom's example, docs/guide/fragments.md)
#define providesInit
#include "MathUtils.frag"
#include "DE-Raytracer.frag"
#group Mandelbox
// the scale s of z -> s · fold(z) + c
uniform float Scale; slider[-4,2.5,4]
// radius² below which the sphere fold inverts fully
uniform float MinRad2; slider[0,0.25,2]
// where the box fold reflects
uniform float FoldLimit; slider[0,1,2]
uniform int Iterations; slider[8,14,40]
// a turn of z each iteration (degrees about RotAxis)
uniform float Angle; slider[-180,0,180]
uniform vec3 RotAxis; slider[(-1,-1,-1),(0,1,0),(1,1,1)]
uniform int ColorIterations; slider[0,4,40]

mat3 rot;
void init() { rot = rotationMatrix3(normalize(RotAxis), Angle); }

float DE(vec3 p)
{
    vec3 z = p;
    float dr = 1.0;
    for (int i = 0; i < Iterations; i++) {
        z = clamp(z, -FoldLimit, FoldLimit) * 2.0 - z; // box fold
        float r2 = dot(z, z);
        if (i < ColorIterations)
            orbitTrap = min(orbitTrap, abs(vec4(z, r2)));
        float k = r2 < MinRad2 ? 1.0 / MinRad2 : r2 < 1.0 ? 1.0 / r2 : 1.0; // sphere fold
        z *= k;
        dr *= k;
        z = rot * (Scale * z) + p;
        dr = dr * abs(Scale) + 1.0;
    }
    return length(z) / abs(dr);
}

#preset Default
FOV = 0.45
Eye = 7.8,5.1,-9.2
Target = 0,0,0
Up = 0,1,0
Detail = -3.3
FudgeFactor = 0.9
MaxRaySteps = 300
Scale = 2.5
MinRad2 = 0.25
Iterations = 14
OrbitStrength = 0.7
BaseColor = 0.9,0.85,0.8
X = 0.9,0.4,0.1,0.6
Y = 0.2,0.5,1,0.3
Z = 0.9,0.9,0.9,0.2
R = 0.3,0.6,0.9,0.4
#endpreset

#preset Rolled
FOV = 0.35
Eye = 8.6,3.2,-7.4
Target = 4.6,1.4,-3.6
Up = 0.35,1,0.1
Aperture = 0.08
FocalPlane = 5.8
Detail = -3.8
Scale = 2.2
MinRad2 = 0.3
Angle = 12
OrbitStrength = 0.8
X = 1,0.6,0.2,0.8
Y = 0.4,0.7,1,0.4
#endpreset

#preset KeyFrame.001
FOV = 0.45
Eye = 7.8,5.1,-9.2
Target = 0,0,0
Up = 0,1,0
Scale = 2.5
#endpreset

#preset KeyFrame.002
FOV = 0.4
Eye = 9.6,2.4,-4.8
Target = 0,0.5,0
Up = 0,1,0
Scale = 2.3
#endpreset

#preset KeyFrame.003
FOV = 0.4
Eye = 8.4,4.2,7.4
Target = 0,0,0
Up = 0.1,1,0
Scale = 2.1
#endpreset
