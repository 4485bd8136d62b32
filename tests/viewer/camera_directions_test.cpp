// The viewer's camera and light drags where the other controller tests cannot tell a sign apart
// (a half turn looks the same either way) or never go: the direction of a small orbit, frame()
// keeping the view direction and fitting the bounding sphere snugly, and dragging a directional
// light or a spot over empty space.
#include <gtest/gtest.h>

#include <cmath>

#include "viewer/camera_controller.h"

namespace tyndall {
namespace {

CameraController makeController() {
    Camera c = Camera::lookAt(Vec3(0, 1, 5), Vec3(0, 1, 0), Vec3(0, 1, 0), 0.7f);
    CameraController ctl(c, 5.0f);
    ctl.setViewport(400, 300);
    return ctl;
}

/// Window x, y of `p` (y down).
Vec2 screen(const CameraController& ctl, const Vec3& p) {
    float fx = 0, fy = 0, depth = 0;
    EXPECT_TRUE(ctl.camera().project(p, 400, 300, &fx, &fy, &depth));
    return {fx, fy};
}

TEST(CameraDirections, ASmallOrbitTurnsTheSceneWithTheCursor) {
    // A point between the eye and the pivot: dragging right moves it right on screen (the eye
    // goes left around the pivot), dragging down moves it down (the eye goes up).
    const Vec3 near(0, 1, 2.5f);
    CameraController right = makeController();
    const Vec2 before = screen(right, near);
    right.orbit(20.0f, 0.0f);
    const Vec2 afterRight = screen(right, near);
    EXPECT_GT(afterRight.x, before.x + 5.0f) << "drag right: the scene turns right";
    EXPECT_NEAR(afterRight.y, before.y, 0.5f);
    EXPECT_LT(right.eye().x, -0.1f) << "the eye orbits to the left";
    // The yaw is pi per viewport height: 20 / 300 of pi.
    const float yaw = std::atan2(-right.eye().x, right.eye().z);
    EXPECT_NEAR(yaw, kPi * 20.0f / 300.0f, 1e-4f);

    CameraController down = makeController();
    down.orbit(0.0f, 20.0f);
    const Vec2 afterDown = screen(down, near);
    EXPECT_GT(afterDown.y, before.y + 5.0f) << "drag down: the scene tilts down";
    EXPECT_NEAR(afterDown.x, before.x, 0.5f);
    EXPECT_GT(down.eye().y, 1.1f) << "the eye rises above the pivot";
    EXPECT_LT(down.camera().forward.y, -0.1f) << "and looks down at it";
}

TEST(CameraDirections, FrameKeepsTheViewDirectionAndFitsTheBoundingSphere) {
    for (float dx : {0.0f, 70.0f}) {
        CameraController ctl = makeController();
        ctl.orbit(dx, -30.0f);  // some direction other than the start's
        const Vec3 forward = ctl.forward();
        Bounds3 b;
        b.extend(Vec3(10, 0, -3));
        b.extend(Vec3(14, 2, 1));
        ctl.frame(b);
        EXPECT_NEAR(dot(ctl.forward(), forward), 1.0f, 1e-6f) << "frame() looks from the current direction";
        const Vec3 c = b.center();
        EXPECT_NEAR(length(ctl.pivot() - c), 0.0f, 1e-5f);
        EXPECT_GT(dot(normalize(c - ctl.eye()), ctl.camera().forward), 0.99999f) << "the centre in the middle";
        // The bounding sphere's angular radius against the narrower half field of view (vertical
        // here: 400 x 300): inside it, and filling at least 90% of it (not framed from afar).
        const float radius = 0.5f * length(b.diagonal());
        const float angular = std::asin(radius / length(c - ctl.eye()));
        EXPECT_LE(angular, 0.35f + 1e-4f);
        EXPECT_GE(angular, 0.9f * 0.35f);
    }
}

TEST(CameraDirections, DirectionalLightDraggedOverEmptySpaceTravelsAlongTheCursorRay) {
    CameraController ctl = makeController();
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = Vec3(0, -1, 0);
    for (Vec2 p : {Vec2{50, 40}, Vec2{350, 260}, Vec2{200, 150}}) {
        dragLight(sun, ctl, p.x, p.y, 3.0f, -2.0f, nullptr);
        const Ray r = ctl.ray(p.x, p.y);
        EXPECT_NEAR(length(sun.direction - r.d), 0.0f, 1e-6f) << "at " << p.x << "," << p.y;
        EXPECT_NEAR(length(sun.direction), 1.0f, 1e-6f);
    }
    // Top-left of the window: the light travels up-left, away from the eye.
    dragLight(sun, ctl, 0.0f, 0.0f, 1.0f, 1.0f, nullptr);
    EXPECT_LT(sun.direction.x, 0.0f);
    EXPECT_GT(sun.direction.y, 0.0f);
    EXPECT_LT(sun.direction.z, 0.0f);
}

TEST(CameraDirections, SpotDraggedOverEmptySpaceAimsAlongTheCursorRayAtThePivotsDistance) {
    CameraController ctl = makeController();
    Light spot;
    spot.type = LightType::Spot;
    spot.position = Vec3(2, 3, 1);
    const float x = 320.0f, y = 60.0f;
    dragLight(spot, ctl, x, y, 4.0f, 4.0f, nullptr);
    // The target: the point on the cursor's ray at the spot's distance to the pivot.
    const Ray r = ctl.ray(x, y);
    const Vec3 target = r.o + r.d * length(ctl.pivot() - spot.position);
    EXPECT_NEAR(length(spot.direction - normalize(target - spot.position)), 0.0f, 1e-5f);
    // Seen from the eye, the spot now points at what lies under the cursor: its target projects there.
    const Vec2 s = screen(ctl, target);
    EXPECT_NEAR(s.x, x, 1e-2f);
    EXPECT_NEAR(s.y, y, 1e-2f);
    EXPECT_EQ(spot.position.x, 2.0f) << "a spot re-aims; it does not move";
}

}  // namespace
}  // namespace tyndall
