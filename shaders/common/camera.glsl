// Primary rays and their per-pixel differentials (for texture filtering). The projections, the thin
// lens and stereo are app/view/camera.h's (its header states them; camera_ray_from is the same in C).
struct Ray {
    vec3 o, d;       // origin, unit direction
    vec3 dDdx, dDdy; // change of the (unnormalized) direction per pixel in x and y
    bool sees;       // false outside a fisheye's circle: the pixel sees nothing
};

const int PROJECTION_PERSPECTIVE = 0, PROJECTION_ORTHOGRAPHIC = 1, PROJECTION_EQUIRECTANGULAR = 2,
          PROJECTION_FISHEYE = 3;
const int STEREO_SIDE_BY_SIDE = 1, STEREO_TOP_BOTTOM = 2;
const float CAMERA_PI = 3.14159265358979;

// A point of the unit disc from a point of the unit square, area-preserving (Shirley & Chiu, "A low
// distortion map between disk and square", JGT 1997).
vec2 concentricDisc(vec2 u)
{
    vec2 a = 2.0 * u - 1.0;
    if (a == vec2(0.0))
        return a;
    bool wide = abs(a.x) > abs(a.y);
    float r = wide ? a.x : a.y, phi = wide ? 0.25 * CAMERA_PI * a.y / a.x : 0.5 * CAMERA_PI - 0.25 * CAMERA_PI * a.x / a.y;
    return r * vec2(cos(phi), sin(phi));
}

// This sample's lens point for this pixel: the sample's Halton point (uLensSample, the same for the
// whole image) shifted by a per-pixel offset (Cranley–Patterson rotation), so neighbours sample the
// lens differently and few samples give noise, not copies of the image.
vec2 lensPoint(vec2 pixel)
{
    uvec2 q = uvec2(pixel);
    uint h = q.x * 1973u + q.y * 9277u + 26699u;
    h = (h ^ (h >> 16)) * 0x7feb352du;
    h = (h ^ (h >> 15)) * 0x846ca68bu;
    vec2 shift = vec2(float(h & 0xffffu), float(h >> 16)) / 65536.0;
    return concentricDisc(fract(uLensSample + shift));
}

Ray primaryRay(vec2 fragCoord)
{
    vec2 pixel = fragCoord + uTileOffset, res = uResolution, at = pixel + uJitter;
    float eye = 0.0; // -1 left, +1 right
    if (uStereo == STEREO_SIDE_BY_SIDE) {
        res.x = floor(res.x * 0.5);
        eye = pixel.x >= res.x ? 1.0 : -1.0;
        at.x -= pixel.x >= res.x ? res.x : 0.0;
    } else if (uStereo == STEREO_TOP_BOTTOM) { // the left eye on top (GL rows count up)
        res.y = floor(res.y * 0.5);
        eye = pixel.y >= res.y ? -1.0 : 1.0;
        at.y -= pixel.y >= res.y ? res.y : 0.0;
    }
    vec2 s = 2.0 * at / res - 1.0;
    float aspect = res.x / res.y;
    Ray r;
    r.sees = true;
    vec3 offset = vec3(0.0);
    if (uProjection == PROJECTION_ORTHOGRAPHIC) {
        r.d = uCamForward;
        offset = (s.x * aspect * uCamRight + s.y * uCamUp) * uFocus * uTanHalfFov;
    } else if (uProjection == PROJECTION_EQUIRECTANGULAR) {
        float lon = CAMERA_PI * s.x, lat = 0.5 * CAMERA_PI * s.y;
        r.d = cos(lat) * (sin(lon) * uCamRight + cos(lon) * uCamForward) + sin(lat) * uCamUp;
        offset = eye * 0.5 * uEyeSeparation * (cos(lon) * uCamRight - sin(lon) * uCamForward); // omnidirectional
        eye = 0.0;
    } else if (uProjection == PROJECTION_FISHEYE) {
        vec2 q = vec2(s.x * aspect, s.y);
        float rad = length(q), th = 0.5 * CAMERA_PI * rad;
        r.sees = rad <= 1.0;
        r.d = cos(th) * uCamForward + (rad > 0.0 ? sin(th) / rad : 0.0) * (q.x * uCamRight + q.y * uCamUp);
    } else {
        r.d = uCamForward + s.x * uTanHalfFov * aspect * uCamRight + s.y * uTanHalfFov * uCamUp;
    }
    r.d = normalize(r.d);
    // the eye's or the lens point's offset in the lens plane; the ray aims at the pinhole ray's point
    // at the focal distance (along forward for perspective, along the ray otherwise)
    vec3 shift = eye * 0.5 * uEyeSeparation * uCamRight;
    if (uLensRadius > 0.0) {
        vec2 l = uLensRadius * lensPoint(pixel);
        shift += l.x * uCamRight + l.y * uCamUp;
    }
    if (shift != vec3(0.0)) {
        float along = uProjection == PROJECTION_PERSPECTIVE ? uFocus / dot(r.d, uCamForward) : uFocus;
        r.d = normalize(r.d * along - shift);
        offset += shift;
    }
    r.o = uCamPos + offset;
    if (uProjection == PROJECTION_PERSPECTIVE || uProjection == PROJECTION_ORTHOGRAPHIC) {
        r.dDdx = uCamRight * uPixelAngle;
        r.dDdy = uCamUp * uPixelAngle;
    } else { // the ray's own horizontal and vertical, a pixel's angle each
        vec3 tx = cross(r.d, uCamUp);
        tx = dot(tx, tx) > 1e-8 ? normalize(tx) : uCamRight;
        r.dDdx = tx * uPixelAngle;
        r.dDdy = cross(tx, r.d) * uPixelAngle;
    }
    return r;
}
