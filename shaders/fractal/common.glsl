// Shared by the fractal programs: their parameters, the bounding sphere and orbit-trap colouring.
// Each formula declares its own parameters as annotated uniforms (app/scene/formula.h); one that
// colours its surface defines PROGRAM_ALBEDO and programAlbedo() (common/contract.glsl).
uniform float uBoundRadius; // a sphere about the origin that holds the whole set
uniform vec3 uPalette[3]; // orbit-trap colours: near, middle, far

// The footprint rule defines a fractal's surface at a level of detail (a ray within HIT_K pixel
// footprints of the set has hit it): the marcher does not refine these hits (common/march.glsl).
#define PROGRAM_FOOTPRINT_SURFACE 1

// Outside the bounding sphere (which holds the whole set) its distance is a safe, cheap bound. It is
// returned with MATERIAL_BOUND: rays step by it but never stop on it, at any hit threshold (a far
// camera's threshold can exceed any fixed margin). The margin keeps the switch to the fractal's
// estimate away from the set.
const float BOUND_MARGIN = 0.1;

// True (with the bound's distance in d) when p is far enough outside the bounding sphere to use it.
bool outsideBound(vec3 p, out float d)
{
    d = length(p) - uBoundRadius;
    return d > BOUND_MARGIN;
}

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
