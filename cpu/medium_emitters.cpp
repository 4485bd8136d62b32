#include "cpu/medium_emitters.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace tyndall {

namespace {
constexpr double kUniformShare = 0.1;

Bounds3 intersect(const Bounds3& a, const Bounds3& b) {
    Bounds3 r;
    r.lo = vmax(a.lo, b.lo);
    r.hi = vmin(a.hi, b.hi);
    return r;
}
}  // namespace

MediumEmitters::MediumEmitters(const EmbreeScene& rt) : m_rt(rt) {
    const Scene& scene = rt.scene();
    for (const TriangleMesh& mesh : scene.meshes) m_regionTest |= mesh.interiorMedium != mesh.exteriorMedium;
    std::vector<double> weights;
    for (size_t i = 0; i < scene.media.size(); ++i) {
        const Medium& m = scene.media[i];
        if (!m.emissive() || scene.bounds.empty()) continue;
        Bounds3 box;
        if (m.density) {
            box = m.density->bounds();
        } else if (MediumId(i) == scene.globalMedium) {
            box = scene.bounds;
        } else {
            for (const TriangleMesh& mesh : scene.meshes)
                if (mesh.interiorMedium == MediumId(i) || mesh.exteriorMedium == MediumId(i))
                    for (const Vec3& p : mesh.positions) box.extend(p);
        }
        box = intersect(box, scene.bounds);
        const Vec3 ext = box.diagonal();
        if (box.empty() || !(ext.x > 0 && ext.y > 0 && ext.z > 0)) continue;
        Source s;
        s.medium = MediumId(i);
        s.box = box;
        // Cells about cubic, at most kMaxCells.
        const double side = std::cbrt(double(ext.x) * ext.y * ext.z / double(kMaxCells));
        for (int a = 0; a < 3; ++a) s.res[a] = std::clamp(int(double(ext[a]) / side), 1, 1 << 10);
        while (size_t(s.res[0]) * s.res[1] * s.res[2] > kMaxCells)
            for (int a = 0; a < 3; ++a) s.res[a] = std::max(1, s.res[a] / 2);
        s.cellSize = Vec3(ext.x / float(s.res[0]), ext.y / float(s.res[1]), ext.z / float(s.res[2]));
        s.cellVolume = s.cellSize.x * s.cellSize.y * s.cellSize.z;
        const size_t cells = size_t(s.res[0]) * s.res[1] * s.res[2];
        s.cdf.resize(cells);
        double sum = 0;
        Rgb power(0.0f);
        for (int k = 0; k < s.res[2]; ++k)
            for (int j = 0; j < s.res[1]; ++j)
                for (int c = 0; c < s.res[0]; ++c) {
                    const Vec3 x = box.lo + Vec3((c + 0.5f) * s.cellSize.x, (j + 0.5f) * s.cellSize.y,
                                                 (k + 0.5f) * s.cellSize.z);
                    const Rgb src = m.sourceAt(x);
                    power += src;
                    sum += std::max(0.0f, src.luminance());
                    s.cdf[(size_t(k) * s.res[1] + j) * s.res[0] + c] = sum;
                }
        if (sum > 0) {
            for (double& v : s.cdf) v /= sum;
            s.uniformShare = kUniformShare;
        } else {
            s.cdf.clear();
            s.uniformShare = 1.0;
        }
        const Rgb estimate = power * float(4.0 * kPi * s.cellVolume);
        m_estimatedPower += estimate;
        weights.push_back(std::max(0.0, double(estimate.luminance())));
        m_sources.push_back(std::move(s));
    }
    if (m_sources.empty()) return;
    const double top = *std::max_element(weights.begin(), weights.end());
    double sum = 0;
    for (double w : weights) {
        sum += top > 0 ? std::max(w, 1e-3 * top) : 1.0;
        m_sourceCdf.push_back(sum);
    }
    for (double& c : m_sourceCdf) c /= sum;
}

MediumEmitters::Photon MediumEmitters::sample(Rng& rng) const {
    const float uSource = rng.uniform(), uCell = rng.uniform();
    const Vec3 uPoint(rng.uniform(), rng.uniform(), rng.uniform());
    const float u1 = rng.uniform(), u2 = rng.uniform();
    size_t si = size_t(std::lower_bound(m_sourceCdf.begin(), m_sourceCdf.end(), double(uSource)) - m_sourceCdf.begin());
    si = std::min(si, m_sources.size() - 1);
    const double pSource = m_sourceCdf[si] - (si > 0 ? m_sourceCdf[si - 1] : 0.0);
    const Source& s = m_sources[si];
    const size_t cells = size_t(s.res[0]) * s.res[1] * s.res[2];

    // The cell: the uniform part for u below its share, else by weight (u rescaled).
    size_t cell;
    if (double(uCell) < s.uniformShare) {
        cell = std::min(size_t(double(uCell) / s.uniformShare * double(cells)), cells - 1);
    } else {
        const double u = (double(uCell) - s.uniformShare) / (1.0 - s.uniformShare);
        cell = std::min(size_t(std::lower_bound(s.cdf.begin(), s.cdf.end(), u) - s.cdf.begin()), cells - 1);
    }
    double pCell = s.uniformShare / double(cells);
    if (!s.cdf.empty()) pCell += (1.0 - s.uniformShare) * (s.cdf[cell] - (cell > 0 ? s.cdf[cell - 1] : 0.0));
    const int c = int(cell % size_t(s.res[0])), j = int((cell / size_t(s.res[0])) % size_t(s.res[1])),
              k = int(cell / (size_t(s.res[0]) * s.res[1]));
    const Vec3 x = s.box.lo + Vec3((float(c) + uPoint.x) * s.cellSize.x, (float(j) + uPoint.y) * s.cellSize.y,
                                   (float(k) + uPoint.z) * s.cellSize.z);
    Photon ph;
    ph.medium = s.medium;
    ph.ray = Ray{x, sampleUniformSphere(u1, u2)};
    const Medium& m = m_rt.scene().media[size_t(s.medium)];
    if (m_regionTest && m_rt.mediumAt(x) != s.medium) return ph;  // not in this medium: no emission here
    const double pdf = pSource * pCell / double(s.cellVolume);
    ph.power = m.sourceAt(x) * float(4.0 * kPi / pdf);
    return ph;
}

}  // namespace tyndall
