// The command line as a user meets it: `--help` lists every option with its default, bad values
// give one line naming the option or file and a non-zero exit, renders are reproducible, the EXR
// header carries the settings that reproduce it, and `--passes 8` is exactly the first 8 passes of
// `--passes 16`.
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "core/accumulator.h"
#include "loading/default_scene.h"
#include "core/error.h"
#include "core/image_io.h"
#include "cpu/pass_renderer.h"
#include "gpu/gl_context.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::CliRun;
using tyndall::test::runTyndall;

int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

/// One entry of a command's "Options:" help section.
struct HelpOption {
    std::string opts;         ///< the left column: "--passes UINT=64 Excludes: --time"
    std::string description;  ///< the right column (continued on the next line for long names)
    bool takesValue = false;  ///< a TYPE follows the names (flags have none)
    bool hasDefault = false;  ///< "TYPE=value" or "(default: ...)" in the description
};

/// The options of CLI11 help text, keyed by their longest name ("--output" for "-o,--output").
std::map<std::string, HelpOption> parseHelpOptions(const std::string& help) {
    std::map<std::string, HelpOption> out;
    std::istringstream in(help);
    std::string line;
    bool inOptions = false;
    HelpOption* last = nullptr;
    static const std::regex kEntry(R"(^\s+(-\S+)((?: \S+)*)(?:\s{2,}(.*))?$)");
    static const std::regex kType(R"(^ ([A-Z]+)(=\S+)?)");
    while (std::getline(in, line)) {
        if (!line.empty() && line[0] != ' ') {  // a section header
            inOptions = line.rfind("Options:", 0) == 0;
            last = nullptr;
            continue;
        }
        if (!inOptions) continue;
        std::smatch m;
        if (std::regex_match(line, m, kEntry)) {
            std::string names = m[1];
            std::string key = names.substr(names.rfind(',') == std::string::npos ? 0 : names.rfind(',') + 1);
            HelpOption& o = out[key];
            o.opts = names + std::string(m[2]);
            o.description = m[3];
            std::string rest = m[2];
            std::smatch t;
            if (std::regex_search(rest, t, kType)) {
                o.takesValue = true;
                o.hasDefault = t[2].matched;
            }
            last = &o;
        } else if (last && line.find_first_not_of(' ') != std::string::npos) {
            last->description += " " + line.substr(line.find_first_not_of(' '));
        }
    }
    for (auto& [key, o] : out) o.hasDefault |= o.description.find("(default: ") != std::string::npos;
    return out;
}

/// The OpenGL the `tyndall` binary will find: a context made here, on the same machine.
enum class GlKind { None, Software, Hardware };
GlKind glKind() {
    try {
        return tyndall::GlContext::create()->isSoftware() ? GlKind::Software : GlKind::Hardware;
    } catch (const tyndall::Error&) {
        return GlKind::None;
    }
}

tyndall::Image renderPasses(const tyndall::PassRenderer& renderer, uint64_t first, uint64_t count) {
    tyndall::Accumulator acc(renderer.settings().width, renderer.settings().height);
    for (uint64_t p = first; p < first + count; ++p) acc.addPass(renderer.renderPass(p));
    return acc.mean();
}

}  // namespace

