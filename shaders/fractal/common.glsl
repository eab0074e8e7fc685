// Shared by every fractal formula (app/scene/formula/formula.h has the file format): the precision-neutral
// types, the bounding sphere, orbit-trap colouring, and the pieces several formulas are made of.
//
// Precision. A formula is written once against `real`, `real3`, `real4` and `realMat3`. Normally
// these are float types. For a deep zoom (the hit threshold near a float's resolution: formulas that
// declare @deep) the program is compiled with PRECISION_DOUBLE and they are doubles: the whole
// shader then works in coordinates relative to the eye, and worldOf() adds the eye's double
// position uOrigin back before the formula iterates. GLSL's doubles have +, −, ×, ÷, sqrt, abs,
// min, max, clamp, floor, dot and length, but no pow, exp, log or trigonometry: a @deep formula uses
// only those, or the helpers below that work in both precisions (realLog, bulbPower).
#ifdef PRECISION_DOUBLE
#define real double
#define real3 dvec3
#define real4 dvec4
#define realMat3 dmat3
uniform dvec3 uOrigin; // the eye, in world coordinates (app/gpu/render.c)
real3 worldOf(vec3 p) { return uOrigin + real3(p); }
#else
#define real float
#define real3 vec3
#define real4 vec4
#define realMat3 mat3
real3 worldOf(vec3 p) { return p; }
#endif

#include "common/uniforms.glsl" // the eye and the pixel's angle: the bound's margin
uniform float uBoundRadius; // a sphere about the origin that holds the whole set
uniform int uFormulaLoops;  // loop iterations one estimate runs: the formula's @loops (common/budget.glsl)
uniform int uFormulaStepLoops; // of them, those of one step of a step formula (1: its loop's own)
uniform vec3 uPalette[3];   // orbit-trap colours: near, middle, far
uniform vec2 uTrapRange;    // the formula's @trap: the orbit trap's values spread over the palette
uniform float uHitRelative; // 10^fractal.detail: Fragmentarium's hit rule (common/march.glsl, HIT_RELATIVE)
uniform float uFragMaxDistance; // fractal.max_distance: rays past it are background under that rule

// A zoom goes as deep as positions resolve (common/march.glsl's positionFloor), not to a fixed
// threshold in metres: the fractal has detail at every scale.
#define HIT_EPS_MIN 0.0

// Ambient occlusion looks as far as the scale of the view: half the distance from the eye, at most
// the usual 0.6 m (common/ao.glsl); a deep zoom's creases are 1e-12 wide.
#define AO_RADIUS_AT(t) min(0.6, 0.5 * (t))

// The footprint rule defines a fractal's surface at a level of detail (a ray within HIT_K pixel
// footprints of the set has hit it): the marcher does not refine these hits (common/march.glsl).
#define PROGRAM_FOOTPRINT_SURFACE 1

// Outside the bounding sphere (which holds the whole set) its distance is a safe, cheap bound. It is
// returned with MATERIAL_BOUND: rays step by it but never stop on it, at any hit threshold. The
// surface drawn is the set grown by the hit threshold (the footprint rule), so the switch to the
// formula's estimate waits until a point is within a few thresholds of the sphere: where the set
// touches it (the Mandelbox's corners lie on it) a fixed margin smaller than a far camera's threshold
// clipped the corners (IoU 0.9957 against Mandelbulber2 from afar). The margin is four primary-ray
// thresholds at the point's distance from the eye, never less than 0.1: the estimate runs below the
// distance near the corners, and two thresholds still clipped 53 of 1757 pixels from 45 m
// (test_fractal far_corners_are_kept). In the band between 0.1 and that margin the step is the
// estimate's, labelled a bound while it is above the threshold: the glow (sdf_main.glsl) counts no
// steps there, or it drew a ring around the sphere.
const float BOUND_MARGIN = 0.1, BOUND_MARGIN_THRESHOLDS = 4.0;

// The largest singular value of J (its operator norm: how far it can stretch a step): the square root of
// the largest eigenvalue of JᵀJ, by the closed form for a symmetric 3×3 (O. K. Smith 1961, "Eigenvalues
// of a symmetric 3 × 3 matrix"). For a step formula's running derivative (dr ← ‖J‖ dr).
float largestSingular(mat3 J)
{
    mat3 M = transpose(J) * J;
    float q = (M[0][0] + M[1][1] + M[2][2]) / 3.0;
    float off = M[0][1] * M[0][1] + M[0][2] * M[0][2] + M[1][2] * M[1][2];
    float p = sqrt(((M[0][0] - q) * (M[0][0] - q) + (M[1][1] - q) * (M[1][1] - q) + (M[2][2] - q) * (M[2][2] - q) + 2.0 * off) / 6.0);
    if (p <= 1e-7 * q) // a multiple of the identity (to rounding): all three eigenvalues are q
        return sqrt(max(q, 0.0));
    float r = clamp(0.5 * determinant((M - mat3(q)) / p), -1.0, 1.0);
    return sqrt(max(q + 2.0 * p * cos(acos(r) / 3.0), 0.0));
}

// The primary ray's hit threshold at p (shader space, where the eye is uCamPos): common/march.glsl.
float boundThreshold(vec3 p) { return float(HIT_K) * footprintAt(length(p - uCamPos)); }

