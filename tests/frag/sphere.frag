#info A sphere of radius Radius about Centre: fathom's test of Fragmentarium fragments (tests/scene/test_frag.c)
#include "MathUtils.frag"
#include "DE-Raytracer.frag"
#group Sphere
// the sphere's radius
uniform float Radius; slider[0.1,1,3] NotLocked
// where its centre is
uniform vec3 Centre; slider[(-2,-2,-2),(0,0,0),(2,2,2)]
uniform int Iterations; slider[0,4,20]
uniform vec2 Squash; slider[(0,0),(1,1),(2,2)]
uniform vec4 Spare; slider[(0,0,0,0),(0.1,0.2,0.3,0.4),(1,1,1,1)]
uniform bool Hollow; checkbox[false]
uniform vec3 Tint; color[0.9,0.6,0.3]
uniform vec4 Glint; color[0,0.5,2,0.1,0.2,0.3]
uniform float Detailed; slider[0,0.5,1] Locked
uniform float time;

float DE(vec3 p) {
    orbitTrap = min(orbitTrap, abs(vec4(p, dot(p, p))));
    float d = length(p - Centre) - Radius;
    return Hollow ? abs(d) - 0.01 : d;
}

#preset Default
FOV = 0.4
Eye = 0,0,-5
Target = 0,0,0
Up = 0,1,0
Radius = 1.5
FudgeFactor = 0.8
Detail = -3
MaxRaySteps = 300
Specular = 0.4
Reflection = 0.2
#endpreset

#preset Rolled
FOV = 0.5
Eye = 4,0,0
Target = 0,0,0
Up = 0,0.5,1
Aperture = 0.05
FocalPlane = 3.5
Radius = 0.75
Centre = 0,0.5,0
Hollow = true
Glint = 0.4,0.5,0.6,1.5
Spare = 9,0.2,0.3,0.4
Detail = 2
MaxRaySteps = 100000
#endpreset

#preset KeyFrame.001
Eye = 0,0,-6
#endpreset
