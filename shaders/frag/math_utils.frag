// fathom's MathUtils.frag for Fragmentarium fragments (app/scene/formula/frag.h): the names and contracts
// fragments call, written here from what they must return, not copied. Angles are in degrees.
//
// Fragmentarium's rotation matrices are filled row by row into GLSL's column-major constructor, so
// M * p turns p by −angle about v (M is the transpose of Rodrigues' R): every fragment is tuned to
// that, and these matrices are the same ones. Rodrigues: R = c·I + (1 − c)·v vᵀ + s·[v]×, with [v]×
// the cross-product matrix (R rotates by +angle, right-handed).

// (FLT_MAX, FLT_MIN and PI come with every fragment: app/scene/formula/frag.c's HOST_MACROS)
mat3 rotationMatrix3(vec3 v, float angle)
{
    float c = cos(radians(angle)), s = sin(radians(angle));
    mat3 cross = mat3(0.0, v.z, -v.y, -v.z, 0.0, v.x, v.y, -v.x, 0.0); // columns: [v]× p = v × p
    return transpose(c * mat3(1.0) + (1.0 - c) * outerProduct(v, v) + s * cross);
}

// about x by v.x, then y by v.y, then z by v.z, composed as Fragmentarium composes them
mat3 rotationMatrixXYZ(vec3 v)
{
    return rotationMatrix3(vec3(1.0, 0.0, 0.0), v.x) * rotationMatrix3(vec3(0.0, 1.0, 0.0), v.y) *
           rotationMatrix3(vec3(0.0, 0.0, 1.0), v.z);
}

mat4 rotationMatrix(vec3 v, float angle) { return mat4(rotationMatrix3(v, angle)); }

// homogeneous translation by v (in the fourth column) and uniform scale by s
mat4 translate(vec3 v)
{
    mat4 m = mat4(1.0);
    m[3] = vec4(v, 1.0);
    return m;
}

mat4 scale4(float s) { return mat4(vec4(s, 0.0, 0.0, 0.0), vec4(0.0, s, 0.0, 0.0), vec4(0.0, 0.0, s, 0.0),
                                   vec4(0.0, 0.0, 0.0, 1.0)); }

// Pseudo-random numbers in [0, 1): a 32-bit integer hash of the coordinates' bits (a mix of
// multiplies and xor-shifts, after C. Wellons' "Prospecting for hash functions", 2018), so equal
// inputs give equal outputs on every GPU. Fragments use them for dithering and jitter only.
uint fragHash(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
float rand(float v) { return float(fragHash(floatBitsToUint(v))) / 4294967296.0; }
float rand(vec2 v) { return float(fragHash(fragHash(floatBitsToUint(v.x)) ^ floatBitsToUint(v.y))) / 4294967296.0; }
float rand(vec3 v) { return rand(vec2(rand(v.xy), v.z)); }
vec2 rand2(vec2 v) { return vec2(rand(v), rand(v.yx + 0.5)); }
