#include "cpu/segment_emission.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "cpu/free_flight.h"

namespace tyndall {

EmissionImportance::EmissionImportance(const Medium& medium) {
    if (medium.homogeneous() || !medium.emissive()) return;
    const MajorantGrid* mg = medium.density->majorantGrid();
    if (!mg || mg->cellCount() == 0 || mg->worldToCell().determinant() == 0) return;
    m_worldToCell = mg->worldToCell();
    for (int a = 0; a < 3; ++a) m_res[a] = mg->resolution(a);
    const Affine3 cellToWorld = m_worldToCell.inverse();
    size_t occupied = 0;
    for (int k = 0; k < m_res[2]; ++k)
        for (int j = 0; j < m_res[1]; ++j)
            for (int i = 0; i < m_res[0]; ++i) occupied += mg->at(i, j, k) > 0;
    int m = 4;
    while (m > 1 && occupied * size_t(m * m * m) > kMaxLookups) --m;
    std::vector<double> cells(mg->cellCount(), 0.0);
    const DensityGrid& grid = *medium.density;
    tbb::parallel_for(0, m_res[2], [&](int k) {
        for (int j = 0; j < m_res[1]; ++j)
            for (int i = 0; i < m_res[0]; ++i) {
                if (!(mg->at(i, j, k) > 0)) continue;
                double sum = 0;
                for (int c = 0; c < m * m * m; ++c) {
                    const Vec3 inCell(float(i) + (float(c % m) + 0.5f) / float(m),
                                      float(j) + (float(c / m % m) + 0.5f) / float(m),
                                      float(k) + (float(c / (m * m)) + 0.5f) / float(m));
                    const Vec3 p = cellToWorld.point(inCell);
                    const float d = grid.density(p);
                    if (!(d > 0)) continue;
                    const Rgb le = medium.emissionField ? medium.emissionField->radiance(p) : medium.emission;
                    const Rgb s = medium.sigmaA * le * d;
                    sum += double(s.r) + s.g + s.b;
                }
                cells[(size_t(k) * m_res[1] + j) * m_res[0] + i] = sum;
            }
    });
    // Relative to the largest, so that a faint field (a blackbody far below its peak) keeps its
    // ratios in float.
    double largest = 0;
    for (double c : cells) largest = std::max(largest, c);
    m_cells.assign(cells.size(), 0.0f);
    if (largest > 0)
        for (size_t c = 0; c < cells.size(); ++c) m_cells[c] = float(cells[c] / largest);
}

float EmissionImportance::at(const Vec3& p) const {
    const Vec3 c = m_worldToCell.point(p);
    int idx[3];
    for (int a = 0; a < 3; ++a) idx[a] = clampValue(int(std::floor(c[a])), 0, m_res[a] - 1);
    return m_cells[(size_t(idx[2]) * m_res[1] + idx[1]) * m_res[0] + idx[0]];
}

Rgb estimateSegmentEmission(const Medium& medium, const EmissionImportance& importance, const Ray& ray, float tEnd,
                            Rng& rng, int samples) {
    if (!medium.emissive() || samples <= 0 || !(tEnd > 0)) return Rgb(0.0f);
    if (medium.homogeneous()) return homogeneousEmission(medium, tEnd);
    const DensityGrid& grid = *medium.density;
    const float sigmaT = medium.sigmaT().r;
    if (!(sigmaT > 0)) return Rgb(0.0f);
    auto importanceOf = [&](float t0, float t1) { return double(importance.at(ray.at(0.5f * (t0 + t1)))); };
    // Walk 1: the pieces' importance Q and majorant M (both integrated along the segment).
    double Q = 0, M = 0;
    {
        MajorantPieces pieces(grid, ray, tEnd);
        float t0, t1, maj;
        while (pieces.next(&t0, &t1, &maj)) {
            if (!(maj > 0)) continue;
            M += double(maj) * (t1 - t0);
            if (!importance.none()) Q += importanceOf(t0, t1) * (t1 - t0);
        }
    }
    if (!(M > 0)) return Rgb(0.0f);
    const bool byImportance = Q > 0;
    const double share = byImportance ? double(kEmissionDefensiveShare) * Q / M : 1.0;
    const double W = byImportance ? Q * (1.0 + kEmissionDefensiveShare) : M;
    // Walk 2: the stratified distances in increasing t, each piece's share of them placed
    // uniformly in it, and the residual tracker advanced to each before its source is taken.
    const float combPerUnit = combPointsPerUnit(grid, ray, tEnd);
    const float combOffset = rng.uniform();
    Rgb sum(0.0f);
    double controlDepth = 0;  // sigma_t times the control's integral over the pieces passed
    float residual = 1.0f;    // the residual ratio tracker's running product
    double cum = 0;
    int i = 0;
    double target = (double(i) + rng.uniform()) / samples * W;
    float comb[kMaxCombPoints], prefix[kMaxCombPoints + 1];
    MajorantPieces pieces(grid, ray, tEnd);
    float t0, t1, maj;
    while (i < samples && pieces.next(&t0, &t1, &maj)) {
        if (!(maj > 0)) continue;
        const double w = (byImportance ? importanceOf(t0, t1) : 0.0) + share * maj;
        const double wl = w * (t1 - t0);
        // The control: the density at a comb of m points (spacing h, one random offset for the
        // segment), constant over each point's stratum; its integral up to t in closed form.
        const int m = clampValue(int(std::ceil((t1 - t0) * combPerUnit)), 1, kMaxCombPoints);
        const float h = (t1 - t0) / float(m);
        prefix[0] = 0;
        for (int j = 0; j < m; ++j) {
            comb[j] = grid.density(ray.at(t0 + (float(j) + combOffset) * h));
            prefix[j + 1] = prefix[j] + comb[j] * h;
        }
        auto stratum = [&](float t) { return clampValue(int((t - t0) / h), 0, m - 1); };
        const float mu = maj * sigmaT;
        auto step = [&]() { return -std::log(1.0f - rng.uniform()) / mu; };
        float tc = t0 + step();  // the tracker's next tentative collision (memoryless per piece)
        auto advanceTo = [&](float t) {
            for (; tc < t; tc += step()) residual *= 1.0f - (grid.density(ray.at(tc)) - comb[stratum(tc)]) / maj;
        };
        while (i < samples && target < cum + wl) {
            const float t = std::min(t1, t0 + float((target - cum) / w));
            advanceTo(t);
            const int j = stratum(t);
            const double depth = controlDepth + sigmaT * (double(prefix[j]) + double(comb[j]) * (t - t0 - float(j) * h));
            sum += medium.sourceAt(ray.at(t)) * float(residual * std::exp(-depth) * W / (w * samples));
            ++i;
            if (i < samples) target = (double(i) + rng.uniform()) / samples * W;
        }
        if (i < samples) advanceTo(t1);
        controlDepth += sigmaT * double(prefix[m]);
        cum += wl;
    }
    return sum;
}

SegmentEmission::SegmentEmission(const Scene& scene) : m_scene(scene) {
    m_importance.reserve(scene.media.size());
    for (const Medium& m : scene.media) m_importance.emplace_back(m);
}

}  // namespace tyndall
