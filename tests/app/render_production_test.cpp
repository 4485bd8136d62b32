// `tyndall render` for final frames: the progress report on a pseudo-terminal (a bar redrawn in
// place with percentage, passes/s and ETA) and in a pipe (plain lines, no control characters),
// --quiet; AOV layers (names, the three components add up to the beauty image, the beauty image
// unchanged by --aov, a variance layer that is the variance of the running mean); the convergence
// CSV; and Open MPI: 2 ranks give the single-process image bit for bit (--passes), agree on one
// pass count (--time) and record tyndall:ranks; --gpu on with --aov and under two ranks; the GL
// splat failing mid-render (the render finishes on the CPU with one warning).
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/progress_meter.h"
#include "core/image_io.h"
#include "core/layer_accumulator.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

namespace fs = std::filesystem;
using tyndall::test::runTyndall;

const std::string kSmall = "--size 48x36 --photons 400 --gpu off";

std::string out(const std::string& name) {
    return tyndall::test::outputDir() + "/production_" + name;
}

/// Runs `tyndall <args>` with stderr and stdout on a pseudo-terminal of `cols` columns; returns
/// everything it wrote.
std::string runOnPty(const std::vector<std::string>& args, int cols = 100) {
    winsize ws{};
    ws.ws_col = cols;
    ws.ws_row = 24;
    int master = -1;
    pid_t pid = forkpty(&master, nullptr, nullptr, &ws);
    if (pid == 0) {
        std::vector<char*> argv{const_cast<char*>(TYNDALL_BINARY)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        _exit(127);
    }
    std::string text;
    char buf[4096];
    for (;;) {
        ssize_t n = read(master, buf, sizeof buf);
        if (n <= 0) break;  // EIO once the child has exited and closed its side
        text.append(buf, size_t(n));
    }
    waitpid(pid, nullptr, 0);
    close(master);
    return text;
}

TEST(Progress, TerminalGetsABarRedrawnInPlaceWithEta) {
    std::string text = runOnPty({"render", "--size", "48x36", "--photons", "400", "--gpu", "off", "--passes", "6",
                                 "-o", out("pty.png")});
    // One redraw per pass: carriage return, the bar, erase to the end of the line.
    size_t redraws = 0;
    for (size_t at = 0; (at = text.find("\r[", at)) != std::string::npos; ++at) ++redraws;
    EXPECT_EQ(redraws, 6u) << text;
    EXPECT_NE(text.find("\x1b[K"), std::string::npos);
    EXPECT_NE(text.find("100%"), std::string::npos) << text;
    EXPECT_NE(text.find("pass 6/6"), std::string::npos) << text;
    EXPECT_NE(text.find("passes/s"), std::string::npos);
    EXPECT_NE(text.find("ETA"), std::string::npos);
    EXPECT_NE(text.find("[########"), std::string::npos) << "a filled bar at the end";
    EXPECT_NE(text.find("rendered caustic-box"), std::string::npos) << "the summary on its own line";
    // A time budget fills the bar by the clock.
    text = runOnPty({"render", "--size", "48x36", "--photons", "400", "--gpu", "off", "--time", "1", "-o", out("pty.png")});
    EXPECT_NE(text.find("ETA"), std::string::npos) << text;
    EXPECT_EQ(text.find("pass 1/"), std::string::npos) << "no pass target with --time";
}

TEST(Progress, PipeGetsPlainLinesAndQuietGetsNone) {
    auto r = runTyndall("render " + kSmall + " --passes 5 --progress-every 0 -o " + out("pipe.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find('\r'), std::string::npos);
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos);
    int lines = 0;
    for (size_t at = 0; (at = r.output.find(" passes/s  ETA ", at)) != std::string::npos; ++at) ++lines;
    EXPECT_EQ(lines, 5) << "one line per pass with --progress-every 0:\n" << r.output;
    EXPECT_NE(r.output.find("pass 5/5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("ETA"), std::string::npos);
    // A line every S seconds: none in a render shorter than S (an hour here, so that the test does
    // not depend on the machine's speed; the 5 s default is tested on the meter below).
    r = runTyndall("render " + kSmall + " --passes 3 --progress-every 3600 -o " + out("pipe.png"));
    EXPECT_EQ(r.output.find("ETA"), std::string::npos) << r.output;
    r = runTyndall("render " + kSmall + " --passes 3 --progress-every 0 --quiet -o " + out("pipe.png"));
    EXPECT_EQ(r.output.find("ETA"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rendered"), std::string::npos);
}

TEST(Progress, PlainLinesComeEveryFiveSecondsByDefault) {
    // The meter's own throttle, on the elapsed times it is given (no clock, no render).
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    tyndall::app::ProgressMeter meter(f, tyndall::app::ProgressStyle::Lines, {100, 0, 0});
    for (int pass = 1; pass <= 100; ++pass) meter.update(uint64_t(pass), 0.11 * pass);  // 11 s in all
    std::rewind(f);
    std::string text;
    for (int ch; (ch = std::fgetc(f)) != EOF;) text.push_back(char(ch));
    std::fclose(f);
    int lines = 0;
    for (size_t at = 0; (at = text.find('\n', at)) != std::string::npos; ++at) ++lines;
    EXPECT_EQ(lines, 2) << "a line 5 s after the start and 5 s after that line:\n" << text;
    EXPECT_NE(text.find("pass 46/100"), std::string::npos) << text;  // 5.06 s: the first pass at or past 5 s
    EXPECT_NE(text.find("pass 92/100"), std::string::npos) << text;  // 10.12 s: 5 s after the first line
}

TEST(Aov, LayersAreNamedAddUpToBeautyAndLeaveItUnchanged) {
    const std::string plain = out("beauty.exr"), aov = out("aov.exr");
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 6 -q -o " + plain).exitCode, 0);
    auto r = runTyndall("render " + kSmall + " --passes 6 -q --aov -o " + aov);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::vector<std::string> expected{"R", "G", "B"};
    for (const char* layer : {"media_primary", "media_secondary", "surface", "variance"})
        for (const char* c : {".R", ".G", ".B"}) expected.push_back(std::string(layer) + c);
    EXPECT_EQ(tyndall::readImageChannels(aov), expected);

    tyndall::Image beauty = tyndall::readImageLayer(aov, "");
    EXPECT_TRUE(tyndall::test::identicalImages(beauty, tyndall::readImage(plain))) << "--aov changed the beauty image";
    tyndall::Image mp = tyndall::readImageLayer(aov, "media_primary"), ms = tyndall::readImageLayer(aov, "media_secondary"),
                   su = tyndall::readImageLayer(aov, "surface");
    double worst = 0, sums[3] = {0, 0, 0};
    for (size_t i = 0; i < beauty.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double sum = double(mp.pixels[i][c]) + ms.pixels[i][c] + su.pixels[i][c], b = beauty.pixels[i][c];
            worst = std::max(worst, std::abs(sum - b) / std::max(std::abs(b), 1e-3));
            sums[0] += mp.pixels[i][c], sums[1] += ms.pixels[i][c], sums[2] += su.pixels[i][c];
        }
    EXPECT_LT(worst, 1e-5) << "media_primary + media_secondary + surface != beauty";
    // The default scene has all three: fog seen directly, fog seen in its mirror, lit walls.
    for (double s : sums) EXPECT_GT(s, 0.0);
    EXPECT_GT(sums[1], 1e-3 * sums[0]);
    // PNG output is the beauty image only.
    r = runTyndall("render " + kSmall + " --passes 2 -q --aov -o " + out("aov.png"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(tyndall::readImageChannels(out("aov.png")).size(), 3u);
}

TEST(Aov, VarianceLayerIsTheVarianceOfTheRunningMean) {
    // Passes 1, 3, 8 at one pixel: mean 4, unbiased sample variance 13, of the mean 13 / 3.
    tyndall::LayerAccumulator acc(2, 1, true);
    for (float v : {1.0f, 3.0f, 8.0f}) {
        tyndall::Image img(2, 1), zero(2, 1);
        img.pixels[0] = tyndall::Rgb(v, 2 * v, 0);
        img.pixels[1] = tyndall::Rgb(5);
        acc.addPass(img, img, zero, zero);
    }
    tyndall::ImageLayers layers = acc.imageLayers();
    ASSERT_EQ(layers.back().first, "variance");
    const tyndall::Image& var = layers.back().second;
    EXPECT_NEAR(var.pixels[0].r, 13.0 / 3.0, 1e-6);
    EXPECT_NEAR(var.pixels[0].g, 4 * 13.0 / 3.0, 1e-5);
    EXPECT_EQ(var.pixels[0].b, 0.0f);
    EXPECT_NEAR(var.pixels[1].r, 0.0, 1e-6) << "a constant pixel has no variance";
}

TEST(Convergence, CsvHasOneRowPerPassAndReachesZeroAgainstItself) {
    // The reference is the same render: the last row's error must be (float-rounding) zero and
    // the first row's must not, and the beam radius must shrink.
    const std::string ref = out("conv_ref.exr"), csv = out("conv.csv");
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 10 -q -o " + ref).exitCode, 0);
    auto r = runTyndall("render " + kSmall + " --passes 10 -q -o " + out("conv.exr") + " --reference " + ref +
                        " --convergence " + csv);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "pass,elapsed_s,photon_paths,beam_radius,rel_rmse,bias");
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::vector<double> row;
        std::istringstream s(line);
        for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
        ASSERT_EQ(row.size(), 6u) << line;
        rows.push_back(row);
    }
    ASSERT_EQ(rows.size(), 10u);
    for (size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(rows[i][0], double(i + 1));
        EXPECT_EQ(rows[i][2], 400.0 * (i + 1));
        if (i > 0) {
            EXPECT_LT(rows[i][3], rows[i - 1][3]) << "beam radius must shrink";
            EXPECT_GE(rows[i][1], rows[i - 1][1]);
        }
    }
    EXPECT_GT(rows[0][4], 0.05);
    EXPECT_LT(rows[9][4], 1e-6);
    EXPECT_LT(std::abs(rows[9][5]), 1e-6);
    // A reference of another size is one clear error.
    r = runTyndall("render --size 40x30 --photons 400 --gpu off --passes 1 -q -o " + out("x.png") + " --reference " +
                   ref + " --convergence " + csv);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("48x36"), std::string::npos) << r.output;
}

// --- Bad samples ----------------------------------------------------------------------------

TEST(BadSamples, PlantedNanSamplesAreLeftOutAndReportedAtTheEnd) {
    // TYNDALL_TEST_NAN_PIXEL makes the camera stage's radiance at one pixel NaN in every pass
    // (cpu/pass_renderer.cpp): the render must leave those samples out (the pixel is black, every
    // other pixel is the clean render's bit for bit), say so in one line at the end and record the
    // count in the EXR. Through the hybrid scheduler's loop and through the rounds (--aov).
    const int x = 5, y = 7, passes = 4;
    const std::string clean = out("nan_clean.exr"), planted = out("nan_planted.exr");
    auto r = runTyndall("render " + kSmall + " --passes 4 -q -o " + clean);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("NaN"), std::string::npos) << "a clean render reports nothing:\n" << r.output;
    EXPECT_EQ(tyndall::readImageAttribute(clean, "tyndall:rejected_samples"), "0");
    for (const std::string aov : {"", " --aov"}) {
        r = runTyndall("render " + kSmall + " --passes 4 -q" + aov + " -o " + planted, "TYNDALL_TEST_NAN_PIXEL=5,7");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("tyndall: warning: " + std::to_string(passes) +
                                " pixel samples were NaN or infinite and were left out"),
                  std::string::npos)
            << aov << "\n" << r.output;
        EXPECT_EQ(tyndall::readImageAttribute(planted, "tyndall:rejected_samples"), std::to_string(passes)) << aov;
        tyndall::Image a = tyndall::readImageLayer(planted, ""), b = tyndall::readImage(clean);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_GT(b.at(x, y).r + b.at(x, y).g + b.at(x, y).b, 0.0f) << "the planted pixel is lit in the clean render";
        size_t differing = 0;
        for (int j = 0; j < a.height; ++j)
            for (int i = 0; i < a.width; ++i)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(a.at(i, j)[c])) << aov << " pixel " << i << "," << j;
                    if (i == x && j == y)
                        EXPECT_EQ(a.at(i, j)[c], 0.0f) << aov << ": a left-out sample counts as black";
                    else
                        differing += a.at(i, j)[c] != b.at(i, j)[c];
                }
        EXPECT_EQ(differing, 0u) << aov << ": only the planted pixel may differ";
    }
}

// --- Open MPI --------------------------------------------------------------------------------

bool haveMpirun() {
    return std::system("command -v mpirun > /dev/null 2>&1") == 0;
}
tyndall::test::CliRun runMpi(int ranks, const std::string& args) {
    std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                      "mpirun -np " + std::to_string(ranks) + " --oversubscribe " + TYNDALL_BINARY + " " + args + " 2>&1";
    tyndall::test::CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
    int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

TEST(Mpi, TwoRanksEqualOneProcessBitForBit) {
    if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed (openmpi-bin)";
    const std::string single = out("mpi_single.exr"), two = out("mpi_two.exr");
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 7 --aov -q -o " + single).exitCode, 0);
    auto r = runMpi(2, "render " + kSmall + " --passes 7 --aov --threads 1 -q -o " + two);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "only rank 0 prints:\n" << r.output;
    EXPECT_NE(r.output.find("2 ranks"), std::string::npos) << r.output;
    EXPECT_EQ(tyndall::readImageAttribute(two, "tyndall:ranks"), "2");
    EXPECT_EQ(tyndall::readImageAttribute(single, "tyndall:ranks"), "1");
    EXPECT_EQ(tyndall::readImageAttribute(two, "tyndall:passes"), "7");
    for (const char* layer : {"", "media_primary", "media_secondary", "surface", "variance"})
        EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImageLayer(two, layer), tyndall::readImageLayer(single, layer)))
            << "layer '" << layer << "'";
}

