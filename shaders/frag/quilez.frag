// fathom's QuilezLib.frag for Fragmentarium fragments (app/scene/formula/frag.h): the distance functions of
// I. Quilez's article "Distance functions" (iquilezles.org/articles/distfunctions), by the names and
// contracts Fragmentarium's library gives them (ud: unsigned, sd: signed), written here from the
// formulas.

float maxcomp(vec3 a) { return max(a.x, max(a.y, a.z)); }
float sdSphere(vec3 p, float s) { return length(p) - s; }
float udBox(vec3 p, vec3 b) { return length(max(abs(p) - b, 0.0)); }
float udRoundBox(vec3 p, vec3 b, float r) { return udBox(p, b) - r; }
// exact inside and out: the largest axis excess inside (negative), the corner distance outside
float sdToBox(vec3 p, vec3 b)
{
    vec3 d = abs(p) - b;
    return min(maxcomp(d), length(max(d, 0.0)));
}
// a torus about y: major radius t.x, minor t.y
float sdTorus(vec3 p, vec2 t) { return length(vec2(length(p.xz) - t.x, p.y)) - t.y; }
// an infinite cylinder along y through (c.x, ?, c.y) of radius c.z
float sdCylinder(vec3 p, vec3 c) { return length(p.xz - c.xy) - c.z; }
// a cone about z with its apex at the origin; c = (cos, sin) of the half angle, normalised
float sdCone(vec3 p, vec2 c) { return dot(c, vec2(length(p.xy), p.z)); }
// the plane n.xyz · p + n.w = 0 (n.xyz unit)
float sdPlane(vec3 p, vec4 n) { return dot(p, n.xyz) + n.w; }
// a hexagonal prism along z: h.x the apothem's bound, h.y the half length (the library's variant)
float udHexPrism(vec3 p, vec2 h)
{
    vec3 q = abs(p);
    return max(q.z - h.y, max(q.x + 0.57735 * q.y, q.y) - h.x);
}
float opU(float d1, float d2) { return min(d1, d2); }
float opS(float d1, float d2) { return max(-d1, d2); } // d2 with d1 cut away
float opI(float d1, float d2) { return max(d1, d2); }
// the L8 and L4 norms of p: rounded squares
float length8(vec2 p)
{
    p *= p;
    p *= p;
    return pow(dot(p, p), 1.0 / 8.0);
}
float length4(vec2 p)
{
    p *= p;
    return pow(dot(p, p), 1.0 / 4.0);
}
float sdTorus88(vec3 p, vec2 t) { return length8(vec2(length8(p.xz) - t.x, p.y)) - t.y; }
