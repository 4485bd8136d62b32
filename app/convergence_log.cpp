#include "app/convergence_log.h"

#include <cmath>

#include "core/error.h"
#include "core/image_io.h"

namespace tyndall::app {

void relativeErrors(const Accumulator& acc, const Image& reference, double* relRmse, double* bias) {
    double se = 0, rr = 0, sm = 0, sr = 0;
    for (int y = 0; y < acc.height(); ++y)
        for (int x = 0; x < acc.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                double m = acc.meanAt(x, y, c), r = reference.at(x, y)[c];
                se += (m - r) * (m - r);
                rr += r * r;
                sm += m;
                sr += r;
            }
    *relRmse = rr > 0 ? std::sqrt(se / rr) : NAN;
    *bias = sr != 0 ? (sm - sr) / sr : NAN;
}

ConvergenceLog::ConvergenceLog(const std::string& referencePath, const std::string& csvPath, int width, int height)
    : m_reference(readImage(referencePath)), m_path(csvPath) {
    if (m_reference.width != width || m_reference.height != height)
        throw Error("--reference '" + referencePath + "' is " + std::to_string(m_reference.width) + "x" +
                    std::to_string(m_reference.height) + ", the render is " + std::to_string(width) + "x" +
                    std::to_string(height) + " (render it at the same --size)");
    m_csv = std::fopen(csvPath.c_str(), "w");
    if (!m_csv) throw Error("--convergence '" + csvPath + "': cannot be written");
    std::fprintf(m_csv, "pass,elapsed_s,photon_paths,beam_radius,rel_rmse,bias\n");
}

ConvergenceLog::~ConvergenceLog() {
    if (m_csv) std::fclose(m_csv);
}

void ConvergenceLog::add(const Accumulator& acc, const ConvergenceRow& row) {
    double relRmse, bias;
    relativeErrors(acc, m_reference, &relRmse, &bias);
    std::fprintf(m_csv, "%llu,%.4f,%llu,%.9g,%.9g,%.9g\n", (unsigned long long)row.pass, row.elapsed,
                 (unsigned long long)row.photonPaths, row.beamRadius, relRmse, bias);
    std::fflush(m_csv);
}

}  // namespace tyndall::app
