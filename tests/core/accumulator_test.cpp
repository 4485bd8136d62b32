// The progressive accumulator: running mean in double, merge equals adding the same passes,
// reset, and a save/load round trip that is exact.
#include "core/accumulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "tests/test_util.h"

using namespace tyndall;

namespace {
Image constantImage(int w, int h, Rgb c) {
    Image img(w, h);
    for (auto& p : img.pixels) p = c;
    return img;
}
}  // namespace

TEST(Accumulator, MeanOfPasses) {
    Accumulator acc(3, 2);
    EXPECT_EQ(acc.mean().pixels[0].r, 0.0f);
    acc.addPass(constantImage(3, 2, Rgb(1, 2, 3)));
    acc.addPass(constantImage(3, 2, Rgb(3, 2, 1)));
    acc.addPass(constantImage(3, 2, Rgb(2, 5, 2)));
    EXPECT_EQ(acc.passCount(), 3u);
    EXPECT_FLOAT_EQ(acc.mean().at(2, 1).r, 2.0f);
    EXPECT_FLOAT_EQ(acc.mean().at(0, 0).g, 3.0f);
    EXPECT_DOUBLE_EQ(acc.meanAt(1, 1, 2), 2.0);
    acc.reset();
    EXPECT_EQ(acc.passCount(), 0u);
    EXPECT_EQ(acc.mean().at(1, 1).g, 0.0f);
    EXPECT_THROW(acc.addPass(constantImage(2, 2, Rgb(1))), Error);
}

TEST(Accumulator, DoublePrecisionKeepsSmallPassesAfterLargeOnes) {
    Accumulator acc(1, 1);
    acc.addPass(constantImage(1, 1, Rgb(1e8f)));
    for (int i = 0; i < 1000; ++i) acc.addPass(constantImage(1, 1, Rgb(1.0f)));
    EXPECT_NEAR(acc.meanAt(0, 0, 0), (1e8 + 1000.0) / 1001.0, 1e-6);
}

TEST(Accumulator, MergeEqualsAddingTheSamePasses) {
    Accumulator a(2, 2), b(2, 2), all(2, 2);
    for (int i = 0; i < 5; ++i) {
        Image img = constantImage(2, 2, Rgb(float(i), float(i * i), 1.0f / (i + 1)));
        (i < 2 ? a : b).addPass(img);
        all.addPass(img);
    }
    a.merge(b);
    EXPECT_EQ(a.passCount(), all.passCount());
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(a.meanAt(1, 0, c), all.meanAt(1, 0, c));
}

TEST(Accumulator, SaveLoadRoundTripIsExact) {
    Accumulator acc(4, 3);
    Image img(4, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Rgb(0.1f * i, 1.0f / (i + 1), 3.0f);
    acc.addPass(img);
    acc.addPass(img);
    std::string path = test::outputDir() + "/acc_roundtrip.tacc";
    acc.save(path);
    Accumulator back = Accumulator::load(path);
    EXPECT_EQ(back.passCount(), 2u);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(back.meanAt(x, y, c), acc.meanAt(x, y, c));
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fputs("garbage", f);
    std::fclose(f);
    EXPECT_THROW(Accumulator::load(path), Error);
    EXPECT_THROW(Accumulator::load(test::outputDir() + "/no_such_file.tacc"), Error);
}

TEST(Accumulator, NaNAndInfinityNeverReachTheSums) {
    // A planted NaN and an infinity: those pixels count as black in that pass, are counted, and
    // the running mean stays finite (one bad sample would otherwise poison the pixel for good).
    Accumulator acc(2, 2);
    Image bad = constantImage(2, 2, Rgb(1, 1, 1));
    bad.at(0, 0).g = std::numeric_limits<float>::quiet_NaN();
    bad.at(1, 1).b = std::numeric_limits<float>::infinity();
    acc.addPass(bad);
    acc.addPass(constantImage(2, 2, Rgb(3, 3, 3)));
    EXPECT_EQ(acc.rejectedSamples(), 2u);
    for (const Rgb& p : acc.mean().pixels)
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(p[c]));
    EXPECT_DOUBLE_EQ(acc.meanAt(0, 0, 0), 1.5);  // (0 + 3) / 2: the whole pixel dropped in the bad pass
    EXPECT_DOUBLE_EQ(acc.meanAt(1, 0, 1), 2.0);
    Accumulator other(2, 2);
    other.addPass(bad);
    acc.merge(other);
    EXPECT_EQ(acc.rejectedSamples(), 4u);
    acc.reset();
    EXPECT_EQ(acc.rejectedSamples(), 0u);
}
