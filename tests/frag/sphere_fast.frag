#info A sphere of radius 1.5 on Fast-Raytracer: fathom's test of that renderer's look, Phong's highlight and the light toward -SpotLightDir (tests/fractal/test_frag_rule.c)
#include "Fast-Raytracer.frag"
float DE(vec3 p) { return length(p) - 1.5; }

#preset Default
FOV = 0.4
Eye = 0,0,-5
Target = 0,0,0
Up = 0,1,0
FudgeFactor = 0.8
Detail = -3
MaxRaySteps = 300
#endpreset
