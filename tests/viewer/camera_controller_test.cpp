// The viewer's camera controller and light dragging, without a window.
#include <gtest/gtest.h>

#include "viewer/camera_controller.h"

namespace tyndall {
namespace {

CameraController makeController() {
    Camera c = Camera::lookAt(Vec3(0, 1, 5), Vec3(0, 1, 0), Vec3(0, 1, 0), 0.7f);
    CameraController ctl(c, 5.0f);
    ctl.setViewport(400, 300);
    return ctl;
}

TEST(CameraController, StartsWhereTheCameraIsWithThePivotAhead) {
    CameraController ctl = makeController();
    Camera c = ctl.camera();
    EXPECT_NEAR(c.position.z, 5.0f, 1e-6f);
    EXPECT_NEAR(ctl.pivot().y, 1.0f, 1e-5f);
    EXPECT_NEAR(ctl.pivot().z, 0.0f, 1e-5f);
    EXPECT_NEAR(ctl.distanceToPivot(), 5.0f, 1e-5f);
}

TEST(CameraController, OrbitKeepsTheDistanceToThePivotAndTurnsTheView) {
    CameraController ctl = makeController();
    Vec3 pivot = ctl.pivot();
    for (int i = 0; i < 50; ++i) {
        ctl.orbit(13.0f, (i % 7) - 3.0f);
        EXPECT_NEAR(ctl.distanceToPivot(), 5.0f, 1e-3f) << "step " << i;
        EXPECT_NEAR(length(ctl.pivot() - pivot), 0.0f, 1e-6f);
        // The pivot stays where the camera looks (it started at the centre of the view).
        Vec3 toPivot = normalize(ctl.pivot() - ctl.eye());
        EXPECT_GT(dot(toPivot, ctl.camera().forward), 0.9999f);
    }
    // Dragging right by a whole viewport height turns the camera by pi about the up axis.
    CameraController half = makeController();
    half.orbit(300.0f, 0.0f);
    EXPECT_NEAR(half.eye().z, -5.0f, 1e-3f);
    EXPECT_NEAR(half.camera().forward.z, 1.0f, 1e-4f);
}

TEST(CameraController, OrbitStopsShortOfThePoles) {
    CameraController ctl = makeController();
    ctl.orbit(0.0f, 5000.0f);  // far past straight down
    Camera c = ctl.camera();
    EXPECT_LT(std::abs(c.forward.y), 0.99999f);
    EXPECT_TRUE(std::isfinite(c.right.x) && length(c.right) > 0.99f);
    EXPECT_NEAR(ctl.distanceToPivot(), 5.0f, 1e-3f);
}

TEST(CameraController, PanKeepsTheViewDirectionAndMovesThePivotUnderTheCursor) {
    CameraController ctl = makeController();
    Vec3 forward = ctl.camera().forward;
    Vec3 pivot = ctl.pivot();
    ctl.pan(40.0f, -25.0f);
    Camera c = ctl.camera();
    EXPECT_NEAR(dot(c.forward, forward), 1.0f, 1e-6f);
    // Dragging right moves the world right under the cursor: the camera moves left, one pixel's
    // world size at the pivot's depth per pixel.
    float s = ctl.pixelSize(5.0f);
    EXPECT_NEAR(ctl.pivot().x - pivot.x, -40.0f * s, 1e-5f);
    EXPECT_NEAR(ctl.pivot().y - pivot.y, -25.0f * s, 1e-5f);
    EXPECT_NEAR(ctl.distanceToPivot(), 5.0f, 1e-4f);
    // The pivot projects where it did (the centre of the view).
    float fx, fy, depth;
    ASSERT_TRUE(c.project(ctl.pivot(), 400, 300, &fx, &fy, &depth));
    EXPECT_NEAR(fx, 200.0f, 1e-2f);
    EXPECT_NEAR(fy, 150.0f, 1e-2f);
}

TEST(CameraController, DollyApproachesThePivotAndStopsThere) {
    CameraController ctl = makeController();
    ctl.dolly(1.0f);
    EXPECT_NEAR(ctl.distanceToPivot(), 5.0f * 0.85f, 1e-4f);
    ctl.dolly(-1.0f);
    EXPECT_NEAR(ctl.distanceToPivot(), 5.0f, 1e-4f);
    for (int i = 0; i < 1000; ++i) {
        ctl.dolly(3.0f);
        ASSERT_GE(ctl.distanceToPivot(), ctl.minDistance() * 0.999f) << "step " << i;
        // Never passes the pivot: the eye stays on the side it started on.
        ASSERT_GT(ctl.eye().z - ctl.pivot().z, 0.0f) << "step " << i;
        ASSERT_LT(ctl.eye().z - ctl.pivot().z, 5.0f + 1e-4f);
    }
    EXPECT_NEAR(ctl.distanceToPivot(), ctl.minDistance(), 1e-4f);
    EXPECT_GT(ctl.eye().z, ctl.pivot().z);
}

TEST(CameraController, FrameSeesTheWholeBounds) {
    CameraController ctl = makeController();
    Bounds3 b;
    b.extend(Vec3(10, 0, -3));
    b.extend(Vec3(14, 2, 1));
    ctl.frame(b);
    Camera c = ctl.camera();
    EXPECT_NEAR(length(ctl.pivot() - b.center()), 0.0f, 1e-5f);
    for (int i = 0; i < 8; ++i) {
        Vec3 p(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        float fx, fy, depth;
        ASSERT_TRUE(c.project(p, 400, 300, &fx, &fy, &depth));
        EXPECT_GE(fx, 0.0f);
        EXPECT_LE(fx, 400.0f);
        EXPECT_GE(fy, 0.0f);
        EXPECT_LE(fy, 300.0f);
    }
}

TEST(CameraController, PickRayGoesThroughThePixelAndSetPivotFocuses) {
    CameraController ctl = makeController();
    Ray r = ctl.ray(200.0f, 150.0f);
    EXPECT_NEAR(dot(r.d, ctl.camera().forward), 1.0f, 1e-6f);
    // A point projected to a pixel lies on that pixel's ray.
    Vec3 p(0.7f, 1.3f, -2.0f);
    float fx, fy, depth;
    ASSERT_TRUE(ctl.camera().project(p, 400, 300, &fx, &fy, &depth));
    Ray q = ctl.ray(fx, fy);
    float t = dot(p - q.o, q.d);
    EXPECT_NEAR(length(q.o + q.d * t - p), 0.0f, 1e-4f);
    ctl.setPivot(p);
    EXPECT_NEAR(ctl.camera().focusDistance, depth, 1e-4f);
    EXPECT_NEAR(length(ctl.pivot() - p), 0.0f, 1e-6f);
}

TEST(DragLight, PointLightFollowsTheCursorAndSpotAimsAtTheSurfaceUnderIt) {
    CameraController ctl = makeController();
    Light point;
    point.type = LightType::Point;
    point.position = Vec3(0, 1, 0);  // at the pivot's depth
    dragLight(point, ctl, 230.0f, 150.0f, 30.0f, 0.0f, nullptr);
    EXPECT_NEAR(point.position.x, 30.0f * ctl.pixelSize(5.0f), 1e-5f);  // right on screen = +x here
    EXPECT_NEAR(point.position.y, 1.0f, 1e-6f);
    dragLight(point, ctl, 230.0f, 160.0f, 0.0f, 10.0f, nullptr);
    EXPECT_LT(point.position.y, 1.0f);  // down on screen = down

    Light spot;
    spot.type = LightType::Spot;
    spot.position = Vec3(0, 3, 0);
    Vec3 floor(1.0f, 0.0f, 0.5f);
    dragLight(spot, ctl, 0, 0, 0, 0, &floor);
    EXPECT_NEAR(length(spot.direction - normalize(floor - spot.position)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace tyndall