TEST(Cli, HelpListsEveryOptionWithDefaults) {
    CliRun top = runTyndall("--help");
    EXPECT_EQ(top.exitCode, 0);
    for (const char* command : {"render", "reference", "bench", "compare"})
        EXPECT_NE(top.output.find(command), std::string::npos) << command;

    // Every option of every command, each with its default ("TYPE=value" or "(default: ...)")
    // unless it is a flag; nothing listed that is not expected here.
    const std::vector<std::string> scene = {"--camera", "--environment", "--size", "--seed", "--threads",
                                            "--load-memory"};
    const std::vector<std::string> output = {"--output", "--exposure"};
    const std::vector<std::string> ppb = {"--passes", "--time",           "--photons",       "--alpha",
                                          "--radius", "--surface-radius", "--radius-offset", "--planned-paths",
                                          "--photon-angle", "--free-flights", "--memory", "--simd", "--direct-light",
                                          "--surface-boundary", "--equiangular", "--equiangular-samples",
                                          "--film-light-sampling", "--photon-planes", "--scattered-beam-mfp", "--medium-points",
                                          "--indirect-photon-spread"};
    auto join = [](std::initializer_list<std::vector<std::string>> parts) {
        std::set<std::string> all = {"--help", "--help-all"};
        for (const auto& p : parts) all.insert(p.begin(), p.end());
        return all;
    };
    const std::map<std::string, std::set<std::string>> expected = {
        {"render", join({scene, output, ppb,
                         {"--gpu", "--checkpoint", "--checkpoint-every", "--resume", "--quiet", "--progress-every", "--aov",
                          "--reference", "--convergence", "--max-path-length", "--region", "--transparent"}})},
        {"reference", join({scene, output, {"--spp", "--max-depth", "--max-path-length", "--no-nee", "--transparent"}})},
        {"bench", join({scene, {"--passes", "--photons", "--no-hybrid", "--radius", "--radius-offset", "--simd",
                            "--direct-light", "--surface-boundary", "--equiangular", "--equiangular-samples",
                            "--film-light-sampling", "--photon-planes", "--scattered-beam-mfp", "--medium-points",
                            "--indirect-photon-spread"}})},
        {"compare", join({scene, output, ppb, {"--gpu", "--density", "--twin"}})}};
    for (const auto& [command, names] : expected) {
        CliRun r = runTyndall(command + " --help");
        EXPECT_EQ(r.exitCode, 0) << command;
        std::map<std::string, HelpOption> options = parseHelpOptions(r.output);
        std::set<std::string> listed;
        for (const auto& [name, o] : options) {
            listed.insert(name);
            if (o.takesValue) {
                EXPECT_TRUE(o.hasDefault) << command << " " << o.opts << ": no default in '" << o.description << "'";
            }
        }
        EXPECT_EQ(listed, names) << command << " --help:\n" << r.output;
    }

    CliRun r = runTyndall("render --help");
    for (const char* opt : {"--passes UINT=64", "--photons UINT=4000", "--alpha FLOAT=0.5", "--radius FLOAT=0",
                            "--radius-offset UINT ", "(default: automatic, so the beam radius ends", "--free-flights INT=4", "--seed UINT=1", "--size TEXT=512x512",
                            "--threads INT=0", "-o,--output TEXT=tyndall.png", "--exposure FLOAT=1", "--gpu TEXT=auto",
                            "(default: off, --passes decides)"})
        EXPECT_NE(r.output.find(opt), std::string::npos) << opt << " missing from:\n" << r.output;
    CliRun b = runTyndall("bench --help");
    for (const char* opt : {"--passes INT=10", "--photons UINT=1000"})
        EXPECT_NE(b.output.find(opt), std::string::npos) << opt << " missing from:\n" << b.output;
}

// `tyndall bench` describes the user's machine: the stages' throughput and the hybrid split (or
// why it was skipped), every figure a number, nothing judged against targets.
TEST(Cli, BenchReportsStagesAndTheHybridSplit) {
    CliRun r = runTyndall("bench --size 32x32 --passes 2 --photons 200 --threads 2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* line : {"photon tracing", "photon paths", "beams per photon path", "mean beam length", "full passes", "camera paths", "  photon stage",
                             "  camera stage", "  primary splat stage", "  CPU time per pass", "hybrid"})
        EXPECT_NE(r.output.find(line), std::string::npos) << line << " missing from:\n" << r.output;
    const bool hybridRan = r.output.find("hybrid loop") != std::string::npos;
    EXPECT_TRUE(hybridRan || r.output.find("hybrid: skipped (") != std::string::npos) << r.output;
    for (const char* word : {"target", ": met", "NOT met", "issue", " nan", " inf"})
        EXPECT_EQ(r.output.find(word), std::string::npos) << "'" << word << "' in:\n" << r.output;
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
                                           {"render --time 0 -o " + out, "--time"},
                                           {"render --time -2 -o " + out, "--time"},
                                           {"render --time nan -o " + out, "--time"},
                                           {"compare --time 0 -o " + out, "--time"},
                                           {"bench --passes 0", "--passes"},
                                           {"bench --passes -4", "--passes"},
                                           {"bench --photons 0", "--photons"},
                                           {"bench --photons many", "--photons"},
                                           {"render --direct-light maybe -o " + out, "--direct-light"},
                                           {"render --surface-boundary maybe -o " + out, "--surface-boundary"},
                                           {"render --size 64x48 --region 60 40 10 10 -o " + out, "--region"},
                                           {"render --region 1 2 3 -o " + out, "--region"},
                                           {"render --region 1 2 0 4 -o " + out, "--region"},
                                           {"render --frobnicate", "--frobnicate"}}) {
        CliRun r = runTyndall(c.args);
        EXPECT_NE(r.exitCode, 0) << c.args;
        EXPECT_EQ(lineCount(r.output), 1) << c.args << " printed:\n" << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << " printed:\n" << r.output;
        EXPECT_EQ(r.output.rfind("tyndall: ", 0), 0u) << r.output;
    }
}

