// The command line as a user meets it: `--help` lists every option with its default, bad values
// give one line naming the option or file and a non-zero exit, and renders are reproducible.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "core/image_io.h"
#include "tests/test_util.h"

namespace {

struct Result {
    int status = -1;
    std::string out;  // stdout and stderr together
};

Result run(const std::string& args) {
    std::string cmd = std::string(TYNDALL_BINARY) + " " + args + " 2>&1";
    Result r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
    int st = pclose(pipe);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace

TEST(Cli, HelpListsEveryOptionWithDefaults) {
    Result top = run("--help");
    EXPECT_EQ(top.status, 0);
    EXPECT_NE(top.out.find("render"), std::string::npos);
    EXPECT_NE(top.out.find("bench"), std::string::npos);
    Result r = run("render --help");
    EXPECT_EQ(r.status, 0);
    for (const char* opt : {"--passes UINT=64", "--time", "--photons UINT=1000", "--alpha FLOAT=0.5", "--radius FLOAT=0",
                            "--seed UINT=1", "--size TEXT=512x512", "--threads INT=0", "-o,--output TEXT=tyndall.png"})
        EXPECT_NE(r.out.find(opt), std::string::npos) << opt << " missing from:\n" << r.out;
}

TEST(Cli, BadValuesGiveOneLineNamingTheOption) {
    const std::string out = tyndall::test::outputDir() + "/cli_bad.png";
    struct Case {
        std::string args, needle;
    };
    for (const Case& c : std::vector<Case>{{"render --alpha 1.5 -o " + out, "--alpha"},
                                           {"render --alpha 0 -o " + out, "--alpha"},
                                           {"render --passes 0 -o " + out, "--passes"},
                                           {"render --photons 0 -o " + out, "--photons"},
                                           {"render --size 0x10 -o " + out, "--size"},
                                           {"render --size banana -o " + out, "--size"},
                                           {"render --passes -3 -o " + out, "--passes"},
                                           {"render --radius -1 -o " + out, "--radius"},
                                           {"render --threads -2 -o " + out, "--threads"},
                                           {"render --passes 2 --time 3 -o " + out, "--passes"},
                                           {"render no/such/scene.json -o " + out, "no/such/scene.json"},
                                           {"render --passes 1 -o /no/such/dir/out.png", "/no/such/dir/out.png"},
                                           {"render --passes 1 -o " + out + ".bmpx", "unknown image type"},
                                           {"render --frobnicate", "--frobnicate"}}) {
        Result r = run(c.args);
        EXPECT_NE(r.status, 0) << c.args;
        EXPECT_EQ(lineCount(r.out), 1) << c.args << " printed:\n" << r.out;
        EXPECT_NE(r.out.find(c.needle), std::string::npos) << c.args << " printed:\n" << r.out;
        EXPECT_EQ(r.out.rfind("tyndall: ", 0), 0u) << r.out;
    }
}

TEST(Cli, RendersAreReproducibleAcrossThreadCounts) {
    const std::string a = tyndall::test::outputDir() + "/cli_t1.exr", b = tyndall::test::outputDir() + "/cli_t2.exr";
    Result r1 = run("render --passes 3 --photons 200 --size 48x32 --threads 1 -o " + a);
    Result r2 = run("render --passes 3 --photons 200 --size 48x32 --threads 2 -o " + b);
    ASSERT_EQ(r1.status, 0) << r1.out;
    ASSERT_EQ(r2.status, 0) << r2.out;
    EXPECT_NE(r1.out.find("3 passes, 600 photon paths"), std::string::npos) << r1.out;
    tyndall::Image ia = tyndall::readImage(a), ib = tyndall::readImage(b);
    ASSERT_EQ(ia.pixels.size(), size_t(48 * 32));
    double sum = 0;
    for (size_t i = 0; i < ia.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(ia.pixels[i][c], ib.pixels[i][c]) << "pixel " << i;
            sum += ia.pixels[i][c];
        }
    EXPECT_GT(sum, 0.0);
}

TEST(Cli, GpuModes) {
    const std::string out = tyndall::test::outputDir() + "/cli_gpu.exr";
    const std::string common = "render --passes 2 --photons 200 --size 48x32 -o " + out + " --gpu ";
    Result off = run(common + "off");
    ASSERT_EQ(off.status, 0) << off.out;
    EXPECT_NE(off.out.find("passes/s, CPU)"), std::string::npos) << off.out;
    EXPECT_EQ(lineCount(off.out), 1) << off.out;
    Result on = run(common + "on");
    ASSERT_EQ(on.status, 0) << on.out;
    EXPECT_NE(on.out.find("hybrid, "), std::string::npos) << on.out;
    // Here OpenGL is llvmpipe: auto renders on the CPU and says why in one line.
    Result automatic = run(common + "auto");
    ASSERT_EQ(automatic.status, 0) << automatic.out;
    EXPECT_NE(automatic.out.find("tyndall: --gpu auto: rendering on the CPU"), std::string::npos) << automatic.out;
    EXPECT_EQ(lineCount(automatic.out), 2) << automatic.out;
    Result bad = run(common + "sometimes");
    EXPECT_NE(bad.status, 0);
    EXPECT_EQ(lineCount(bad.out), 1) << bad.out;
    EXPECT_NE(bad.out.find("--gpu"), std::string::npos) << bad.out;
}
