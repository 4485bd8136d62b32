// The checkpoint file format (core/checkpoint.h): an exact round trip of named double sums, pass
// and rejected-sample counts; every truncation length and a flipped bit refused with an Error.
// In core_tests, so the sanitizer build (ASan + UBSan) runs the parser over every truncation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/accumulator.h"
#include "core/checkpoint.h"
#include "core/error.h"
#include "core/image.h"

namespace {

TEST(CheckpointFile, RoundTripIsExactAndEveryTruncationIsRefused) {
    tyndall::Accumulator acc(5, 3);
    tyndall::Image pass(5, 3);
    for (size_t i = 0; i < pass.pixels.size(); ++i) pass.pixels[i] = tyndall::Rgb(0.1f * i, 1.0f / (i + 1), 3.0f);
    acc.addPass(pass);
    pass.pixels[2].g = NAN;
    acc.addPass(pass);
    tyndall::Checkpoint c;
    c.header = {{"format", "test"}, {"n", 7}};
    c.layers.emplace_back("beauty", acc);
    std::string bytes = tyndall::serializeCheckpoint(c);
    tyndall::Checkpoint back = tyndall::parseCheckpoint(bytes, "mem");
    EXPECT_EQ(back.header, c.header);
    ASSERT_EQ(back.layers.size(), 1u);
    EXPECT_EQ(back.layers[0].second.sums(), acc.sums());
    EXPECT_EQ(back.layers[0].second.passCount(), 2u);
    EXPECT_EQ(back.layers[0].second.rejectedSamples(), 1u);
    for (size_t keep = 0; keep < bytes.size(); ++keep)
        EXPECT_THROW(tyndall::parseCheckpoint(bytes.substr(0, keep), "mem"), tyndall::Error) << keep;
    bytes[bytes.size() / 2] ^= 1;
    EXPECT_THROW(tyndall::parseCheckpoint(bytes, "mem"), tyndall::Error);
}

}  // namespace