TEST(Cli, RendersAreReproducibleAcrossThreadCounts) {
    const std::string a = tyndall::test::outputDir() + "/cli_t1.exr", b = tyndall::test::outputDir() + "/cli_t2.exr";
    CliRun r1 = runTyndall("render --passes 3 --photons 200 --size 48x32 --threads 1 -o " + a);
    CliRun r2 = runTyndall("render --passes 3 --photons 200 --size 48x32 --threads 2 -o " + b);
    ASSERT_EQ(r1.exitCode, 0) << r1.output;
    ASSERT_EQ(r2.exitCode, 0) << r2.output;
    EXPECT_NE(r1.output.find("3 passes, 600 photon paths"), std::string::npos) << r1.output;
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
    CliRun off = runTyndall(common + "off");
    ASSERT_EQ(off.exitCode, 0) << off.output;
    EXPECT_NE(off.output.find("passes/s, CPU)"), std::string::npos) << off.output;
    EXPECT_EQ(lineCount(off.output), 1) << off.output;

    // What on and auto do depends on the OpenGL this machine has: none, a software rasterizer
    // (llvmpipe: auto stays on the CPU and says why in one line) or a hardware GPU (auto splats).
    const GlKind gl = glKind();
    std::printf("OpenGL here: %s\n", gl == GlKind::None ? "none" : gl == GlKind::Software ? "software" : "hardware");
    CliRun on = runTyndall(common + "on");
    CliRun automatic = runTyndall(common + "auto");
    ASSERT_EQ(automatic.exitCode, 0) << automatic.output;
    if (gl == GlKind::None) {
        EXPECT_NE(on.exitCode, 0) << on.output;
        EXPECT_EQ(lineCount(on.output), 1) << on.output;
        EXPECT_NE(on.output.find("--gpu on"), std::string::npos) << on.output;
    } else {
        ASSERT_EQ(on.exitCode, 0) << on.output;
        EXPECT_NE(on.output.find("hybrid, "), std::string::npos) << on.output;
        EXPECT_EQ(lineCount(on.output), 1) << on.output;
    }
    if (gl == GlKind::Hardware) {
        EXPECT_NE(automatic.output.find("hybrid, "), std::string::npos) << automatic.output;
        EXPECT_EQ(lineCount(automatic.output), 1) << automatic.output;
    } else {
        EXPECT_NE(automatic.output.find("tyndall: --gpu auto: rendering on the CPU"), std::string::npos)
            << automatic.output;
        EXPECT_NE(automatic.output.find("passes/s, CPU)"), std::string::npos) << automatic.output;
        EXPECT_EQ(lineCount(automatic.output), 2) << automatic.output;
    }
    CliRun bad = runTyndall(common + "sometimes");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_EQ(lineCount(bad.output), 1) << bad.output;
    EXPECT_NE(bad.output.find("--gpu"), std::string::npos) << bad.output;
}

TEST(Cli, WithoutAnyGlLibraryAutoFallsBackAndOnFails) {
    // libEGL and libOSMesa are loaded at run time: hide both and the program still renders on
    // the CPU (auto, with one line saying why) or fails clearly (on).
    const std::string noGl =
        "TYNDALL_EGL_LIBRARY=/nonexistent/libEGL.so.1 TYNDALL_OSMESA_LIBRARY=/nonexistent/libOSMesa.so.8";
    const std::string out = tyndall::test::outputDir() + "/cli_nogl.png";
    const std::string common = "render --passes 1 --photons 100 --size 24x16 -o " + out + " --gpu ";
    CliRun automatic = runTyndall(common + "auto", noGl);
    ASSERT_EQ(automatic.exitCode, 0) << automatic.output;
    EXPECT_EQ(lineCount(automatic.output), 2) << automatic.output;
    EXPECT_NE(automatic.output.find("tyndall: --gpu auto: rendering on the CPU: no OpenGL 4.5 core context"),
              std::string::npos)
        << automatic.output;
    EXPECT_NE(automatic.output.find("/nonexistent/libEGL.so.1 not found"), std::string::npos) << automatic.output;
    EXPECT_NE(automatic.output.find("/nonexistent/libOSMesa.so.8 not found"), std::string::npos) << automatic.output;
    EXPECT_NE(automatic.output.find("passes/s, CPU)"), std::string::npos) << automatic.output;

    CliRun on = runTyndall(common + "on", noGl);
    EXPECT_EQ(on.exitCode, 1) << on.output;
    EXPECT_EQ(lineCount(on.output), 1) << on.output;
    EXPECT_NE(on.output.find("tyndall: --gpu on: no OpenGL 4.5 core context"), std::string::npos) << on.output;

    CliRun off = runTyndall(common + "off", noGl);
    EXPECT_EQ(off.exitCode, 0) << off.output;
    EXPECT_EQ(lineCount(off.output), 1) << off.output;
}

