#pragma once
// `--reference REF.exr --convergence FILE.csv`: one CSV row per pass of the running mean against
// a reference image of the same size:
//   pass, elapsed_s, photon_paths, beam_radius, rel_rmse, bias
// rel_rmse = sqrt(sum (m - r)^2 / sum r^2) over all pixels and channels (the RMSE relative to the
// reference's RMS, defined where the reference has black pixels); bias = (sum m - sum r) / sum r
// (the relative error of the image's mean: PPB's bias shows here, noise mostly averages out);
// beam_radius = the beam radius of the last photon path of that pass (scene units). Rank 0 only.
#include <cstdio>
#include <string>

#include "core/accumulator.h"
#include "core/image.h"

namespace tyndall::app {

struct ConvergenceRow {
    uint64_t pass = 0;  ///< passes in the running mean
    double elapsed = 0;
    uint64_t photonPaths = 0;
    double beamRadius = 0;
};

/// rel_rmse and bias of `acc`'s running mean against `reference` (see above).
void relativeErrors(const Accumulator& acc, const Image& reference, double* relRmse, double* bias);

class ConvergenceLog {
public:
    /// Reads `referencePath` (Error naming it when unreadable or not width x height) and creates
    /// `csvPath` with its header line (Error naming it when it cannot be written).
    ConvergenceLog(const std::string& referencePath, const std::string& csvPath, int width, int height);
    ~ConvergenceLog();
    ConvergenceLog(const ConvergenceLog&) = delete;
    ConvergenceLog& operator=(const ConvergenceLog&) = delete;

    void add(const Accumulator& acc, const ConvergenceRow& row);

private:
    Image m_reference;
    std::FILE* m_csv = nullptr;
    std::string m_path;
};

}  // namespace tyndall::app
