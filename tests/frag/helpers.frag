#donotrun
// a helper the fragment includes from its own folder (tests/frag/rotated.frag)
vec3 turned(vec3 p) { return rotationMatrix3(vec3(0.0, 0.0, 1.0), 90.0) * p; }
