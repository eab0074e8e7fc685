// Signed distance primitives and CSG operators.
// Conventions: every sd* returns the exact Euclidean distance to its surface (negative inside);
// primitives sit at the origin with Y as their axis, and callers move p into their frame. Sizes are
// half-extents. Operators take and return vec2(distance, material index). Formulas: I. Quilez,
// "distance functions" (iquilezles.org); smooth minimum: Quilez, "smooth minimum" (polynomial).

float sdSphere(vec3 p, float r) { return length(p) - r; }

float sdBox(vec3 p, vec3 halfSize)
{
    vec3 q = abs(p) - halfSize;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float sdRoundBox(vec3 p, vec3 halfSize, float radius) { return sdBox(p, halfSize - radius) - radius; }

// Ring in the XZ plane: major radius to the tube's centre, minor radius of the tube.
float sdTorus(vec3 p, float major, float minor)
{
    vec2 q = vec2(length(p.xz) - major, p.y);
    return length(q) - minor;
}

float sdCylinder(vec3 p, float halfHeight, float radius)
{
    vec2 d = abs(vec2(length(p.xz), p.y)) - vec2(radius, halfHeight);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}

float sdCapsule(vec3 p, float halfHeight, float radius)
{
    p.y -= clamp(p.y, -halfHeight, halfHeight);
    return length(p) - radius;
}

float distToSegment2(vec2 p, vec2 a, vec2 b)
{
    vec2 ab = b - a;
    float h = clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    return length(p - a - ab * h);
}

// Cone frustum: radius rBottom at y = -halfHeight, rTop at +halfHeight. In the (radial, y) plane its
// section is a trapezoid; the distance is the nearest of its three outer edges, signed by an inside test.
float sdCappedCone(vec3 p, float halfHeight, float rBottom, float rTop)
{
    vec2 q = vec2(length(p.xz), p.y);
    vec2 b0 = vec2(0.0, -halfHeight), b1 = vec2(rBottom, -halfHeight);
    vec2 t0 = vec2(0.0, halfHeight), t1 = vec2(rTop, halfHeight);
    float d = min(min(distToSegment2(q, b0, b1), distToSegment2(q, t0, t1)), distToSegment2(q, b1, t1));
    float rAtY = mix(rBottom, rTop, (q.y + halfHeight) / (2.0 * halfHeight));
    bool inside = abs(q.y) < halfHeight && q.x < rAtY;
    return inside ? -d : d;
}

// Half-space below the plane through the origin with unit normal n.
float sdPlane(vec3 p, vec3 n) { return dot(p, n); }

vec2 opUnion(vec2 a, vec2 b) { return a.x < b.x ? a : b; }
vec2 opIntersection(vec2 a, vec2 b) { return a.x > b.x ? a : b; }
vec2 opDifference(vec2 a, vec2 b) { return a.x > -b.x ? a : vec2(-b.x, b.y); }

// Blend radius k: the result differs from the sharp operator by at most k/4, and only where the two
// distances are within k of each other. The surface keeps the nearer part's material.
vec2 opSmoothUnion(vec2 a, vec2 b, float k)
{
    float h = max(k - abs(a.x - b.x), 0.0) / k;
    return vec2(min(a.x, b.x) - h * h * k * 0.25, a.x < b.x ? a.y : b.y);
}

vec2 opSmoothIntersection(vec2 a, vec2 b, float k)
{
    float h = max(k - abs(a.x - b.x), 0.0) / k;
    return vec2(max(a.x, b.x) + h * h * k * 0.25, a.x > b.x ? a.y : b.y);
}

vec2 opSmoothDifference(vec2 a, vec2 b, float k) { return opSmoothIntersection(a, vec2(-b.x, b.y), k); }
