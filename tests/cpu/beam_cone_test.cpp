// The photon cone (cpu/beam_cone.h): a beam near its light stored as pieces over the dyadic path
// distances. The pieces must cover the beam exactly once, carry the beam's transmittance to
// their start (analytic or stored distances), have the cone's radii, and leave beams outside the
// reach untouched bit for bit. Quick: no rendering.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "core/transmittance.h"
#include "cpu/beam_cone.h"

namespace tyndall {
namespace {

PhotonBeam testBeam(float tMax) {
    PhotonBeam b;
    b.origin = Vec3(0.1f, 0.2f, 0.3f);
    b.dir = normalize(Vec3(1.0f, 2.0f, -0.5f));
    b.tMax = tMax;
    b.radius = 0.08f;
    b.power = Rgb(1.0f, 0.5f, 0.25f);
    b.medium = 0;
    return b;
}

Medium fog() {
    Medium m;
    m.sigmaS = Rgb(0.3f, 0.2f, 0.1f);
    m.sigmaA = Rgb(0.05f);
    return m;
}

TEST(BeamCone, PiecesCoverTheBeamWithTheConeRadiiAndItsTransmittance) {
    const double reach = 2.0;
    const PhotonBeam beam = testBeam(5.0f);
    const Medium m = fog();
    for (double s0 : {0.0, 0.01, 0.3, 1.1}) {
        std::vector<PhotonBeam> pieces;
        std::vector<float> ff;
        appendConeBeam(beam, s0, reach, m, nullptr, 0, pieces, ff);
        ASSERT_GE(pieces.size(), 2u);
        ASSERT_LE(pieces.size(), size_t(kConePieces) + 1) << "path distance only grows: one piece per interval";
        double t = 0;
        for (size_t i = 0; i < pieces.size(); ++i) {
            const PhotonBeam& p = pieces[i];
            // Contiguous along the beam's line, in order.
            Vec3 expected = beam.origin + beam.dir * float(t);
            EXPECT_NEAR(length(p.origin - expected), 0.0, 1e-5) << "s0 " << s0 << " piece " << i;
            EXPECT_EQ(p.dir.x, beam.dir.x);
            // Radius: the full radius beyond the reach; inside it, no wider than the cone at the
            // piece's far end and within a factor sqrt(kConeRatio) of it along the piece.
            const double sMid = s0 + t + 0.5 * p.tMax, sStart = s0 + t;
            const double cone = double(beam.radius) / reach * (s0 + t + p.tMax);
            if (sStart >= reach * (1 - 1e-5)) {
                EXPECT_EQ(p.radius, beam.radius);
            } else {
                EXPECT_LT(p.radius, beam.radius);
                EXPECT_LE(p.radius, cone * 1.0001) << "never wider than the cone at the piece's far end";
                const bool innermost = sStart < reach * std::pow(kConeRatio, 1 - kConePieces) * 0.999;
                if (innermost)
                    EXPECT_NEAR(p.radius, beam.radius * std::pow(kConeRatio, 0.5 - kConePieces), 1e-7)
                        << "the floor below the last interval";
                else
                    EXPECT_GE(p.radius, double(beam.radius) / reach * sStart / std::sqrt(kConeRatio) * 0.999)
                        << "within sqrt(kConeRatio) of the cone along the piece";
                (void)sMid;
            }
            // Power: the beam's, times the transmittance up to the piece's start.
            Rgb tr = m.transmittance(float(t));
            EXPECT_NEAR(p.power.r, beam.power.r * tr.r, 1e-6);
            EXPECT_NEAR(p.power.b, beam.power.b * tr.b, 1e-6);
            t += p.tMax;
        }
        EXPECT_NEAR(t, beam.tMax, 1e-5) << "the pieces end where the beam ends";
    }
}

TEST(BeamCone, BeamsBeyondTheReachOrWithoutAConeAreStoredUnchanged) {
    const PhotonBeam beam = testBeam(3.0f);
    const Medium m = fog();
    for (auto [s0, reach] : {std::pair{2.0, 2.0}, std::pair{5.0, 2.0}, std::pair{0.0, 0.0}}) {
        std::vector<PhotonBeam> pieces;
        std::vector<float> ff;
        appendConeBeam(beam, s0, reach, m, nullptr, 0, pieces, ff);
        ASSERT_EQ(pieces.size(), 1u);
        EXPECT_EQ(std::memcmp(&pieces[0], &beam, sizeof(PhotonBeam)), 0) << "bit for bit";
    }
}

TEST(BeamCone, StoredFreeFlightsGiveEachPieceTheBeamsTransmittance) {
    const PhotonBeam beam = testBeam(4.0f);
    Medium grid = fog();
    struct Uniform : DensityGrid {
        float density(const Vec3&) const override { return 1.0f; }
        Bounds3 bounds() const override { return Bounds3(); }
        float maxDensity() const override { return 1.0f; }
        float meanDensity() const override { return 1.0f; }
    };
    grid.density = std::make_shared<Uniform>();  // only homogeneous() is read
    const float distances[4] = {0.02f, 0.7f, 1.9f, 100.0f};
    std::vector<PhotonBeam> pieces;
    std::vector<float> ff;
    appendConeBeam(beam, 0.0, 3.0, grid, distances, 4, pieces, ff);
    ASSERT_EQ(ff.size(), 4 * pieces.size());
    double t = 0;
    for (size_t i = 0; i < pieces.size(); ++i) {
        EXPECT_EQ(pieces[i].power.r, beam.power.r) << "grid pieces keep the power: the distances carry Tr";
        for (float u : {0.0f, 0.5f, 1.0f})
            EXPECT_EQ(storedTransmittance(&ff[4 * i], 4, u * pieces[i].tMax),
                      storedTransmittance(distances, 4, float(t) + u * pieces[i].tMax))
                << "piece " << i << " at " << u;
        t += pieces[i].tMax;
    }
}

}  // namespace
}  // namespace tyndall