TEST(Cli, RenderRegionHasTheWholeImagesPixelsThereAndZeroElsewhere) {
    const std::string dir = tyndall::test::outputDir() + "/";
    const std::string common = "render --gpu off --passes 2 --photons 300 --size 64x48 --seed 9 -o ";
    CliRun whole = runTyndall(common + dir + "cli_region_whole.exr");
    CliRun part = runTyndall(common + dir + "cli_region_part.exr --region 10 7 30 20");
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    ASSERT_EQ(part.exitCode, 0) << part.output;
    tyndall::Image a = tyndall::readImage(dir + "cli_region_whole.exr"), b = tyndall::readImage(dir + "cli_region_part.exr");
    ASSERT_EQ(b.width, 64);
    ASSERT_EQ(b.height, 48);
    int different = 0, outsideLit = 0, insideLit = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            bool inside = x >= 10 && x < 40 && y >= 7 && y < 27;
            const tyndall::Rgb &p = a.at(x, y), &q = b.at(x, y);
            if (inside) different += p.r != q.r || p.g != q.g || p.b != q.b, insideLit += !q.isBlack();
            else outsideLit += !q.isBlack();
        }
    EXPECT_EQ(different, 0);
    EXPECT_EQ(outsideLit, 0);
    EXPECT_GT(insideLit, 300);
    nlohmann::json settings =
        nlohmann::json::parse(tyndall::readImageAttribute(dir + "cli_region_part.exr", "tyndall:settings"));
    EXPECT_EQ(settings.at("region"), nlohmann::json({10, 7, 30, 20}));
    EXPECT_EQ(nlohmann::json::parse(tyndall::readImageAttribute(dir + "cli_region_whole.exr", "tyndall:settings"))
                  .count("region"),
              0u);
}

