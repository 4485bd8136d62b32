// Bounded memory, as a user meets it: one pass of 4e6 photon paths (about 13 million beams,
// some 1.5 GB of beams and their structures if traced at once) under a 1 GiB address-space limit
// (ulimit -v, CPU only, 2 threads: the program and its threads take about 0.75 GiB of it) renders
// to a finite image, the photon batches keeping the pass's beams bounded; a pass whose batches
// do not bound it (traced at once) ends out of memory. A --memory above the limit is refused up
// front with both figures. The image is 16x16 so that the photons, not the pixels, are the work.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::CliRun;

/// `tyndall <args>` with its address space limited to `limitKiB` (ulimit -v).
CliRun runLimited(uint64_t limitKiB, const std::string& args) {
    return tyndall::test::runShell("sh -c 'ulimit -v " + std::to_string(limitKiB) + " && exec " +
                                   std::string(TYNDALL_BINARY) + " " + args + " 2>&1'");
}

/// Open fog around a point light between two quads: about one beam per photon path, so the
/// photons of a pass are the memory.
std::string writeOpenFogScene() {
    std::string path = tyndall::test::outputDir() + "/memory_limit_open_fog.json";
    std::ofstream(path) << R"({"name": "open-fog",
 "materials": [{"name": "grey", "type": "diffuse", "albedo": 0.5}],
 "media": [{"name": "fog", "sigma_s": 0.02, "sigma_a": 0.01}], "global_medium": "fog",
 "shapes": [{"type": "quad", "name": "floor", "material": "grey", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]},
            {"type": "quad", "name": "top", "material": "grey", "corner": [-1, 2, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2]}],
 "lights": [{"type": "point", "name": "p", "position": [0, 1, 0], "intensity": [1, 1, 1]}],
 "cameras": [{"name": "c", "position": [0, 1, 3], "target": [0, 1, 0], "up": [0, 1, 0], "fov": 50}]})";
    return path;
}

constexpr uint64_t kOneGiB = 1ull << 20;   // KiB
constexpr uint64_t kFourGiB = 4ull << 20;  // KiB

TEST(MemoryLimit, FourMillionPhotonPathsInOnePassUnderOneGigabyte) {
    const std::string scene = writeOpenFogScene();
    const std::string out = tyndall::test::outputDir() + "/memory_limit_4e6.exr";
    std::remove(out.c_str());
    CliRun r = runLimited(kOneGiB, "render " + scene +
                                       " --size 16x16 --passes 1 --photons 4000000 --memory 1000 --threads 2 "
                                       "--gpu off --seed 3 -o " + out);
    std::printf("%s", r.output.c_str());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("4000000 photon paths"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("batches of up to"), std::string::npos) << r.output;
    tyndall::Image image = tyndall::readImage(out);
    ASSERT_EQ(image.width, 16);
    double sum = 0;
    for (const tyndall::Rgb& p : image.pixels)
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(p[c]));
            sum += p[c];
        }
    EXPECT_GT(sum, 0.0) << "the fog should be lit";
}

TEST(MemoryLimit, ABudgetOverTheAddressSpaceLimitIsRefusedUpFront) {
    const std::string scene = writeOpenFogScene();
    CliRun r = runLimited(kFourGiB, "render " + scene + " --size 16x16 --passes 1 --memory 8192 --gpu off -o " +
                                     tyndall::test::outputDir() + "/memory_limit_refused.png");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("--memory 8.0 GiB is more than this process's address-space limit (ulimit -v) of 4.0 GiB"),
              std::string::npos)
        << r.output;
}

}  // namespace
