// What a ray march returns (common/march.glsl, or a program's own castRay).
struct Hit {
    bool hit;
    float t;   // distance along the ray from its origin
    float mat; // material index
    int steps;
};
