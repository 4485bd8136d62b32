// The radius schedule: closed form against the defining product, normalisation, monotonicity and
// the asymptotic rate that gives the running mean variance ~ N^-alpha.
#include "core/radius_schedule.h"

#include <gtest/gtest.h>

#include <cmath>

using tyndall::RadiusSchedule;

TEST(RadiusSchedule, ClosedFormMatchesProduct) {
    for (double alpha : {0.1, 0.3, 0.5, 0.8, 0.9}) {
        double product = 1.0;  // R(1) = 1
        for (int n = 1; n <= 200000; ++n) {
            if (n > 1) product *= (n - 1 + alpha) / double(n);
            if (n == 1 || n == 2 || n == 10 || n == 999 || n == 1000 || n == 1001 || n == 100000 || n == 200000) {
                double closed = std::exp(RadiusSchedule::logR(alpha, n));
                EXPECT_NEAR(closed / product, 1.0, 1e-9) << "alpha " << alpha << " n " << n;
            }
        }
    }
}

TEST(RadiusSchedule, StartsAtOneAndShrinksPerPath) {
    RadiusSchedule s(0.5, 1000);
    EXPECT_DOUBLE_EQ(s.beamFactor(0), 1.0);
    double prev = 1.0;
    for (uint64_t j = 1; j < 5000; ++j) {
        double f = s.beamFactor(j);
        ASSERT_LT(f, prev);
        // Each step is the PPB ratio (n + alpha)/(n + 1) at n = j + offset.
        ASSERT_NEAR(f / prev, (j + 1000 + 0.5) / (j + 1000 + 1.0), 1e-11);
        prev = f;
    }
    EXPECT_NEAR(s.surfaceFactor(12345), std::sqrt(s.beamFactor(12345)), 1e-15);
}

TEST(RadiusSchedule, AsymptoticRateIsNToTheAlphaMinusOne) {
    // R(n) ~ n^(alpha-1): the log-log slope between 1e6 and 1e12 paths.
    for (double alpha : {0.3, 0.8}) {
        RadiusSchedule s(alpha, 0);
        double slope = (std::log(s.beamFactor(1000000000000ull)) - std::log(s.beamFactor(1000000))) /
                       (std::log(1e12) - std::log(1e6));
        EXPECT_NEAR(slope, alpha - 1.0, 1e-6);
    }
}

TEST(RadiusSchedule, StableAtHugePathCounts) {
    RadiusSchedule s(0.5, 1000);
    double f = s.beamFactor(uint64_t(1) << 50);
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_GT(f, 0.0);
    // Continuity across the switch from lgamma to the asymptotic series at n = 1000.
    for (double alpha : {0.1, 0.5, 0.9}) {
        double below = std::exp(RadiusSchedule::logR(alpha, 999.0)), above = std::exp(RadiusSchedule::logR(alpha, 1000.0));
        EXPECT_NEAR(above / below, (999.0 + alpha) / 1000.0, 1e-12) << alpha;
    }
}

TEST(RadiusSchedule, RejectsAlphaOutsideUnitInterval) {
    EXPECT_THROW(RadiusSchedule(0.0, 0), std::exception);
    EXPECT_THROW(RadiusSchedule(1.0, 0), std::exception);
    EXPECT_THROW(RadiusSchedule(-0.5, 0), std::exception);
}