TEST(Mpi, TimeBudgetRanksAgreeOnOnePassCount) {
    if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed (openmpi-bin)";
    const std::string two = out("mpi_time.exr"), single = out("mpi_time_single.exr");
    // One plan for both (a --time render plans the open-ended horizon, --passes N plans N passes).
    auto r = runMpi(2, "render " + kSmall + " --time 1 --planned-paths 20000 --threads 1 -q -o " + two);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string passes = tyndall::readImageAttribute(two, "tyndall:passes");
    ASSERT_FALSE(passes.empty());
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes " + passes + " --planned-paths 20000 -q -o " + single).exitCode, 0);
    EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(two), tyndall::readImage(single)))
        << "the 2-rank --time render is not the single-process render of its " << passes << " passes";
}

TEST(Mpi, CheckpointUnderMpiResumesInOneProcess) {
    if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed (openmpi-bin)";
    const std::string ck = out("mpi.ckpt"), full = out("mpi_full.exr"), resumed = out("mpi_resumed.exr");
    fs::remove(ck);
    // The 5-pass part plans for the 9 passes it is resumed to (the radii come from the checkpoint).
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 9 -q -o " + full).exitCode, 0);
    auto r = runMpi(2, "render " + kSmall + " --passes 5 --planned-paths 3600 --threads 1 -q -o " + out("mpi_part.exr") +
                           " --checkpoint " + ck);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = runTyndall("render --resume " + ck + " --passes 9 -q -o " + resumed);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(resumed), tyndall::readImage(full)));
}

