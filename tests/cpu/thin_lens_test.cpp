// Depth of field from averaging passes: each pass jitters every camera path over the thin lens, so
// an edge on the plane of focus stays sharp and an edge far behind it blurs by its circle of
// confusion, while a pinhole keeps both sharp.
//
// Scene: two emissive, black (albedo 0) half-planes facing the camera, so the image is their
// emission times pixel coverage, free of photon noise: a near one (z = -2, the focus distance,
// lower half of the view) and a far one (z = -8, upper half), both ending at x = 0, which projects
// onto a pixel boundary in the middle column. Camera at the origin looking down -z, 40 degree
// vertical field of view, 48 x 32 pixels: a pixel spans 0.0455 at distance 2. A lens of radius
// 0.25 focused at 2 blurs a point at 8 into a disk of diameter 2 * 0.25 * (8 - 2) / 8 = 0.375 at
// the focus plane, 8.2 pixels; a disk's edge profile rises from 10% to 90% over 0.69 of its
// diameter, 5.7 pixels, so 5 or 6 columns have a mean strictly between 0.1 and 0.9 (asserted: 4..8).
// In focus and with the pinhole: at most one such column (the edge falls on a pixel boundary).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/accumulator.h"
#include "loading/mesh_builders.h"
#include "cpu/pass_renderer.h"

namespace tyndall {
namespace {

constexpr int kWidth = 48, kHeight = 32;

Scene twoEdgesScene(float lensRadius) {
    Scene s;
    s.name = "two-edges";
    s.source = "<test scene>";
    Material glow;
    glow.name = "glow";
    glow.albedo = Rgb(0.0f);
    glow.emission = Rgb(1.0f);
    s.materials = {glow};
    s.meshes.push_back(makeQuad("near", {-10, -10, -2}, {10, 0, 0}, {0, 10, 0}, 0));  // normal +z
    s.meshes.push_back(makeQuad("far", {-40, 0, -8}, {40, 0, 0}, {0, 40, 0}, 0));
    s.camera = Camera::lookAt({0, 0, 0}, {0, 0, -2}, {0, 1, 0}, 40.0f * kPi / 180.0f);
    s.camera.lensRadius = lensRadius;
    s.finalize();
    s.validate();
    return s;
}

/// Mean over rows [y0, y1) of each column.
std::vector<double> columnProfile(const Image& img, int y0, int y1) {
    std::vector<double> p(img.width, 0.0);
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < img.width; ++x) p[x] += img.at(x, y).g / double(y1 - y0);
    return p;
}

/// Columns whose profile lies strictly between 10% and 90% of the left plateau (the right is 0).
int edgeWidth(const std::vector<double>& p) {
    const double plateau = p.front();
    int n = 0;
    for (double v : p) n += v > 0.1 * plateau && v < 0.9 * plateau;
    return n;
}

struct Edges {
    int nearWidth, farWidth;
    double nearPlateau, farPlateau;
};

Edges renderEdges(float lensRadius) {
    Scene scene = twoEdgesScene(lensRadius);
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.photonsPerPass = 64;  // they all fly off to nowhere or land on black
    s.seed = 5;
    PassRenderer renderer(scene, s);
    Accumulator acc(kWidth, kHeight);
    for (uint64_t p = 0; p < 64; ++p) acc.addPass(renderer.renderPass(p));
    Image img = acc.mean();
    // Rows well away from the horizontal edges at the middle (blurred by up to 4 px for the far one).
    std::vector<double> farRows = columnProfile(img, 2, 10), nearRows = columnProfile(img, 22, 30);
    Edges e{edgeWidth(nearRows), edgeWidth(farRows), nearRows.front(), farRows.front()};
    std::printf("lens radius %.2f: edge width in focus %d px, out of focus %d px\n", lensRadius, e.nearWidth,
                e.farWidth);
    return e;
}

TEST(ThinLens, DepthOfFieldBlursOnlyWhatIsOutOfFocus) {
    Edges pinhole = renderEdges(0.0f), lens = renderEdges(0.25f);
    for (const Edges& e : {pinhole, lens}) {
        EXPECT_NEAR(e.nearPlateau, 1.0, 1e-5) << "emission 1 seen head on";
        EXPECT_NEAR(e.farPlateau, 1.0, 1e-5);
    }
    EXPECT_LE(pinhole.nearWidth, 1);
    EXPECT_LE(pinhole.farWidth, 1);
    EXPECT_LE(lens.nearWidth, 1) << "the plane of focus blurred";
    EXPECT_GE(lens.farWidth, 4) << "no depth of field behind the focus plane";
    EXPECT_LE(lens.farWidth, 8) << "more blur than the circle of confusion";
}

}  // namespace
}  // namespace tyndall
