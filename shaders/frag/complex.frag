// fathom's Complex.frag for Fragmentarium fragments (app/scene/formula/frag.h): complex numbers as vec2
// (x the real part, y the imaginary), the names fragments call, from the textbook identities.

vec2 cMul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 cSqr(vec2 z) { return vec2(z.x * z.x - z.y * z.y, 2.0 * z.x * z.y); }
vec2 cInverse(vec2 a) { return vec2(a.x, -a.y) / dot(a, a); }
vec2 cDiv(vec2 a, vec2 b) { return cMul(a, cInverse(b)); }
vec2 cExp(vec2 z) { return exp(z.x) * vec2(cos(z.y), sin(z.y)); }
vec2 cLog(vec2 a) { return vec2(log(length(a)), atan(a.y, a.x)); }
// z^n = |z|^n e^(i n arg z)
vec2 cPower(vec2 z, float n)
{
    float r = pow(length(z), n), a = n * atan(z.y, z.x);
    return r * vec2(cos(a), sin(a));
}
// z^a for a complex exponent: e^(a log z)
vec2 cPower2(vec2 z, vec2 a) { return cExp(cMul(a, cLog(z))); }
vec2 cSin(vec2 z) { return vec2(sin(z.x) * cosh(z.y), cos(z.x) * sinh(z.y)); }
vec2 cCos(vec2 z) { return vec2(cos(z.x) * cosh(z.y), -sin(z.x) * sinh(z.y)); }