// --- --gpu on with layers, under MPI, and when GL fails -------------------------------------

/// `tyndall render --gpu on` works here (an OpenGL context, llvmpipe counts).
bool haveGl() {
    static const bool gl = runTyndall("render --size 8x8 --passes 1 --photons 10 --gpu on -q -o " + out("gl_probe.exr"))
                               .exitCode == 0;
    return gl;
}

TEST(Aov, GpuOnSplatsTheMediaPrimaryLayer) {
    if (!haveGl()) GTEST_SKIP() << "no OpenGL context";
    const std::string plain = out("gl_beauty.exr"), aov = out("gl_aov.exr"), cpu = out("gl_cpu_aov.exr");
    // Equiangular sampling on: its single scattering along the primary segments is the CPU's share
    // of media_primary, which the hybrid pass adds to the splat's.
    const std::string gl = "--size 48x36 --photons 400 --passes 4 -q --gpu on --equiangular on";
    auto r = runTyndall("render " + gl + " --aov -o " + aov);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("hybrid"), std::string::npos) << r.output;
    ASSERT_EQ(runTyndall("render " + gl + " -o " + plain).exitCode, 0);
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 4 -q --equiangular on --aov -o " + cpu).exitCode, 0);
    tyndall::Image beauty = tyndall::readImageLayer(aov, "");
    EXPECT_TRUE(tyndall::test::identicalImages(beauty, tyndall::readImage(plain))) << "--aov changed the GL beauty";
    for (const char* layer : {"", "media_primary", "media_secondary", "surface"}) {
        const double rms = tyndall::test::relativeRms(tyndall::readImageLayer(aov, layer), tyndall::readImageLayer(cpu, layer));
        EXPECT_LT(rms, tyndall::test::kGlCpuParity) << "layer '" << layer << "' against --gpu off";
    }
}

