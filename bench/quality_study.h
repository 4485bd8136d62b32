#pragma once
// build/bench/tyndall_quality: image error against a long reference of the in-tree path tracer
// (bench/quality_reference.h), for several radius settings in one run, at equal work (the same
// passes) or at equal time. Per scene, for each setting, a progressive render with the relative
// RMSE and bias taken at doubling pass counts and at its end, and the process CPU time its passes
// took (error measurements excluded).
//
// Equal work (FILE:PASSES, no CPU budget): every setting renders the same passes. The settings:
// LEGACY (scene-relative radii, no photon cone, no shadow rays, the plain surface kernel: the
// defaults before the automatic radii), the automatic radii planned for the pass count, the same
// without the photon cone (cpu/beam_cone.h), and the automatic radii of an open-ended render. The
// plot: error against passes.
//
// Equal time (cpuSeconds > 0): every render goes on until its passes' process CPU time reaches the
// budget, so a setting that costs more per pass gets fewer passes. CPU time stands in for wall time
// on a machine shared with other work (its wall clock measures the neighbours); on an idle machine
// with T threads busy the two differ by about T (docs/performance.md). The image is still a pure
// function of the pass count: the budget only decides where the render stops, so a row is
// reproduced by rendering its printed pass count. The settings: legacy, today's defaults as
// `tyndall render --time` resolves them (the open-ended plan), the same with --equiangular switched
// (single scattering from point, spot and area lights by equiangular sampling or by their first beams:
// cpu/equiangular.h) and, given FILE:PASSES, the automatic radii planned for that pass count. The
// plot: error against CPU seconds.
// With a library folder its scenes are added, made valid for the path tracer (withoutSpecularSurfaces).
#include <string>
#include <vector>

#include "core/scene.h"
#include "core/settings.h"

namespace tyndall::bench {

struct QualityStudyOptions {
    std::vector<std::string> scenes;  ///< scene files; each with its pass count after ':' (file:passes)
    std::string referenceDir = "build/quality-references";
    uint32_t referenceSpp = 1024;
    std::string plot;  ///< PREFIX of PREFIX.csv, PREFIX.gp and (by gnuplot) PREFIX.png; "" = no plot
    /// Seeds each setting is rendered with (seed, seed + 1, ...): errors are the root mean square
    /// over them, bias the mean (a visible light's central pixel is heavy-tailed: one seed misleads).
    int seeds = 1;
    /// > 0: equal time, each render stops when its passes' process CPU time reaches this (seconds).
    double cpuSeconds = 0;
    /// A folder of scene files (the scene library, scenes/): each *.json after the `scenes`, with
    /// its mirror and glass surfaces made index-matched Interfaces (withoutSpecularSurfaces), where
    /// the path tracer is valid; named <scene>-no-specular (also in the reference cache).
    std::string library;
    /// A folder for each row's final image per seed (<scene>-<row>-seed<N>.exr); "" = none.
    std::string imageDir;
    /// Only the scenes whose file name without its extension is one of these; empty = all.
    std::vector<std::string> only;
    /// The LEGACY row (false leaves it out, for studies of today's settings alone).
    bool legacy = true;
    /// Equal time: the rows of today's defaults with --equiangular and --film-light-sampling switched
    /// (false leaves them out: the defaults' row alone, as bench/baseline_compare.sh may want).
    bool switches = true;
    /// Equal time: one more row per entry, today's defaults with --equiangular on and this many
    /// equiangular samples per segment (RenderSettings::equiangularSamples; 0 = auto), to compare
    /// counts in one run.
    std::vector<double> equiangularSamples;
    /// Equal time: one more row per entry, today's defaults with this many mean free paths for the
    /// beams after a scattering (RenderSettings::scatteredBeamMfp; 0 = every beam the schedule's).
    std::vector<double> scatteredBeamMfp;
    /// Equal time: one more row per entry, today's defaults with photon points in dense media of this
    /// many mean free paths (RenderSettings::mediumPointMfp; 0 = beams only).
    std::vector<double> mediumPointMfp;
    /// Equal time: one more row per entry, today's defaults with the indirect surface photons at
    /// least this many times their path length from their last diffuse scattering wide
    /// (RenderSettings::indirectPhotonSpread; 0 = every photon the schedule's).
    std::vector<double> indirectPhotonSpread;
    /// Only print each scene's equiangular pilot (bench/equiangular_pilot.h): no references, no rows.
    bool pilotOnly = false;
};

/// The LEGACY row's settings: `s` with the scene-relative radii (withSceneRelativeRadii), no photon
/// cone, surfaces lit by photons alone (no shadow rays), the plain surface kernel and the media lit
/// by beams alone (no equiangular sampling), every beam of the schedule's radius.
RenderSettings withLegacyDefaults(RenderSettings s, const Scene& scene);

/// Runs the study; `base` carries size, seed, threads, photons and alpha. Prints a table.
void runQualityStudy(const RenderSettings& base, const QualityStudyOptions& options);

}  // namespace tyndall::bench