TEST(Cli, ExrMetadataHoldsTheSettingsThatMadeIt) {
    using tyndall::readImageAttribute;
    const std::string out = tyndall::test::outputDir() + "/cli_metadata.exr";
    CliRun r = runTyndall(
        "render --passes 3 --photons 150 --size 20x12 --seed 42 --alpha 0.3 --radius 0.02 --gpu off -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImageAttribute(out, "Software"), "tyndall");
    EXPECT_EQ(readImageAttribute(out, "tyndall:scene"), "<built-in default scene>");
    EXPECT_EQ(readImageAttribute(out, "tyndall:passes"), "3");
    EXPECT_EQ(readImageAttribute(out, "tyndall:photon_paths"), "450");
    EXPECT_EQ(readImageAttribute(out, "tyndall:no_such_key"), "");
    nlohmann::json settings = nlohmann::json::parse(readImageAttribute(out, "tyndall:settings"));
    EXPECT_EQ(settings.at("seed"), 42);
    EXPECT_DOUBLE_EQ(settings.at("alpha").get<double>(), 0.3);
    EXPECT_EQ(settings.at("passes"), 3);
    EXPECT_EQ(settings.at("photons"), 150);
    EXPECT_EQ(settings.at("width"), 20);
    EXPECT_EQ(settings.at("height"), 12);
    EXPECT_FLOAT_EQ(settings.at("radius").get<float>(), 0.02f);
    EXPECT_FLOAT_EQ(settings.at("resolved_radius").get<float>(), 0.02f);
    EXPECT_GT(settings.at("resolved_surface_radius").get<double>(), 0.0) << "0 = automatic, resolved to the scene";
    EXPECT_EQ(settings.at("gpu"), "off");
    // The settings in the header are render settings (what a scene file's render block takes).
    settings.erase("resolved_radius");
    settings.erase("resolved_surface_radius");
    tyndall::RenderSettings parsed = tyndall::RenderSettings::fromJson(settings, out);
    EXPECT_EQ(parsed.seed, 42u);
    EXPECT_EQ(parsed.photonsPerPass, 150u);

    const std::string ref = tyndall::test::outputDir() + "/cli_metadata_reference.exr";
    CliRun rr = runTyndall("reference --spp 2 --max-depth 3 --size 12x8 --seed 5 -o " + ref);
    ASSERT_EQ(rr.exitCode, 0) << rr.output;
    EXPECT_EQ(readImageAttribute(ref, "Software"), "tyndall");
    EXPECT_EQ(readImageAttribute(ref, "tyndall:renderer"), "reference");
    EXPECT_EQ(readImageAttribute(ref, "tyndall:scene"), "<built-in default scene>");
    EXPECT_EQ(readImageAttribute(ref, "tyndall:spp"), "2");
    nlohmann::json rs = nlohmann::json::parse(readImageAttribute(ref, "tyndall:reference_settings"));
    EXPECT_EQ(rs.at("seed"), 5);
    EXPECT_EQ(rs.at("spp"), 2);
    EXPECT_EQ(rs.at("max_depth"), 3);
    EXPECT_EQ(rs.at("width"), 12);
    EXPECT_EQ(rs.at("height"), 8);
    EXPECT_EQ(rs.at("nee"), true);
    EXPECT_EQ(readImageAttribute(ref, "tyndall:settings"), "") << "the PPB settings do not describe a reference image";
}

TEST(Cli, FewerPassesAreExactlyTheFirstPassesOfMore) {
    // The binary's --passes 8 and --passes 16 images against the library's passes 0..7 and 0..15,
    // rebuilt from the settings in the 16-pass image's header: bit for bit (a pass is a pure
    // function of its index, and the render loop adds passes 0, 1, 2, ... in order), so the
    // 16-pass mean is (8 mean8 + 8 mean(passes 8..15)) / 16 up to float rounding.
    const std::string dir = tyndall::test::outputDir();
    // The automatic radii plan for the budget, so both renders are given the same plan.
    const std::string common = "render --photons 200 --size 40x24 --seed 9 --gpu off --planned-paths 3200 ";
    CliRun r8 = runTyndall(common + "--passes 8 --threads 1 -o " + dir + "/cli_prefix8.exr");
    CliRun r16 = runTyndall(common + "--passes 16 --threads 2 -o " + dir + "/cli_prefix16.exr");
    ASSERT_EQ(r8.exitCode, 0) << r8.output;
    ASSERT_EQ(r16.exitCode, 0) << r16.output;
    tyndall::Image m8 = tyndall::readImage(dir + "/cli_prefix8.exr"),
                   m16 = tyndall::readImage(dir + "/cli_prefix16.exr");

    nlohmann::json j =
        nlohmann::json::parse(tyndall::readImageAttribute(dir + "/cli_prefix16.exr", "tyndall:settings"));
    j.erase("resolved_radius");
    j.erase("resolved_surface_radius");
    tyndall::RenderSettings s = tyndall::RenderSettings::fromJson(j, "cli_prefix16.exr");
    tyndall::Scene scene = tyndall::makeDefaultScene();
    scene.validate();
    tyndall::PassRenderer renderer(scene, s);
    tyndall::Image first8 = renderPasses(renderer, 0, 8), all16 = renderPasses(renderer, 0, 16);
    tyndall::Image last8 = renderPasses(renderer, 8, 8);
    EXPECT_TRUE(tyndall::test::identicalImages(m8, first8)) << "--passes 8 is not passes 0..7";
    EXPECT_TRUE(tyndall::test::identicalImages(m16, all16)) << "--passes 16 is not passes 0..15";
    double maxErr = 0, sum = 0, diff = 0;
    for (size_t i = 0; i < m16.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double split = (8.0 * m8.pixels[i][c] + 8.0 * last8.pixels[i][c]) / 16.0;
            maxErr = std::max(maxErr, std::abs(split - m16.pixels[i][c]) / std::max(1e-6, std::abs(split)));
            sum += m16.pixels[i][c];
            diff += std::abs(m8.pixels[i][c] - last8.pixels[i][c]);
        }
    EXPECT_LT(maxErr, 1e-6) << "16-pass mean vs (8 mean8 + 8 mean(8..15)) / 16";
    EXPECT_GT(sum, 0.0);
    EXPECT_GT(diff, 0.0) << "passes 8..15 should differ from passes 0..7";
}

namespace {
/// The settings recorded in an EXR's header, as render options.
nlohmann::json recordedSettings(const std::string& exr) {
    nlohmann::json j = nlohmann::json::parse(tyndall::readImageAttribute(exr, "tyndall:settings"));
    j.erase("resolved_radius");
    j.erase("resolved_surface_radius");
    return j;
}
std::string number(const nlohmann::json& v) {
    return v.dump();  // nlohmann prints the shortest text that reads back to the same number
}
}  // namespace

TEST(Cli, AutomaticRadiiAreRecordedAsPlainSettingsThatReproduceTheImage) {
    // Defaults: the radii and the schedule are chosen from the camera and the budget, and written
    // into the header as plain numbers; rendering with those numbers given explicitly (and no
    // budget to plan from: a different pass count) gives the same passes bit for bit.
    const std::string dir = tyndall::test::outputDir();
    CliRun a = runTyndall("render --photons 300 --size 40x24 --seed 3 --gpu off --passes 6 -o " + dir + "/cli_auto.exr");
    ASSERT_EQ(a.exitCode, 0) << a.output;
    nlohmann::json j = recordedSettings(dir + "/cli_auto.exr");
    ASSERT_TRUE(j.at("radius_offset").is_number_integer()) << j.dump();
    EXPECT_GT(j.at("radius").get<double>(), 0.0);
    EXPECT_GT(j.at("surface_radius").get<double>(), 0.0);
    EXPECT_EQ(j.at("planned_paths"), 1800);
    CliRun b = runTyndall("render --photons 300 --size 40x24 --seed 3 --gpu off --passes 6 --radius " +
                          number(j.at("radius")) + " --surface-radius " + number(j.at("surface_radius")) +
                          " --radius-offset " + number(j.at("radius_offset")) + " --alpha " + number(j.at("alpha")) +
                          " -o " + dir + "/cli_auto_replay.exr");
    ASSERT_EQ(b.exitCode, 0) << b.output;
    EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(dir + "/cli_auto.exr"),
                                               tyndall::readImage(dir + "/cli_auto_replay.exr")));
}

