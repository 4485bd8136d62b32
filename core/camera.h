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

    class RayGenerator;
    /// Primary ray through film position (filmX, filmY) in pixels of a width x height film,
    /// through lens sample `lens` in [0,1)^2 (ignored for a pinhole). Direction is unit length.
    Ray generateRay(float filmX, float filmY, int width, int height, Vec2 lens) const;

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

/// generateRay for many rays of one width x height film: the film's constants (the field of
/// view's tangent among them) computed once; the same rays bit for bit.
class Camera::RayGenerator {
public:
    RayGenerator(const Camera& camera, int width, int height)
        : m_camera(camera),
          m_width(float(width)),
          m_height(float(height)),
          m_aspect(float(width) / float(height)),
          m_tanHalf(std::tan(0.5f * camera.yFov)) {}

    Ray operator()(float filmX, float filmY, Vec2 lens) const {
        const Camera& c = m_camera;
        float ndcX = 2.0f * filmX / m_width - 1.0f;
        float ndcY = 1.0f - 2.0f * filmY / m_height;
        Vec3 d = c.forward + c.right * (ndcX * m_tanHalf * m_aspect) + c.up * (ndcY * m_tanHalf);
        Ray ray;
        if (c.lensRadius <= 0.0f) {
            ray.o = c.position;
            ray.d = normalize(d);
            return ray;
        }
        Vec3 focus = c.position + d * c.focusDistance;  // d has unit component along forward
        Vec2 disk = sampleConcentricDisk(lens.x, lens.y);
        ray.o = c.position + c.right * (disk.x * c.lensRadius) + c.up * (disk.y * c.lensRadius);
        ray.d = normalize(focus - ray.o);
        return ray;
    }

private:
    const Camera& m_camera;
    float m_width, m_height, m_aspect, m_tanHalf;
};

inline Ray Camera::generateRay(float filmX, float filmY, int width, int height, Vec2 lens) const {
    return RayGenerator(*this, width, height)(filmX, filmY, lens);
}

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