vec3 paletteColor(float t)
{
    t = clamp(t, 0.0, 1.0);
    return t < 0.5 ? mix(uPalette[0], uPalette[1], 2.0 * t) : mix(uPalette[1], uPalette[2], 2.0 * t - 1.0);
}

// A rotation by a.x about x, then a.y about y, then a.z about z (radians): the per-iteration twist of
// the kaleidoscopic formulas. A rotation keeps lengths, so it changes no running derivative.
mat3 twistMatrix(vec3 a)
{
    float cx = cos(a.x), sx = sin(a.x), cy = cos(a.y), sy = sin(a.y), cz = cos(a.z), sz = sin(a.z);
    return mat3(1, 0, 0, 0, cx, sx, 0, -sx, cx) * mat3(cy, 0, -sy, 0, 1, 0, sy, 0, cy) * mat3(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
}

// ln x in either precision. The estimates only need the logarithm to a float's relative accuracy
// (they are bounds scaled by a step factor), while their arguments need a double's digits.
real realLog(real x) { return real(log(float(x))); }

// The Mandelbulb's "triplex" power (D. White and P. Nylander, 2009): z = r (sin θ cos φ, cos θ,
// sin θ sin φ) with θ from +Y and φ around it goes to rⁿ (sin nθ cos nφ, cos nθ, sin nθ sin nφ).
// Returns rⁿ⁻¹ (for the running derivative n rⁿ⁻¹). At r → 0 and on the axis, acos and atan are
// 0/0 and undefined: each falls back to its limit (tests/fractal/test_fractal.c fails without the guards).
// In double precision (no trigonometry) and for a whole n it is exact algebra: (cos θ + i sin θ)ⁿ
// and ((x + i z) / ρ)ⁿ by repeated complex products, ρ = √(x² + z²).
#ifndef BULB_GUARDS // tests compile them out (0) to show what each prevents
#define BULB_GUARDS 1
#endif
const float BULB_TINY = BULB_GUARDS != 0 ? 1e-30 : -1.0;

#ifdef PRECISION_DOUBLE
dvec2 complexPowD(dvec2 a, int n)
{
    dvec2 r = dvec2(1.0, 0.0);
    for (int i = 0; i < n; i++)
        r = dvec2(r.x * a.x - r.y * a.y, r.x * a.y + r.y * a.x);
    return r;
}

real bulbPower(inout real3 z, float power)
{
    int n = int(power + 0.5); // @deep formulas ask for a whole power (formula.h: @deep whole)
    real r = length(z), rho = length(z.xz);
    dvec2 theta = BULB_GUARDS == 0 || r > 0.0 ? complexPowD(dvec2(z.y, rho) / r, n) : dvec2(1.0, 0.0);
    dvec2 phi = BULB_GUARDS == 0 || rho > 0.0 ? complexPowD(z.xz / rho, n) : dvec2(1.0, 0.0);
    real rn1 = 1.0;
    for (int i = 1; i < n; i++)
        rn1 *= r;
    z = rn1 * r * real3(theta.y * phi.x, theta.x, theta.y * phi.y);
    return rn1;
}
#else
real bulbPower(inout real3 z, float power)
{
    float r = length(z);
    float theta = r > BULB_TINY ? acos(clamp(z.y / r, -1.0, 1.0)) : 0.0;
    float phi = (BULB_GUARDS == 0 || z.x != 0.0 || z.z != 0.0) ? atan(z.z, z.x) : 0.0;
    float rn1 = r > BULB_TINY ? pow(r, power - 1.0) : 0.0;
    theta *= power;
    phi *= power;
    z = rn1 * r * vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
    return rn1;
}
#endif

// The Mandelbox's folds (T. Lowe, 2010): the box fold reflects each coordinate beyond ±limit back
// inside; the sphere fold inverts in the sphere of radius fixedR, and scales by (fixedR / minR)²
// within minR. Returns the sphere fold's factor (the running derivative's).
real sphereFold(inout real3 z, float minR, float fixedR)
{
    real r2 = dot(z, z), minR2 = real(minR * minR), fixedR2 = real(fixedR * fixedR);
    real k = r2 < minR2 ? fixedR2 / minR2 : (r2 < fixedR2 ? fixedR2 / r2 : real(1.0));
    z *= k;
    return k;
}

real3 boxFold(real3 z, float limit) { return clamp(z, -real(limit), real(limit)) * 2.0 - z; }

// The exact distance to the cube of half-side h about the origin (common/sdf.glsl's sdBox, in either
// precision): the Menger sponge's cells, and the cube an infinite set is cut to (the maximum of two
// distance bounds is a bound of the intersection).
real realBox(real3 p, real h)
{
    real3 q = abs(p) - h;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// The folds of the kaleidoscopic formulas: into the wedge x ≥ y ≥ z ≥ 0 of the cube's 48 mirror
// images (the octahedral group), and across the tetrahedron's three mirror planes x + y, x + z, y + z.
real3 foldOctahedral(real3 z)
{
    z = abs(z);
    if (z.x < z.y) z.xy = z.yx;
    if (z.x < z.z) z.xz = z.zx;
    if (z.y < z.z) z.yz = z.zy;
    return z;
}

real3 foldTetrahedral(real3 z)
{
    if (z.x + z.y < 0.0) z.xy = -z.yx;
    if (z.x + z.z < 0.0) z.xz = -z.zx;
    if (z.y + z.z < 0.0) z.yz = -z.zy;
    return z;
}
