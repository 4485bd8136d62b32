// Smooth dielectric Fresnel (core/fresnel.h) against the textbook values: 0.04 at normal incidence
// for glass (n = 1.5) from either side, Fresnel's sine and tangent laws at every angle (so a stray
// factor or a polarisation mixed up shows), zero p-reflectance at Brewster's angle, total internal
// reflection from inside beyond the critical angle (and not before it), reciprocity
// F(outside, theta_i) = F(inside, theta_t), and Snell's law and reversibility of refract(). The
// expected values are computed here from the angles alone, not from the code's formula.
#include "core/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tyndall;

namespace {

constexpr double kEta = 1.5;  // glass inside, air outside

/// Unpolarised reflectance from Fresnel's sine and tangent laws, light in a medium of index n1
/// meeting one of index n2 at angle thetaI (radians). Returns 1 past the critical angle.
double fresnelFromAngles(double thetaI, double n1, double n2) {
    double s = n1 / n2 * std::sin(thetaI);
    if (s >= 1.0) return 1.0;
    double thetaT = std::asin(s);
    if (thetaI < 1e-9) return std::pow((n1 - n2) / (n1 + n2), 2);
    double rs = std::pow(std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT), 2);
    double rp = std::pow(std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT), 2);
    return 0.5 * (rs + rp);
}

}  // namespace

TEST(Fresnel, FourPercentAtNormalIncidenceFromEitherSide) {
    EXPECT_NEAR(fresnelDielectric(1.0f, float(kEta)), 0.04f, 1e-6f);   // from outside (air -> glass)
    EXPECT_NEAR(fresnelDielectric(-1.0f, float(kEta)), 0.04f, 1e-6f);  // from inside (glass -> air)
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f), 0.0f, 1e-7f) << "index-matched: no reflection";
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.33f), std::pow(0.33 / 2.33, 2), 1e-6);  // water
}

TEST(Fresnel, MatchesTheSineAndTangentLawsAtEveryAngle) {
    for (int i = 0; i <= 89; ++i) {
        double theta = i * M_PI / 180.0;
        float c = float(std::cos(theta));
        EXPECT_NEAR(fresnelDielectric(c, float(kEta)), fresnelFromAngles(theta, 1.0, kEta), 2e-6)
            << "from outside at " << i << " degrees";
        EXPECT_NEAR(fresnelDielectric(-c, float(kEta)), fresnelFromAngles(theta, kEta, 1.0), 2e-6)
            << "from inside at " << i << " degrees";
    }
    // Grazing: everything reflects.
    EXPECT_NEAR(fresnelDielectric(1e-4f, float(kEta)), 1.0f, 1e-3f);
}

TEST(Fresnel, BrewstersAngleReflectsOnlyTheSPolarisation) {
    // At tan(theta_B) = n2/n1 the p-reflectance vanishes: F = Rs/2 with Rs = cos^2(2 theta_B) for
    // n = 1.5 (sin(theta_i - theta_t) / sin(theta_i + theta_t) with theta_i + theta_t = 90 deg).
    double thetaB = std::atan(kEta);
    double rs = std::pow(std::cos(2.0 * thetaB), 2);
    EXPECT_NEAR(fresnelDielectric(float(std::cos(thetaB)), float(kEta)), 0.5 * rs, 1e-6);
    // The same from inside at arctan(1/n).
    double thetaBInside = std::atan(1.0 / kEta);
    EXPECT_NEAR(fresnelDielectric(float(-std::cos(thetaBInside)), float(kEta)), 0.5 * rs, 1e-6);
}

TEST(Fresnel, TotalInternalReflectionOnlyFromInsidePastTheCriticalAngle) {
    double critical = std::asin(1.0 / kEta);  // 41.8 degrees
    for (double d : {0.2, 1.0, 10.0, 40.0}) {
        double theta = critical + d * M_PI / 180.0;
        if (theta >= M_PI / 2) continue;
        EXPECT_EQ(fresnelDielectric(float(-std::cos(theta)), float(kEta)), 1.0f) << "inside, critical + " << d << " deg";
        EXPECT_LT(fresnelDielectric(float(std::cos(theta)), float(kEta)), 0.5f) << "outside at the same angle";
        Vec3 n(0, 0, 1), wo(float(std::sin(theta)), 0, -float(std::cos(theta))), wt;
        EXPECT_FALSE(refract(wo, n, float(kEta), &wt)) << "refract() must agree: TIR";
    }
    double below = critical - 0.5 * M_PI / 180.0;
    EXPECT_LT(fresnelDielectric(float(-std::cos(below)), float(kEta)), 0.5f) << "just inside the critical angle";
}

TEST(Fresnel, ReciprocityAndSnellsLaw) {
    // Light refracted from outside at theta_i travels inside at theta_t; the reverse path (wo = wt,
    // on the inside) sees the same reflectance, and refract() of it gives back the original wo.
    const Vec3 n(0, 0, 1);
    for (int i = 1; i <= 85; i += 4) {
        double theta = i * M_PI / 180.0;
        Vec3 wo(float(std::sin(theta)), 0, float(std::cos(theta)));  // outside, pointing away
        Vec3 wt;
        ASSERT_TRUE(refract(wo, n, float(kEta), &wt));
        EXPECT_NEAR(length(wt), 1.0f, 1e-5f);
        EXPECT_LT(wt.z, 0.0f) << "refracted to the inside";
        double sinT = std::sqrt(double(wt.x) * wt.x + double(wt.y) * wt.y);
        EXPECT_NEAR(kEta * sinT, std::sin(theta), 2e-6) << "Snell at " << i << " degrees";
        EXPECT_LT(wt.x, 0.0f) << "the refracted ray continues across the normal";
        EXPECT_NEAR(fresnelDielectric(wt.z, float(kEta)), fresnelDielectric(wo.z, float(kEta)), 1e-5)
            << "reciprocity at " << i << " degrees";
        Vec3 back;
        ASSERT_TRUE(refract(wt, n, float(kEta), &back));
        EXPECT_NEAR(back.x, wo.x, 2e-6f);
        EXPECT_NEAR(back.z, wo.z, 2e-6f);
    }
}