/// An on/off option goes into the header as `key`; the recorded settings reproduce each mode's
/// image bit for bit, and the two modes' images differ (the default scene, 3 passes).
void expectSwitchRecordedAndReplays(const std::string& option, const std::string& key) {
    const std::string dir = tyndall::test::outputDir();
    for (const std::string mode : {"on", "off"}) {
        const std::string out = dir + "/cli_" + key + "_" + mode + ".exr";
        CliRun r = runTyndall("render --photons 300 --size 40x24 --seed 5 --gpu off --passes 3 " + option + " " + mode +
                              " -o " + out);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        nlohmann::json j = recordedSettings(out);
        EXPECT_EQ(j.at(key), mode);
        tyndall::RenderSettings s = tyndall::RenderSettings::fromJson(j, out);
        tyndall::Scene scene = tyndall::makeDefaultScene();
        scene.validate();
        tyndall::PassRenderer renderer(scene, s);
        EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(out), renderPasses(renderer, 0, s.passes))) << mode;
    }
    EXPECT_FALSE(tyndall::test::identicalImages(tyndall::readImage(dir + "/cli_" + key + "_on.exr"),
                                                tyndall::readImage(dir + "/cli_" + key + "_off.exr")));
}

TEST(Cli, EquiangularIsRecordedAndReplays) {
    // The default scene's fog is lit by a spot light, which equiangular sampling estimates.
    expectSwitchRecordedAndReplays("--equiangular", "equiangular");
}

TEST(Cli, DirectLightIsRecordedAndReplays) {
    // The default scene's walls get shadow rays with it on.
    expectSwitchRecordedAndReplays("--direct-light", "direct_light");
}

TEST(Cli, SurfaceBoundaryIsRecordedAndReplays) {
    // The default scene's walls meet at edges.
    expectSwitchRecordedAndReplays("--surface-boundary", "surface_boundary");
}