TEST(Mpi, GpuOnTwoRanksEqualOneProcess) {
    if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed (openmpi-bin)";
    if (!haveGl()) GTEST_SKIP() << "no OpenGL context";
    const std::string single = out("mpi_gl_single.exr"), two = out("mpi_gl_two.exr");
    const std::string gl = "--size 48x36 --photons 400 --passes 5 --aov -q --gpu on";
    ASSERT_EQ(runTyndall("render " + gl + " -o " + single).exitCode, 0);
    auto r = runMpi(2, "render " + gl + " --threads 1 -o " + two);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 ranks, hybrid"), std::string::npos) << r.output;
    for (const char* layer : {"", "media_primary", "media_secondary", "surface"})
        EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImageLayer(two, layer), tyndall::readImageLayer(single, layer)))
            << "layer '" << layer << "'";
}

TEST(GlFailure, RenderFinishesOnTheCpuWithOneLine) {
    // TYNDALL_TEST_GL_FAIL_AFTER_PASS=2: the GL splat of pass 3 on fails as a lost context would.
    if (!haveGl()) GTEST_SKIP() << "no OpenGL context";
    const std::string failed = out("gl_failed.exr"), cpu = out("gl_failed_cpu.exr");
    auto r = runTyndall("render --size 48x36 --photons 400 --passes 6 --gpu on -q -o " + failed,
                        "TYNDALL_TEST_GL_FAIL_AFTER_PASS=2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 2) << "one notice and the summary:\n" << r.output;
    EXPECT_NE(r.output.find("tyndall: warning: the GL splat failed at pass 3"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("6 passes"), std::string::npos) << r.output;
    ASSERT_EQ(runTyndall("render " + kSmall + " --passes 6 -q -o " + cpu).exitCode, 0);
    EXPECT_LT(tyndall::test::relativeRms(tyndall::readImage(failed), tyndall::readImage(cpu)), tyndall::test::kGlCpuParity);
}

}  // namespace
