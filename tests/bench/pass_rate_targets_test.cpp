// build/bench/tyndall_stages judges its pass rate only against the target for the run's size,
// photon count and thread count (512x512 with 1000 photon paths, 1920x1080 with 4000; 2 threads).
#include "bench/pass_rate_targets.h"

#include <gtest/gtest.h>

using tyndall::bench::passRateTarget;
using tyndall::bench::passRateVerdict;

TEST(BenchTargets, EachSizeGetsItsOwnTarget) {
    const auto* t512 = passRateTarget(512, 512, 1000);
    ASSERT_NE(t512, nullptr);
    EXPECT_EQ(t512->passesPerSecond, 3.0);
    const auto* t1080 = passRateTarget(1920, 1080, 4000);
    ASSERT_NE(t1080, nullptr);
    EXPECT_EQ(t1080->passesPerSecond, 1.0);
    EXPECT_EQ(passRateTarget(1920, 1080, 1000), nullptr);
    EXPECT_EQ(passRateTarget(512, 512, 4000), nullptr);
    EXPECT_EQ(passRateTarget(1080, 1920, 4000), nullptr);
    EXPECT_EQ(passRateTarget(960, 540, 4000), nullptr);
}

TEST(BenchTargets, VerdictsSayMetOrNotMetAgainstTheRightThreshold) {
    EXPECT_EQ(passRateVerdict(1.117, 1920, 1080, 4000, 2), "(target at 1920x1080: >= 1: met)");
    EXPECT_EQ(passRateVerdict(0.99, 1920, 1080, 4000, 2), "(target at 1920x1080: >= 1: NOT met)");
    EXPECT_EQ(passRateVerdict(1.0, 1920, 1080, 4000, 2), "(target at 1920x1080: >= 1: met)");
    EXPECT_EQ(passRateVerdict(6.1, 512, 512, 1000, 2), "(target at 512x512: >= 3: met)");
    EXPECT_EQ(passRateVerdict(2.9, 512, 512, 1000, 2), "(target at 512x512: >= 3: NOT met)");
}

TEST(BenchTargets, RunsAtOtherSettingsAreNotJudged) {
    const std::string photons = passRateVerdict(5.0, 1920, 1080, 1000, 2);
    EXPECT_EQ(photons.rfind("(not judged: >= 1 passes/s is the target for 1920x1080, 4000 photon paths/pass", 0), 0u)
        << photons;
    const std::string threads = passRateVerdict(5.0, 512, 512, 1000, 16);
    EXPECT_EQ(threads.find("met"), std::string::npos) << threads;
    EXPECT_NE(threads.find("2 threads"), std::string::npos) << threads;
    const std::string size = passRateVerdict(5.0, 960, 540, 4000, 2);
    EXPECT_EQ(size.rfind("(no pass-rate target at this size", 0), 0u) << size;
    EXPECT_EQ(size.find(": met"), std::string::npos) << size;
    EXPECT_NE(size.find("512x512"), std::string::npos) << size;
    EXPECT_NE(size.find("1920x1080"), std::string::npos) << size;
}
