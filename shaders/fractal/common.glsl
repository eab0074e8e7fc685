// Shared by the fractal programs: their parameters, the bounding sphere and orbit-trap colouring.
uniform vec4 uFractalA; // mandelbulb: power, bailout; mandelbox: scale, min radius (in z, w)
uniform vec4 uFractalB; // mandelbox: fixed radius, fold limit; all: bound radius (z); menger: half size (w)
uniform vec3 uPalette[3]; // orbit-trap colours: near, middle, far

// Outside the bounding sphere (which holds the whole set) its distance is a safe, cheap bound;
// the margin keeps the switch to the fractal's estimate away from the set.
const float BOUND_MARGIN = 0.1;

// True (with the bound's distance in d) when p is far enough outside the bounding sphere to use it.
bool outsideBound(vec3 p, out float d)
{
    d = length(p) - uFractalB.z;
    return d > BOUND_MARGIN;
}

vec3 paletteColor(float t)
{
    t = clamp(t, 0.0, 1.0);
    return t < 0.5 ? mix(uPalette[0], uPalette[1], 2.0 * t) : mix(uPalette[1], uPalette[2], 2.0 * t - 1.0);
}

#define PROGRAM_ALBEDO 1
