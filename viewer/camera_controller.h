#pragma once
// The viewer's camera and light manipulation, free of any window system so it is unit-tested
// (tests/viewer/camera_controller_test.cpp). Input arrives as motion in window pixels.
//
// The camera is an eye, a unit view direction and a world up, turned into a Camera by
// Camera::lookAt (the same call the view file's edits use: loading/scene_edits.h). A pivot is the
// point orbit turns about and dolly moves toward:
//   orbit(dx, dy)  turns eye and view direction about the pivot: yaw about the world up, pitch
//                  about the camera's right (stopping short of the poles); the eye keeps its
//                  distance to the pivot;
//   pan(dx, dy)    moves eye and pivot in the view plane so that the point at the pivot's depth
//                  follows the cursor; the view direction is unchanged;
//   dolly(steps)   moves the eye toward the pivot (steps > 0) or away, a fixed fraction per step;
//                  it slows down and stops at minDistance from the pivot, never passing it;
//   frame(bounds)  looks at the bounds' centre from the current direction, from far enough to see
//                  their bounding sphere.
// Picking: ray(x, y) is the pinhole ray through window pixel (x, y); the caller intersects it
// with the scene (EmbreeScene on the viewer's UI thread) and calls setPivot with the hit.
#include "core/camera.h"
#include "core/light.h"
#include "core/math.h"

namespace tyndall {

class CameraController {
public:
    CameraController() = default;
    /// Takes the camera's eye, direction, field of view and lens; the pivot goes `pivotDistance`
    /// along the view direction (the focus distance is a good choice).
    CameraController(const Camera& camera, float pivotDistance);

    /// The viewport the pixel motions refer to (window pixels of the image area).
    void setViewport(int width, int height);

    void orbit(float dxPixels, float dyPixels);
    void pan(float dxPixels, float dyPixels);
    void dolly(float steps);
    void frame(const Bounds3& bounds);
    /// Sets the pivot (and the focus distance of a thin-lens camera) to `point`.
    void setPivot(const Vec3& point);

    /// The pinhole ray through window pixel (x, y) (origin at the eye, unit direction).
    Ray ray(float x, float y) const;
    /// The camera as rendered.
    Camera camera() const;

    const Vec3& eye() const { return m_eye; }
    const Vec3& forward() const { return m_forward; }
    const Vec3& pivot() const { return m_pivot; }
    float distanceToPivot() const { return length(m_pivot - m_eye); }
    /// Dolly never comes closer to the pivot than this (default 1e-3 x the initial distance).
    float minDistance() const { return m_minDistance; }
    void setMinDistance(float d) { m_minDistance = d; }
    /// World-space size of one viewport pixel at distance `depth` along the view direction.
    float pixelSize(float depth) const;

private:
    Vec3 m_eye{0, 0, 0};
    Vec3 m_forward{0, 0, -1};
    Vec3 m_worldUp{0, 1, 0};
    Vec3 m_pivot{0, 0, -1};
    float m_yFov = 0.7f;
    float m_lensRadius = 0;
    float m_focusDistance = 1;
    float m_minDistance = 1e-3f;
    int m_width = 512, m_height = 512;
};

/// Moves `light` for a drag of the cursor to window pixel (x, y) by (dx, dy) pixels, seen through
/// `view`: a point light moves in the view plane through it (so it follows the cursor); a spot
/// re-aims at `target` (the surface point under the cursor, or when nothing is hit the point on
/// the cursor's ray at the spot's current distance to the pivot); a directional light turns to
/// travel along the cursor's ray.
void dragLight(Light& light, const CameraController& view, float x, float y, float dx, float dy,
               const Vec3* surfaceUnderCursor);

}  // namespace tyndall