TEST(Cli, TimeBudgetRecordsItsPlanAndReplaysFromIt) {
    // --time plans the automatic radii for the open-ended horizon; the planned count goes into the
    // header, so the same settings with the recorded pass count reproduce the image bit for bit
    // whatever the machine's speed.
    const std::string dir = tyndall::test::outputDir();
    CliRun t = runTyndall("render --photons 200 --size 32x20 --seed 4 --gpu off --time 1 -o " + dir + "/cli_time.exr");
    ASSERT_EQ(t.exitCode, 0) << t.output;
    nlohmann::json j = recordedSettings(dir + "/cli_time.exr");
    EXPECT_GT(j.at("planned_paths").get<uint64_t>(), 0u);
    std::string passes = tyndall::readImageAttribute(dir + "/cli_time.exr", "tyndall:passes");
    j["time"] = 0.0;
    j["passes"] = std::stoull(passes);
    tyndall::RenderSettings s = tyndall::RenderSettings::fromJson(j, "cli_time.exr");
    tyndall::Scene scene = tyndall::makeDefaultScene();
    scene.validate();
    tyndall::PassRenderer renderer(scene, s);
    EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(dir + "/cli_time.exr"),
                                               renderPasses(renderer, 0, s.passes)));
}

// The transparent film through the binary: --transparent (EXR) and the render block's
// "transparent" (PNG) write an alpha channel: 0 where the environment is the background (no
// radiance there), 1 on a surface; tyndall reference --transparent alike.
TEST(Cli, TransparentFilmWritesAlpha) {
    const std::string dir = tyndall::test::outputDir();
    const std::string scene = dir + "/transparent_film.json";
    auto writeScene = [&](const std::string& render) {
        std::ofstream(scene) << R"({"name": "film", )" << render << R"(
          "environment": {"radiance": 1.5},
          "materials": [{"name": "card", "albedo": 0.5}],
          "shapes": [{"type": "quad", "name": "card", "material": "card",
                      "corner": [-2, -2, -3], "edge1": [2, 0, 0], "edge2": [0, 4, 0]}],
          "cameras": [{"position": [0, 0, 0], "target": [0, 0, -3], "fov": 40}]})";
    };
    auto readRgba = [](const std::string& path, std::vector<float>* px, int* w) {
        auto in = OIIO::ImageInput::open(path);
        if (!in) return 0;
        const OIIO::ImageSpec& spec = in->spec();
        *w = spec.width;
        px->resize(size_t(spec.width) * spec.height * spec.nchannels);
        in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px->data());
        return spec.nchannels == 4 && spec.alpha_channel == 3 ? 4 : -spec.nchannels;
    };
    writeScene("");
    const std::string exr = dir + "/transparent_film.exr", png = dir + "/transparent_film.png";
    CliRun r = runTyndall("render " + scene + " --transparent --size 16x16 --passes 2 --photons 100 --gpu off -o " + exr);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    writeScene(R"("render": {"transparent": "on"},)");
    CliRun p = runTyndall("render " + scene + " --size 16x16 --passes 2 --photons 100 --gpu off -o " + png);
    ASSERT_EQ(p.exitCode, 0) << p.output;
    const std::string ref = dir + "/transparent_film_reference.exr";
    CliRun q = runTyndall("reference " + scene + " --transparent --size 16x16 --spp 2 -o " + ref);
    ASSERT_EQ(q.exitCode, 0) << q.output;
    for (const std::string& path : {exr, png, ref}) {
        std::vector<float> px;
        int w = 0;
        ASSERT_EQ(readRgba(path, &px, &w), 4) << path << ": not RGBA";
        const float* card = &px[size_t(8 * w + 2) * 4];    // left: the card
        const float* empty = &px[size_t(8 * w + 13) * 4];  // right: the environment
        EXPECT_EQ(card[3], 1.0f) << path;
        EXPECT_GT(card[0], 0.0f) << path;
        EXPECT_EQ(empty[3], 0.0f) << path;
        EXPECT_EQ(empty[0], 0.0f) << path << ": the background is left out";
    }
    for (const std::string command : {"render --passes 1", "reference --spp 1"}) {
        CliRun bad = runTyndall(command + " " + scene + " --transparent --size 16x16 -o " + dir + "/film.jpg");
        EXPECT_NE(bad.exitCode, 0) << command;
        EXPECT_NE(bad.output.find("needs .exr, .png or .tif"), std::string::npos) << command << ": " << bad.output;
    }
}
