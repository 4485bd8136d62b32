#pragma once
// Pinhole and thin-lens cameras. Film coordinates are in pixels: (0,0) is the top-left corner of
// the image, (width, height) the bottom-right; a pass jitters the film position inside each
// pixel and the lens position over the aperture, so anti-aliasing and depth of field come from
// averaging passes.
#include "core/math.h"
#include "core/sampling.h"

namespace tyndall {

struct Camera {
    Vec3 position{0, 0, 0};
    Vec3 forward{0, 0, -1};  ///< unit view direction
    Vec3 up{0, 1, 0};        ///< unit, orthogonal to forward
    Vec3 right{1, 0, 0};     ///< unit, forward x up
    float yFov = 0.7f;       ///< full vertical field of view, radians
    float lensRadius = 0.0f; ///< 0 = pinhole; scene units
    float focusDistance = 1.0f; ///< distance along `forward` to the plane in focus

    /// Points the camera at `target`; `worldUp` need not be orthogonal to the view direction.
    static Camera lookAt(const Vec3& eye, const Vec3& target, const Vec3& worldUp, float yFovRadians);

    /// Primary ray through film position (filmX, filmY) in pixels of a width x height film,
    /// through lens sample `lens` in [0,1)^2 (ignored for a pinhole). Direction is unit length.
    Ray generateRay(float filmX, float filmY, int width, int height, Vec2 lens) const {
        float aspect = float(width) / float(height);
        float tanHalf = std::tan(0.5f * yFov);
        float ndcX = 2.0f * filmX / float(width) - 1.0f;
        float ndcY = 1.0f - 2.0f * filmY / float(height);
        Vec3 d = forward + right * (ndcX * tanHalf * aspect) + up * (ndcY * tanHalf);
        Ray ray;
        if (lensRadius <= 0.0f) {
            ray.o = position;
            ray.d = normalize(d);
            return ray;
        }
        Vec3 focus = position + d * focusDistance;  // d has unit component along forward
        Vec2 disk = sampleConcentricDisk(lens.x, lens.y);
        ray.o = position + right * (disk.x * lensRadius) + up * (disk.y * lensRadius);
        ray.d = normalize(focus - ray.o);
        return ray;
    }

    /// Film position (pixels) where the pinhole projection of `p` lands; false when `p` is not in
    /// front of the camera (depth <= 0). Used by the beam rasterizers for bounding.
    bool project(const Vec3& p, int width, int height, float* filmX, float* filmY, float* depth) const {
        Vec3 v = p - position;
        float z = dot(v, forward);
        *depth = z;
        if (z <= 0.0f) return false;
        float aspect = float(width) / float(height);
        float tanHalf = std::tan(0.5f * yFov);
        float ndcX = dot(v, right) / (z * tanHalf * aspect);
        float ndcY = dot(v, up) / (z * tanHalf);
        *filmX = 0.5f * (ndcX + 1.0f) * float(width);
        *filmY = 0.5f * (1.0f - ndcY) * float(height);
        return true;
    }
};

inline Camera Camera::lookAt(const Vec3& eye, const Vec3& target, const Vec3& worldUp, float yFovRadians) {
    Camera c;
    c.position = eye;
    c.forward = normalize(target - eye);
    c.right = normalize(cross(c.forward, worldUp));
    c.up = cross(c.right, c.forward);
    c.yFov = yFovRadians;
    c.focusDistance = length(target - eye);
    return c;
}

}  // namespace tyndall
