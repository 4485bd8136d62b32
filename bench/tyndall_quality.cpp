// build/bench/tyndall_quality: image error of several radius settings against cached path-traced
// references, at equal work or at equal CPU time (bench/quality_study.h says which rows and why),
// with the curves as CSV plus a gnuplot script (and the PNG gnuplot makes of it).
//   build/bench/tyndall_quality [--scene FILE:PASSES]... [--cpu-seconds S] [--library scenes]
//                               [--plot PREFIX] [--size WxH] [--photons N] [--seeds K] ...
#include <CLI/CLI.hpp>

#include <cstdio>

#include "app/cli_common.h"
#include "bench/quality_study.h"
#include "bench/study_cli.h"
#include "core/error.h"

namespace tyndall::bench {
namespace {

struct Options {
    app::CommonOptions common;
    QualityStudyOptions study;
};

void addOptions(CLI::App& cli, Options& o) {
    o.common.size = "256x256";
    o.common.settings.photonsPerPass = 4000;
    o.study.scenes = {"bench/scenes/fog-box.json:1584", "bench/scenes/walls-fog-box.json:421",
                      "bench/scenes/fog-lamp-box.json:1584"};
    cli.add_option("--scene", o.study.scenes,
                   "FILE:PASSES (or FILE with --cpu-seconds), repeatable (default: bench/scenes' fog box and fog box "
                   "with a lamp in view at 1584 passes and the box with walls at 421: 60 s at 256x256 on an idle "
                   "2-core machine)");
    cli.add_option("--size", o.common.size, "Image size WxH in pixels")->capture_default_str();
    cli.add_option("--photons", o.common.settings.photonsPerPass, "Photon paths per pass")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--seed", o.common.settings.seed, "First seed")->check(app::nonNegativeInteger())->capture_default_str();
    cli.add_option("--threads", o.common.settings.threads, "Worker threads (0 = all cores)")->capture_default_str();
    cli.add_option("--reference-dir", o.study.referenceDir, "The reference cache")->capture_default_str();
    cli.add_option("--reference-spp", o.study.referenceSpp, "Samples per pixel of a reference rendered when not cached")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--seeds", o.study.seeds, "Render each setting with this many seeds; errors are their root mean square")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--cpu-seconds", o.study.cpuSeconds,
                   "Equal time instead of equal work: every render stops when its passes' process CPU time reaches "
                   "this many seconds (117 = 60 s wall with 2 threads on an idle 2-core machine); --scene's :PASSES "
                   "is then optional and adds a row planned for it (default: 0, equal work)")
        ->check(CLI::NonNegativeNumber);
    cli.add_option("--library", o.study.library,
                   "With --cpu-seconds: also every scene file in this folder (scenes/), its mirrors and glass made "
                   "index-matched so that the path tracer is valid; replaces the default --scene list unless one is "
                   "given (default: none)");
    cli.add_option("--images", o.study.imageDir,
                   "Write every row's final image per seed, <dir>/<scene>-<row>-seed<N>.exr (default: none)");
    cli.add_option("--only", o.study.only,
                   "Only the scenes (of --scene and --library) whose file name without .json is this, repeatable "
                   "(default: all)");
    cli.add_flag("!--no-legacy", o.study.legacy, "Leave out the LEGACY row (default: with it)");
    cli.add_flag("!--no-switch-rows", o.study.switches,
                 "With --cpu-seconds: leave out the rows with --equiangular and --film-light-sampling switched "
                 "(default: with them)");
    cli.add_option("--equiangular-rows", o.study.equiangularSamples,
                   "With --cpu-seconds: one more row per value, --equiangular on with this many samples per segment "
                   "(0 = auto), repeatable (default: none)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxEquiangularSamples));
    cli.add_option("--scattered-beam-rows", o.study.scatteredBeamMfp,
                   "With --cpu-seconds: one more row per value, the beams after a scattering at least this many mean "
                   "free paths wide at the plan's end (--scattered-beam-mfp), repeatable (default: none)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxScatteredBeamMfp));
    cli.add_option("--medium-point-rows", o.study.mediumPointMfp,
                   "With --cpu-seconds: one more row per value, photon points in dense media with a radius of this "
                   "many mean free paths at the plan's end (--medium-points), repeatable (default: none)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxMediumPointMfp));
    cli.add_option("--indirect-photon-rows", o.study.indirectPhotonSpread,
                   "With --cpu-seconds: one more row per value, the surface photons whose light scattered "
                   "diffusely at least this many times their path length from that scattering wide at the plan's "
                   "end (--indirect-photon-spread), repeatable (default: none)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxIndirectPhotonSpread));
    cli.add_flag("--pilot-only", o.study.pilotOnly,
                 "Only print each scene's automatic equiangular pilot (what it measured, the count it chose)");
    // --direct-light, --surface-boundary, --equiangular, --photon-planes: the rows' settings (LEGACY
    // sets its own).
    app::addDirectLightOption(&cli, o.common);
    cli.add_option("--plot", o.study.plot,
                   "Write PREFIX.csv and the gnuplot script PREFIX.gp, and run gnuplot for PREFIX.png: error against "
                   "passes, or against CPU seconds with --cpu-seconds (default: none)");
}

void run(Options& o) {
    if (!o.study.library.empty() && o.common.command->get_option("--scene")->count() == 0) o.study.scenes.clear();
    if (!o.study.library.empty() && !(o.study.cpuSeconds > 0))
        throw Error("--library needs --cpu-seconds (library scenes have no pass count)");
    app::finishOptions(o.common);
    app::ThreadLimit threads(o.common.settings.threads);
    runQualityStudy(o.common.settings, o.study);
}

}  // namespace
}  // namespace tyndall::bench

int main(int argc, char** argv) {
    CLI::App cli{"Image error of radius settings against path-traced references (equal work or equal time)",
                 "tyndall_quality"};
    tyndall::bench::Options o;
    o.common.command = &cli;
    tyndall::bench::addOptions(cli, o);
    return tyndall::bench::runStudy(cli, argc, argv, [&o] { tyndall::bench::run(o); });
}
