// Primary rays and their per-pixel differentials (for texture filtering).
struct Ray {
    vec3 o, d;       // origin, unit direction
    vec3 dDdx, dDdy; // change of the (unnormalized) direction per pixel in x and y
};

Ray primaryRay(vec2 fragCoord)
{
    vec2 s = (2.0 * (fragCoord + uTileOffset + uJitter) / uResolution - 1.0) * uTanHalfFov;
    s.x *= uResolution.x / uResolution.y;
    Ray r;
    r.o = uCamPos;
    r.d = normalize(uCamForward + s.x * uCamRight + s.y * uCamUp);
    r.dDdx = uCamRight * uPixelAngle;
    r.dDdy = uCamUp * uPixelAngle;
    return r;
}
