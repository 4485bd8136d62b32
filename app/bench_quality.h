#pragma once
// `tyndall bench --quality`: image error against a long reference of the in-tree path tracer,
// for several radius settings at equal work (the same photon paths and passes), in one run.
// Per scene: the reference (cached as <dir>/<scene>-<W>x<H>-<spp>spp.exr, rendered when absent,
// with its own noise recorded so the figures can remove it), then for each setting a progressive
// render with the relative RMSE and bias taken at doubling pass counts, and the process CPU time
// each took (so equal work can be checked against equal time). The settings: today's explicit
// "legacy" radii (0.5% / 2% of the diagonal, offset 1000), the automatic radii planned for the
// pass count, the same without the photon cone (cpu/beam_cone.h), and the automatic radii of an
// open-ended render. Writes an error-vs-passes log-log
// plot (PNG) with the N^(-alpha/2) slope drawn.
#include <string>
#include <vector>

#include "app/cli_common.h"

namespace tyndall::app {

struct QualityBenchOptions {
    std::vector<std::string> scenes;  ///< scene files; each with its pass count after ':' (file:passes)
    std::string referenceDir = "build/quality-references";
    uint32_t referenceSpp = 1024;
    std::string plot;                 ///< PNG path; "" = no plot
    /// Seeds each setting is rendered with (seed, seed + 1, ...): errors are the root mean square
    /// over them, bias the mean (a visible light's central pixel is heavy-tailed: one seed misleads).
    int seeds = 1;
};

/// Runs the benchmark; `common` carries size, seed, threads and photons. Prints a table.
void runQualityBench(const CommonOptions& common, const QualityBenchOptions& options);

}  // namespace tyndall::app
