// The torus program: one primitive's exact signed distance, the smallest program there is (the
// example of adding one: app/scene/program.h). A torus about the y axis through the origin: the
// distance to the circle of radius uTorusMajor in the xz plane, less the tube's radius uTorusMinor
// (the torus's distance as Inigo Quilez lists it, "distance functions", 2008).
uniform float uTorusMajor, uTorusMinor;
uniform int uTorusMaterial;

vec2 map(vec3 p)
{
    vec2 q = vec2(length(p.xz) - uTorusMajor, p.y);
    return vec2(length(q) - uTorusMinor, float(uTorusMaterial));
}
