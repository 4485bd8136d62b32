#include "viewer/camera_controller.h"

#include <cmath>

namespace tyndall {

namespace {
/// v rotated by `angle` radians about the unit `axis` (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& axis, float angle) {
    float c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}
}  // namespace

CameraController::CameraController(const Camera& camera, float pivotDistance)
    : m_eye(camera.position),
      m_forward(camera.forward),
      m_worldUp(camera.up),
      m_yFov(camera.yFov),
      m_lensRadius(camera.lensRadius),
      m_focusDistance(camera.focusDistance) {
    // Keep the scene's up when it is a plain +y world; a tilted camera keeps its own up.
    if (length(cross(m_forward, Vec3(0, 1, 0))) > 1e-3f) m_worldUp = Vec3(0, 1, 0);
    pivotDistance = pivotDistance > 0 && std::isfinite(pivotDistance) ? pivotDistance : 1.0f;
    m_pivot = m_eye + m_forward * pivotDistance;
    m_minDistance = 1e-3f * pivotDistance;
}

void CameraController::setViewport(int width, int height) {
    m_width = std::max(width, 1);
    m_height = std::max(height, 1);
}

float CameraController::pixelSize(float depth) const {
    return 2.0f * depth * std::tan(0.5f * m_yFov) / float(m_height);
}

void CameraController::orbit(float dx, float dy) {
    const float radiansPerPixel = kPi / float(m_height);
    Vec3 offset = m_eye - m_pivot;
    float yaw = -dx * radiansPerPixel, pitch = -dy * radiansPerPixel;
    // Pitch stops 1 degree short of the poles (lookAt needs forward not parallel to up).
    float elevation = std::asin(std::clamp(dot(m_forward, m_worldUp), -1.0f, 1.0f));
    const float limit = 0.5f * kPi - 0.0175f;
    pitch = std::clamp(elevation + pitch, -limit, limit) - elevation;
    Vec3 right = normalize(cross(m_forward, m_worldUp));
    offset = rotate(offset, right, pitch);
    Vec3 forward = rotate(m_forward, right, pitch);
    offset = rotate(offset, m_worldUp, yaw);
    forward = rotate(forward, m_worldUp, yaw);
    m_forward = normalize(forward);
    m_eye = m_pivot + offset;
}

void CameraController::pan(float dx, float dy) {
    Camera c = camera();
    float depth = std::max(dot(m_pivot - m_eye, m_forward), m_minDistance);
    float s = pixelSize(depth);
    Vec3 move = c.right * (-dx * s) + c.up * (dy * s);
    m_eye = m_eye + move;
    m_pivot = m_pivot + move;
}

void CameraController::dolly(float steps) {
    Vec3 toPivot = m_pivot - m_eye;
    float d = length(toPivot);
    if (!(d > 0)) return;
    // Each step covers 15% of what is left to the pivot: approaching it ever slower, never passing.
    float target = std::max(d * std::pow(0.85f, steps), m_minDistance);
    m_eye = m_pivot - toPivot * (target / d);
}

void CameraController::frame(const Bounds3& bounds) {
    if (bounds.empty()) return;
    Vec3 center = bounds.center();
    float radius = 0.5f * length(bounds.diagonal());
    float aspect = float(m_width) / float(m_height);
    float halfFov = 0.5f * m_yFov;
    float halfFovX = std::atan(std::tan(halfFov) * aspect);
    float d = radius / std::sin(std::min(halfFov, halfFovX));
    m_pivot = center;
    m_eye = center - m_forward * d;
    m_minDistance = 1e-3f * d;
}

void CameraController::setPivot(const Vec3& point) {
    m_pivot = point;
    float depth = dot(point - m_eye, m_forward);
    if (depth > 0) m_focusDistance = depth;
}

Ray CameraController::ray(float x, float y) const {
    Camera c = camera();
    c.lensRadius = 0;
    return c.generateRay(x, y, m_width, m_height, Vec2{0.5f, 0.5f});
}

Camera CameraController::camera() const {
    Camera c = Camera::lookAt(m_eye, m_eye + m_forward, m_worldUp, m_yFov);
    c.lensRadius = m_lensRadius;
    c.focusDistance = m_focusDistance;
    return c;
}

void dragLight(Light& light, const CameraController& view, float x, float y, float dx, float dy,
               const Vec3* surfaceUnderCursor) {
    Ray r = view.ray(x, y);
    Camera c = view.camera();
    switch (light.type) {
        case LightType::Point: {
            float depth = std::max(dot(light.position - c.position, c.forward), view.minDistance());
            float s = view.pixelSize(depth);
            light.position = light.position + c.right * (dx * s) - c.up * (dy * s);
            break;
        }
        case LightType::Spot: {
            Vec3 target = surfaceUnderCursor ? *surfaceUnderCursor
                                             : r.o + r.d * length(view.pivot() - light.position);
            Vec3 d = target - light.position;
            if (length(d) > 0) light.direction = normalize(d);
            break;
        }
        case LightType::Directional:
            light.direction = r.d;
            break;
    }
}

}  // namespace tyndall
