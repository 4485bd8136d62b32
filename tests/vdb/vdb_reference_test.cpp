// Heterogeneous PPB converges to the in-tree reference path tracer (cpu/reference_tracer.h) on a
// small VDB scene: the consistency room of tests/cpu (spot and area light, mirror, glass sphere,
// coloured diffuse walls) with its fog replaced by an OpenVDB grid of smoke blobs over a thin
// haze, built in memory. Every PPB stage meets the grid: photon delta tracking through the
// majorant grid, stored distances on beams and on primary pixels, secondary segments through the
// mirror and the glass sampling their own, sigma_s read from the grid at each gather point. The
// reference tracks the same grid with its own delta and ratio tracking.
//
// Same measures as tests/cpu/ppb_consistency_test.cpp: relMSE (reference variance subtracted)
// must fall from 4 to 16 to 64 passes and end below a bound, and the image and quadrant means
// must agree (they expose normalisation errors the relMSE's noise hides).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "loading/vdb_grid.h"
#include "cpu/reference_tracer.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

// Measured here: relMSE 0.219, 0.073, 0.032 after 4, 16, 64 passes (reference variance 0.0016);
// image mean ratio 1.002, quadrants 0.980 .. 1.016; regions: mirror 1.004 +- 0.011, floor
// 1.017 +- 0.016. The glass sphere's pixels are left out here: through the smoke they are too
// noisy over 8 batches (standard error 8%) to say anything; the homogeneous test checks them.
constexpr double kFinalBound = 0.04;
constexpr double kImageMeanTolerance = 0.02;
constexpr double kQuadrantMeanTolerance = 0.04;
constexpr double kRegionBias = 0.01;

/// Blobs of smoke over a thin haze, voxelised at 0.1 over [-1.2, 1.2] x [-0.2, 2.2] x [-1.2, 1.2]
/// (beyond the room, so the room never sees the grid's edge).
std::shared_ptr<const VdbDensityGrid> smokeBlobs() {
    const float voxel = 0.1f;
    const Vec3 lo(-1.2f, -0.2f, -1.2f);
    int dims[3] = {25, 25, 25};
    struct Blob {
        Vec3 c;
        float r, d;
    };
    const Blob blobs[] = {{{-0.4f, 0.9f, -0.3f}, 0.35f, 3.0f},
                          {{0.3f, 1.3f, -0.2f}, 0.25f, 4.0f},
                          {{0.1f, 0.4f, 0.2f}, 0.3f, 2.0f},
                          {{-0.5f, 0.3f, -0.6f}, 0.2f, 5.0f}};
    std::vector<float> v(size_t(dims[0]) * dims[1] * dims[2]);
    for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
            for (int i = 0; i < dims[0]; ++i) {
                Vec3 p = lo + Vec3(float(i), float(j), float(k)) * voxel;
                float d = 0.15f;
                for (const Blob& b : blobs) d += b.d * std::exp(-lengthSquared(p - b.c) / (b.r * b.r));
                v[(size_t(k) * dims[1] + j) * dims[0] + i] = d;
            }
    return VdbDensityGrid::fromDense(dims, v, Affine3::scaleTranslate(Vec3(voxel), lo), "smoke blobs");
}

TEST(VdbReference, PpbInAVdbSmokeRoomConvergesToTheReference) {
    Scene scene = test::makeConsistencyScene();
    Medium& smoke = scene.media[scene.globalMedium];
    smoke.name = "vdb smoke";
    smoke.sigmaS = Rgb(0.30f, 0.28f, 0.26f);  // grey extinction 0.32 at density 1
    smoke.sigmaA = Rgb(0.02f, 0.04f, 0.06f);
    smoke.density = smokeBlobs();
    scene.validate();

    test::expectPpbConvergesToReference(scene, {kFinalBound, kImageMeanTolerance, kQuadrantMeanTolerance, kRegionBias, /*glassRegion=*/false},
                                        505, 606,
                                        "vdb_reference");
}

}  // namespace
}  // namespace tyndall
