#include "cpu/equiangular.h"

#include <algorithm>

#include "core/equiangular.h"
#include "core/light_sampler.h"
#include "core/phase.h"
#include "core/transmittance.h"
#include "cpu/direct_light.h"
#include "cpu/free_flight.h"

namespace tyndall {

EquiangularScattering::EquiangularScattering(const EmbreeScene& rt, double samples)
    : m_rt(rt),
      m_samples(samples > 0 ? samples : 1.0),
      m_whole(int(std::floor(m_samples))),
      m_fraction(float(m_samples - m_whole)) {
    const Scene& scene = rt.scene();
    double total = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (!handles(l)) continue;
        const double power = LightSampler::lightPower(l, scene.bounds).luminance();
        if (!(power > 0)) continue;
        m_lights.push_back(int(i));
        m_intensity.push_back(std::max(0.0f, l.intensity.luminance()));
        total += power;
        m_cdf.push_back(total);
    }
    if (!scene.emitters.empty()) {
        auto sampler = std::make_unique<LightSampler>(scene);
        if (const double power = sampler->emitterPower(); power > 0) {
            m_areaLights = std::move(sampler);
            m_lights.push_back(kAreaLights);
            m_intensity.push_back(power / kPi);  // a Lambertian emitter's intensity along its normal
            total += power;
            m_cdf.push_back(total);
            Bounds3 bounds;
            for (const EmissiveTriangle& t : scene.emitters)
                for (int v = 0; v < 3; ++v) bounds.extend(scene.meshes[size_t(t.mesh)].vertex(t.triangle, v));
            m_areaCentre = bounds.center();
            m_areaReach = 0.5f * length(bounds.diagonal());
        }
    }
    // The environment: its power as LightSampler weighs it (its integral over the disc that the
    // photons leave, pi R^2).
    if (scene.environment) {
        if (const double integral = scene.environment->integral().luminance(); integral > 0) {
            const double r = scene.bounds.empty() ? 1.0 : std::max(0.5 * double(length(scene.bounds.diagonal())), 1e-3);
            m_lights.push_back(kEnvironment);
            m_intensity.push_back(integral);
            total += integral * kPi * r * r;
            m_cdf.push_back(total);
        }
    }
    for (double& c : m_cdf) c /= total;
    // The media that parallel light cannot enter while direct: not the global medium, and bounded
    // only by opaque surfaces that block shadow rays (no Interface, no alpha), like the sea under a
    // refracting water surface. A shadow ray toward the sun from inside one must cross such a
    // surface, so the estimate there is 0 and is not drawn.
    for (size_t i = 0; i < m_lights.size(); ++i) m_anyParallel = m_anyParallel || parallel(i);
    m_sealed.assign(scene.media.size(), true);
    if (scene.globalMedium >= 0 && size_t(scene.globalMedium) < m_sealed.size()) m_sealed[size_t(scene.globalMedium)] = false;
    for (const TriangleMesh& mesh : scene.meshes) {
        const bool valid = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size();
        const bool blocks = valid && scene.materials[size_t(mesh.material)].type != MaterialType::Interface &&
                            scene.materials[size_t(mesh.material)].alphaMode == AlphaMode::Opaque;
        if (blocks) continue;
        for (MediumId m : {mesh.interiorMedium, mesh.exteriorMedium}) {
            if (m == kInheritMedium) m_sealed.assign(m_sealed.size(), false);  // unresolved: assume open
            if (m >= 0 && size_t(m) < m_sealed.size()) m_sealed[size_t(m)] = false;
        }
    }
}

bool EquiangularScattering::parallel(size_t i) const {
    return m_lights[i] == kEnvironment ||
           (m_lights[i] >= 0 && m_rt.scene().lights[size_t(m_lights[i])].type == LightType::Directional);
}

bool EquiangularScattering::handles(const Scene& scene, const EmittedPhoton& photon) {
    if (photon.light >= 0) return handles(scene.lights[size_t(photon.light)]);
    return photon.emitterMesh >= 0 || (photon.environment && scene.environment);
}

namespace {

/// The integral of the camera's transmittance over [0, sMax], guessed with one extinction: the
/// channels' mean (times the grid's mean density in a grid medium).
double transmittanceIntegral(const Medium& med, float sMax) {
    const Rgb st = med.sigmaT();
    double sigma = (double(st.r) + st.g + st.b) / 3.0;
    if (!med.homogeneous()) sigma *= double(med.density->meanDensity());
    const double depth = sigma * sMax;
    return depth > 1e-6 ? -std::expm1(-depth) / sigma : double(sMax);
}

}  // namespace

double EquiangularScattering::segmentWeight(size_t i, const Medium& med, const Vec3& o, const Vec3& d,
                                            float sMax) const {
    const float g = med.g;
    // The environment: its integral over the sphere, the phase function's mean over directions.
    if (m_lights[i] == kEnvironment) return m_intensity[i] * transmittanceIntegral(med, sMax) * double(kInv4Pi);
    float a = 0, b = sMax, reach = 0;
    Vec3 p = m_areaCentre;
    if (m_lights[i] == kAreaLights) {
        reach = m_areaReach;
    } else {
        const Light& light = m_rt.scene().lights[size_t(m_lights[i])];
        // Parallel light: its irradiance wherever the camera's transmittance lets it count, the
        // phase function the same along the whole segment.
        if (light.type == LightType::Directional)
            return m_intensity[i] * transmittanceIntegral(med, sMax) * double(hgPhase(dot(light.direction, -d), g));
        if (light.type == LightType::Spot &&
            !clipToCone(o, d, light.position, light.direction, light.cosOuterAngle, &a, &b))
            return 0;
        p = light.position;
    }
    // The integral of 1 / (h^2 + D^2) over [a, b], h the distance along the segment from the
    // light's foot (core/equiangular.h), D at least `reach`; the phase function at the foot.
    const EquiangularLine line(o, d, a, b, p);
    const double D = std::max(double(line.D), double(reach));
    const double t0 = line.t0;
    const double span = std::atan2(double(b) - t0, D) - std::atan2(double(a) - t0, D);
    const Vec3 x = o + d * std::clamp(line.t0, a, b);
    const Vec3 toLight = p - x;
    const float dist = length(toLight);
    const float phase = dist > 0 ? hgPhase(dot(toLight / dist, d), g) : 1.0f;
    return m_intensity[i] * std::max(span, 0.0) / D * double(phase);
}

bool EquiangularScattering::segmentCdf(const Medium& med, const Vec3& o, const Vec3& d, float sMax,
                                       double* cdf) const {
    return segmentCdf(med, false, o, d, sMax, cdf);
}

bool EquiangularScattering::segmentCdf(const Medium& med, bool sealed, const Vec3& o, const Vec3& d, float sMax,
                                       double* cdf) const {
    const size_t n = m_lights.size();
    if (n > kWeighedUpTo) {
        std::copy(m_cdf.begin(), m_cdf.end(), cdf);
        return true;
    }
    double total = 0;
    size_t lit = 0;
    for (size_t i = 0; i < n; ++i) {
        cdf[i] = sealed && parallel(i) ? 0.0 : segmentWeight(i, med, o, d, sMax);
        if (!(cdf[i] > 0 && std::isfinite(cdf[i]))) cdf[i] = 0;
        total += cdf[i];
        lit += cdf[i] > 0;
    }
    if (!(total > 0)) return false;
    // (1 - kDefensive) of the estimated shares, kDefensive spread evenly over the sources with one.
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
        if (cdf[i] > 0) sum += (1.0 - kDefensive) * cdf[i] / total + kDefensive / double(lit);
        cdf[i] = sum;
    }
    for (size_t i = 0; i < n; ++i) cdf[i] /= sum;
    cdf[n - 1] = 1.0;
    return true;
}

namespace {

/// The pieces of [a, b] along a ray through a grid medium on which the distance is sampled, each
/// with its weight: the majorant, times a guess of the camera's transmittance to the piece,
/// exp(-sigma_t x the majorant's optical depth from a), kept above kMinAttenuation. The guess only
/// shapes the pdf (the estimate divides by it): it steers samples off the far side of a thick
/// layer; its floor bounds the weight where the majorant overstates the density.
class WeightedPieces {
public:
    static constexpr double kMinAttenuation = 1.0 / 16;
    WeightedPieces(const DensityGrid& grid, const Ray& ray, float a, float b, float sigmaT)
        : m_pieces(grid, ray, b, a), m_sigmaT(sigmaT) {}
    bool next(float* t0, float* t1, double* weight) {
        float maj;
        while (m_pieces.next(t0, t1, &maj)) {
            if (!(maj > 0 && *t1 > *t0)) continue;
            *weight = double(maj) * std::max(std::exp(-double(m_sigmaT) * m_depth), kMinAttenuation);
            m_depth += double(maj) * (*t1 - *t0);
            return true;
        }
        return false;
    }

private:
    MajorantPieces m_pieces;
    float m_sigmaT;
    double m_depth = 0;  ///< the majorant's optical depth (at unit extinction) from a
};

/// The piece of WeightedPieces along [a, b] that a share u of the sum of w x measure(t0, t1) falls
/// in, where `measure` is a piece's size in the sampled variable (its length, or its angle seen from
/// a light): two walks, the first for the sum, the second stopping where the running sum passes
/// u x sum. Returns false when every piece is empty. Rounding can leave the target past the last
/// piece: then `chosen` is false and the caller takes its end.
struct WeightedPiece {
    float t0 = 0, t1 = 0;
    double w = 0, before = 0, size = 0, total = 0, target = 0;
    bool chosen = false;
};

/// The second walk: the pieces from `next(&t0, &t1, &w, &size)` (false after the last), stopping
/// in the one where the running sum of w x size passes u x total.
template <class NextPiece>
bool takePieceAt(double total, float u, WeightedPiece* piece, NextPiece&& next) {
    if (!(total > 0)) return false;
    const double target = double(u) * total;
    double sum = 0, w, size;
    float t0, t1;
    WeightedPiece last;
    while (next(&t0, &t1, &w, &size)) {
        if (!(size > 0)) continue;
        last.t0 = t0, last.t1 = t1, last.w = w, last.size = size;
        if (sum + w * size > target) {
            last.chosen = true;
            break;
        }
        sum += w * size;
    }
    if (!(last.w > 0)) return false;
    last.before = sum, last.total = total, last.target = target;
    *piece = last;
    return true;
}

template <class Measure>
bool chooseWeightedPiece(const DensityGrid& grid, const Ray& ray, float a, float b, float sigmaT, float u,
                         Measure&& measure, WeightedPiece* piece) {
    double total = 0;
    {
        WeightedPieces pieces(grid, ray, a, b, sigmaT);
        float t0, t1;
        double w;
        while (pieces.next(&t0, &t1, &w)) total += w * measure(t0, t1);
    }
    WeightedPieces pieces(grid, ray, a, b, sigmaT);
    return takePieceAt(total, u, piece, [&](float* t0, float* t1, double* w, double* size) {
        if (!pieces.next(t0, t1, w)) return false;
        *size = measure(*t0, *t1);
        return true;
    });
}

}  // namespace

/// WeightedPieces along the whole segment [0, sMax], walked once for all of the segment's samples
/// (its first use builds it), with the sizes of the pieces in the last sampled variable: their
/// lengths, and their angles seen from the last light point. chooseWeightedPiece walks the
/// majorant grid twice and takes two arctangents per piece for every sample; from here each
/// sample of a point or spot light or of parallel light reads sums made once per segment, the same
/// numbers in the same order, so the samples are those of the walks bit for bit. More than
/// kMaxPieces pieces: unusable, the samples walk as before.
class SegmentPieces {
public:
    static constexpr int kMaxPieces = 256;
    /// The segment o + t d, t in [0, sMax], of a grid of extinction sigmaT at density 1; nothing
    /// kept yet.
    void reset(const DensityGrid& grid, const Vec3& o, const Vec3& d, float sMax, float sigmaT) {
        m_grid = &grid, m_o = o, m_d = d, m_sMax = sMax, m_sigmaT = sigmaT;
        m_built = m_haveLengths = m_haveAngles = false;
    }
    float sMax() const { return m_sMax; }
    /// The piece that a share u of the sum of w x length falls in (chooseWeightedPiece's, with its
    /// measure the length); false when every piece is empty or the cache is unusable (*usable).
    bool chooseByLength(float u, WeightedPiece* piece, bool* usable) {
        if (!(*usable = build())) return false;
        if (!m_haveLengths) {
            m_lengthTotal = 0;
            for (int k = 0; k < m_n; ++k) {
                m_lengths[k] = double(m_t1[k]) - m_t0[k];
                m_lengthTotal += m_w[k] * m_lengths[k];
            }
            m_haveLengths = true;
        }
        return choose(m_lengths, m_lengthTotal, u, piece);
    }
    /// The same by the angle seen from p along `line` (built over [0, sMax] for p).
    bool chooseByAngle(const Vec3& p, const EquiangularLine& line, float u, WeightedPiece* piece, bool* usable) {
        if (!(*usable = build())) return false;
        if (!m_haveAngles || !(p.x == m_p.x && p.y == m_p.y && p.z == m_p.z)) {
            m_angleTotal = 0;
            float tPrev = 0;
            double anglePrev = 0;
            bool havePrev = false;
            for (int k = 0; k < m_n; ++k) {
                const double a0 = havePrev && m_t0[k] == tPrev ? anglePrev : line.angle(m_t0[k]);
                const double a1 = line.angle(m_t1[k]);
                m_angles[k] = a1 - a0;
                m_angleTotal += m_w[k] * m_angles[k];
                tPrev = m_t1[k], anglePrev = a1, havePrev = true;
            }
            m_p = p;
            m_haveAngles = true;
        }
        return choose(m_angles, m_angleTotal, u, piece);
    }

private:
    bool build() {
        if (m_built) return m_n >= 0;
        m_built = true;
        m_n = 0;
        WeightedPieces pieces(*m_grid, Ray{m_o, m_d, 0.0f, m_sMax}, 0.0f, m_sMax, m_sigmaT);
        float t0, t1;
        double w;
        while (pieces.next(&t0, &t1, &w)) {
            if (m_n == kMaxPieces) {
                m_n = -1;
                return false;
            }
            m_t0[m_n] = t0, m_t1[m_n] = t1, m_w[m_n] = w;
            ++m_n;
        }
        return true;
    }
    /// chooseWeightedPiece's second walk over the kept pieces.
    bool choose(const double* sizes, double total, float u, WeightedPiece* piece) const {
        int k = 0;
        return takePieceAt(total, u, piece, [&](float* t0, float* t1, double* w, double* size) {
            if (k == m_n) return false;
            *t0 = m_t0[k], *t1 = m_t1[k], *w = m_w[k], *size = sizes[k];
            ++k;
            return true;
        });
    }

    const DensityGrid* m_grid = nullptr;
    Vec3 m_o, m_d, m_p;
    float m_sMax = 0, m_sigmaT = 0;
    bool m_built = false, m_haveLengths = false, m_haveAngles = false;
    int m_n = 0;  ///< pieces kept; -1 when there were more than kMaxPieces
    float m_t0[kMaxPieces], m_t1[kMaxPieces];
    double m_w[kMaxPieces], m_lengths[kMaxPieces], m_angles[kMaxPieces];
    double m_lengthTotal = 0, m_angleTotal = 0;
};

namespace {

/// A distance along [a, b] of the ray o + t d in a grid medium (extinction sigmaT at density 1)
/// with pdf proportional to w(t) / |x(t) - p|^2, w WeightedPieces' weight: a piece chosen by its
/// weight times its angle, then equiangular inside it. Returns false when every piece is empty.
/// *pieceWeight receives w at t and *inverseSquareOverPdf 1 / (|x(t) - p|^2 pdf(t)) times it, so
/// that density(x) / w(t) (at most 1 / kMinAttenuation) times that is the geometric factor.
/// `cache` (or nullptr): the segment's pieces, used where [a, b] is the whole segment.
bool sampleWeightedEquiangular(const DensityGrid& grid, const Vec3& o, const Vec3& d, float a, float b, const Vec3& p,
                               float sigmaT, float u, SegmentPieces* cache, float* t, double* pieceWeight,
                               double* inverseSquareOverPdf) {
    const EquiangularLine line(o, d, a, b, p);
    WeightedPiece piece;
    bool usable = false;
    const bool whole = cache && a == 0.0f && b == cache->sMax();
    const bool found = whole && cache->chooseByAngle(p, line, u, &piece, &usable);
    if (!usable && !chooseWeightedPiece(grid, Ray{o, d, 0.0f, b}, a, b, sigmaT, u,
                                        [&](float t0, float t1) { return line.angle(t1) - line.angle(t0); }, &piece))
        return false;
    if (usable && !found) return false;
    const double theta0 = line.angle(piece.t0);
    const double theta = piece.chosen ? theta0 + (piece.target - piece.before) / piece.w : theta0 + piece.size;
    *t = std::clamp(line.at(theta), piece.t0, piece.t1);
    *pieceWeight = piece.w;
    *inverseSquareOverPdf = piece.total / double(line.D);
    return true;
}

/// A distance along [0, sMax] of the ray o + t d in a homogeneous medium with pdf proportional to
/// the camera's transmittance: the mean of the channels' exponentials exp(-sigma_t,c t) truncated
/// to the segment (one when the medium is grey), the channel chosen by the first part of `u` and
/// the distance by the rest. Each channel's weight sigma_s,c Tr_c(t) / pdf(t) is then at most 3x
/// its own exponential's, (1 - exp(-sigma_t,c sMax)) / sigma_t,c. Returns the distance and
/// 1 / pdf.
float sampleTransmittanceDistance(const Medium& med, float sMax, float u, double* inversePdf) {
    const Rgb st = med.sigmaT();
    const float sigma[3] = {st.r, st.g, st.b};
    const int channels = st.r == st.g && st.r == st.b ? 1 : 3;
    const int c = std::min(int(u * float(channels)), channels - 1);
    const double v = std::clamp(double(u) * channels - c, 0.0, 1.0);
    // One channel's truncated exponential: its pdf at t, and its inverse cdf (uniform where the
    // segment's optical depth is negligible).
    auto depthOf = [&](int k) { return double(sigma[k]) * sMax; };
    auto pdfOf = [&](int k, double t) {
        const double depth = depthOf(k);
        if (!(depth > 1e-6)) return 1.0 / sMax;
        return double(sigma[k]) * std::exp(-double(sigma[k]) * t) / -std::expm1(-depth);
    };
    const double depth = depthOf(c);
    const double t = depth > 1e-6 ? -std::log1p(v * std::expm1(-depth)) / double(sigma[c]) : v * sMax;
    const float tf = std::clamp(float(t), 0.0f, sMax);
    double pdf = 0;
    for (int k = 0; k < channels; ++k) pdf += pdfOf(k, tf);
    pdf /= channels;
    *inversePdf = pdf > 0 ? 1.0 / pdf : 0.0;
    return tf;
}

/// A distance along [0, sMax] of the ray o + t d in a grid medium with pdf proportional to
/// WeightedPieces' weight w(t) (the majorant times a guess of the camera's transmittance): a piece
/// chosen by its weight times its length, then uniform inside it. Returns false when every piece
/// is empty. *pieceWeight receives w at t and *total the sum of w times length, so that
/// density(x) / w(t) x total is density(x) / pdf(t).
/// `cache` (or nullptr): the segment's pieces.
bool sampleWeightedDistance(const DensityGrid& grid, const Vec3& o, const Vec3& d, float sMax, float sigmaT, float u,
                            SegmentPieces* cache, float* t, double* pieceWeight, double* total) {
    WeightedPiece piece;
    bool usable = false;
    const bool found = cache && cache->chooseByLength(u, &piece, &usable);
    if (!usable && !chooseWeightedPiece(grid, Ray{o, d, 0.0f, sMax}, 0.0f, sMax, sigmaT, u,
                                        [](float t0, float t1) { return double(t1) - t0; }, &piece))
        return false;
    if (usable && !found) return false;
    const double at = piece.chosen ? double(piece.t0) + (piece.target - piece.before) / piece.w : double(piece.t1);
    *t = std::clamp(float(at), piece.t0, piece.t1);
    *pieceWeight = piece.w;
    *total = piece.total;
    return true;
}

}  // namespace

bool EquiangularScattering::lit(MediumId medium, float sMax) const {
    if (m_lights.empty() || medium == kVacuum || !(sMax > 0)) return false;
    if (m_rt.scene().media[medium].sigmaS.isBlack()) return false;
    return !(m_sealed[size_t(medium)] && m_lights.size() == 1 && parallel(0));
}

Rgb EquiangularScattering::estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax, Rng& rng) const {
    if (!lit(medium, sMax)) return Rgb(0.0f);
    const int n = m_whole + (m_fraction > 0 && rng.uniform() < m_fraction ? 1 : 0);
    return estimate(medium, o, d, sMax, n, rng);
}

int EquiangularScattering::samplesInPass(uint64_t pass, double phase) const {
    if (!(m_fraction > 0)) return m_whole;
    // In double: exact enough for any pass count a render reaches (2^40 passes x a 1/64 step).
    const double f = double(m_fraction);
    const double k = double(pass);
    return m_whole + int(std::floor((k + 1) * f + phase) - std::floor(k * f + phase));
}

double EquiangularScattering::pixelPhase(uint64_t seed, uint64_t pixel) {
    // Keyed by a pass index no render reaches, so it is the pixel's for every pass.
    Rng rng = Rng::forKey(seed, ~uint64_t(0), pixel, StreamPurpose::Equiangular);
    return double(rng.uniform());
}

Rgb EquiangularScattering::estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax, int n, Rng& rng,
                                    EquiangularLegs* out, const EquiangularSubset* subset) const {
    if (out) out->n = 0;
    if (n <= 0 || !lit(medium, sMax)) return Rgb(0.0f);
    const Scene& scene = m_rt.scene();
    const Medium& med = scene.media[medium];
    const size_t sources = m_lights.size();
    const bool sealed = m_sealed[size_t(medium)];
    // Parallel sources trace one in kParallelThinning of their samples, weighted up: the samples k
    // with k mod kParallelThinning equal to a random offset (drawn only where there is one).
    const int offset =
        m_anyParallel ? std::min(int(rng.uniform() * float(kParallelThinning)), kParallelThinning - 1) : 0;
    double cdf[kWeighedUpTo];
    const double* c = m_cdf.data();
    if (sources > 1 && sources <= kWeighedUpTo) {
        if (!segmentCdf(med, sealed, o, d, sMax, cdf)) return Rgb(0.0f);
        c = cdf;
    }
    // EquiangularSubset::only: the subset's sources alone, each with its share of their part of
    // the segment's choice (`sub` its cdf, `subSource` the sources' indices).
    double sub[EquiangularSubset::kMax];
    size_t subSource[EquiangularSubset::kMax];
    size_t subCount = 0;
    if (subset && subset->only) {
        double total = 0;
        for (size_t i = 0; i < sources; ++i) {
            if (!subset->contains(m_lights[i]) || subCount == EquiangularSubset::kMax) continue;
            const double p = c[i] - (i > 0 ? c[i - 1] : 0.0);
            if (!(p > 0)) continue;
            total += p;
            sub[subCount] = total;
            subSource[subCount++] = i;
        }
        if (!(total > 0)) return Rgb(0.0f);
        for (size_t j = 0; j < subCount; ++j) sub[j] /= total;
        sub[subCount - 1] = 1.0;
    }
    // n stratified uniforms (k + xi) / n, each choosing a source and, rescaled inside the source's
    // interval of the cdf, its distance; the sum over N (n's mean).
    // In a grid the segment's majorant pieces are walked once for all n (SegmentPieces; the
    // thread's own, as it is large, 8 KiB).
    thread_local SegmentPieces kept;
    SegmentPieces* pieces = nullptr;
    if (!med.homogeneous()) {
        kept.reset(*med.density, o, d, sMax, med.sigmaT().r);
        pieces = &kept;
    }
    // In a grid the samples' camera legs share one residual tracker, run after them to the
    // farthest sample's distance and read at each (residualTransmittanceAlong).
    const bool shareLegs = pieces && n <= kMaxSharedLegs;
    float legT[kMaxSharedLegs];
    Rgb legValue[kMaxSharedLegs];
    int legs = 0;
    Rgb sum;
    for (int k = 0; k < n; ++k) {
        const float u = (float(k) + rng.uniform()) / float(n);
        size_t i;
        double lo, p;
        if (subCount > 0) {
            size_t j = size_t(std::upper_bound(sub, sub + subCount, double(u)) - sub);
            j = std::min(j, subCount - 1);
            i = subSource[j];
            lo = j > 0 ? sub[j - 1] : 0.0;
            p = sub[j] - lo;
        } else {
            i = sources == 1 ? 0 : size_t(std::upper_bound(c, c + sources, double(u)) - c);
            i = std::min(i, sources - 1);
            lo = i > 0 ? c[i - 1] : 0.0;
            p = c[i] - lo;
        }
        if (!(p > 0)) continue;
        double weight = 1.0 / p;
        if (subset && (subset->only || subset->contains(m_lights[i]))) weight *= subset->scale;
        if (parallel(i)) {
            if (sealed || k % kParallelThinning != offset) continue;
            weight *= kParallelThinning;
        }
        const float uDistance = std::min(float((double(u) - lo) / p), 1.0f - 0x1p-24f);
        if (!shareLegs) {
            sum += fromSource(m_lights[i], med, medium, o, d, sMax, std::max(uDistance, 0.0f), pieces, nullptr, rng) *
                   float(weight);
            continue;
        }
        float t = -1.0f;
        const Rgb value =
            fromSource(m_lights[i], med, medium, o, d, sMax, std::max(uDistance, 0.0f), pieces, &t, rng) * float(weight);
        if (t >= 0 && !value.isBlack()) {
            legT[legs] = t;
            legValue[legs++] = value;
        }
    }
    if (legs > 0) {
        // Sorted by distance (insertion: a handful), then one tracker for all (the caller's when
        // it takes them).
        for (int i = 1; i < legs; ++i)
            for (int j = i; j > 0 && legT[j] < legT[j - 1]; --j) {
                std::swap(legT[j], legT[j - 1]);
                std::swap(legValue[j], legValue[j - 1]);
            }
        if (out) {
            out->n = legs;
            const float scale = 1.0f / float(m_samples);
            for (int i = 0; i < legs; ++i) out->t[i] = legT[i], out->value[i] = legValue[i] * scale;
            return sum / float(m_samples);
        }
        float tr[kMaxSharedLegs];
        const float tEnd = legT[legs - 1];
        residualTransmittanceAlong(med, Ray{o, d, 0.0f, tEnd}, tEnd, legT, legs, tr, rng);
        for (int i = 0; i < legs; ++i) sum += legValue[i] * tr[i];
    }
    return sum / float(m_samples);
}


Rgb EquiangularScattering::fromDirection(const Vec3& travel, const Rgb& incident, const Medium& med, MediumId medium,
                                         const Vec3& o, const Vec3& d, float sMax, float u, SegmentPieces* pieces,
                                         float* tCam, Rng& rng) const {
    // The distance and sigma_s(x) / pdf: transmittance-proportional in a homogeneous medium; in a
    // grid, by WeightedPieces' weight, and the density at x over that weight.
    float t = 0;
    Rgb scattering;
    if (med.homogeneous()) {
        double inversePdf = 0;
        t = sampleTransmittanceDistance(med, sMax, u, &inversePdf);
        if (!(inversePdf > 0)) return Rgb(0.0f);
        scattering = med.sigmaS * float(inversePdf);
    } else {
        double pieceWeight = 0, total = 0;
        if (!sampleWeightedDistance(*med.density, o, d, sMax, med.sigmaT().r, u, pieces, &t, &pieceWeight, &total))
            return Rgb(0.0f);
        const float density = med.density->density(o + d * t);
        if (!(density > 0)) return Rgb(0.0f);
        scattering = med.sigmaS * float(double(density) / pieceWeight * total);
    }
    if (scattering.isBlack()) return Rgb(0.0f);
    // A shadow ray to infinity along -travel (no point to stop at, no emissive triangle to reach:
    // what shadowTransmittance does for a delta light at infinite distance).
    DirectLightSample target;
    target.wi = -travel;
    target.distance = kInfinity;
    target.delta = true;
    const Rgb trLight = shadowTransmittance(m_rt, o + d * t, target, medium, rng);
    if (trLight.isBlack()) return Rgb(0.0f);
    const float phase = hgPhase(dot(travel, -d), med.g);
    if (tCam) {  // the caller reads the camera's transmittance to t from the segment's tracker
        *tCam = t;
        return scattering * incident * trLight * phase;
    }
    const Rgb trCam = estimateTransmittance(med, Ray{o, d, 0.0f, t}, t, rng);
    if (trCam.isBlack()) return Rgb(0.0f);
    return scattering * incident * trCam * trLight * phase;
}

Rgb EquiangularScattering::fromSource(int source, const Medium& med, MediumId medium, const Vec3& o, const Vec3& d,
                                      float sMax, float u, SegmentPieces* pieces, float* tCam, Rng& rng) const {
    if (source == kEnvironment) {
        // A direction by the environment's importance sampling (its luminance), then the distance.
        const float u1 = rng.uniform(), u2 = rng.uniform();
        const EnvironmentSample es = m_rt.scene().environment->sample(u1, u2);
        if (!(es.pdf > 0) || es.radiance.isBlack()) return Rgb(0.0f);
        return fromDirection(-es.wi, es.radiance * (1.0f / es.pdf), med, medium, o, d, sMax, u, pieces, tCam, rng);
    }
    float a = 0, b = sMax;
    DirectLightSample target;  // the light point and what the shadow ray needs of it
    if (source == kAreaLights) {
        // A point on the area lights first; then only the part of the segment in front of its
        // triangle (one-sided emitters) can receive its light.
        const LightSampler::EmitterPoint y = m_areaLights->sampleEmitterPoint(rng);
        if (!(y.pdfArea > 0)) return Rgb(0.0f);
        const float c0 = dot(o - y.point, y.normal), c1 = dot(d, y.normal);
        if (c1 == 0.0f) {
            if (!(c0 > 0)) return Rgb(0.0f);
        } else if (c1 > 0) {
            a = std::max(a, -c0 / c1);
        } else {
            b = std::min(b, -c0 / c1);
        }
        if (!(b > a)) return Rgb(0.0f);
        target.point = y.point;
        target.normal = y.normal;
        target.source = y.source;
        target.incident = y.radiance / y.pdfArea;
        target.delta = false;
    } else {
        const Light& light = m_rt.scene().lights[size_t(source)];
        if (light.type == LightType::Directional)
            return fromDirection(light.direction, light.intensity, med, medium, o, d, sMax, u, pieces, tCam, rng);
        if (light.type == LightType::Spot &&
            !clipToCone(o, d, light.position, light.direction, light.cosOuterAngle, &a, &b))
            return Rgb(0.0f);
        target.point = light.position;
        target.source = source;
        target.incident = light.intensity;
        target.delta = true;
    }
    const Vec3 p = target.point;
    // The distance and 1 / (|x - p|^2 pdf) times the medium's scattering at x: equiangular in a
    // homogeneous medium; in a grid, equiangular times WeightedPieces' weight (the majorant and a
    // guess of the camera's transmittance), and the density at x over that weight.
    float t = 0;
    Rgb scattering;
    if (med.homogeneous()) {
        const EquiangularSample s = sampleEquiangular(o, d, a, b, p, u);
        if (!(s.inverseSquareOverPdf > 0)) return Rgb(0.0f);
        t = s.t;
        scattering = med.sigmaS * s.inverseSquareOverPdf;
    } else {
        double pieceWeight = 0, weighted = 0;
        if (!sampleWeightedEquiangular(*med.density, o, d, a, b, p, med.sigmaT().r, u, pieces, &t, &pieceWeight,
                                       &weighted))
            return Rgb(0.0f);
        const float density = med.density->density(o + d * t);
        if (!(density > 0)) return Rgb(0.0f);
        scattering = med.sigmaS * float(double(density) / pieceWeight * weighted);
    }
    if (scattering.isBlack()) return Rgb(0.0f);
    const Vec3 x = o + d * t;
    const Vec3 toLight = p - x;
    const float dist = length(toLight);
    if (!(dist > 0)) return Rgb(0.0f);
    const Vec3 wi = toLight / dist;  // from x toward the light; the light travels along -wi
    // What leaves the light toward x, times |x - p|^2 (the inverse square is in `scattering`): a
    // spot's falloff; an area light's cosine, over the point's density.
    float emitted = 1.0f;
    if (!target.delta) {
        emitted = -dot(wi, target.normal);
    } else if (m_rt.scene().lights[size_t(source)].type == LightType::Spot) {
        const Light& light = m_rt.scene().lights[size_t(source)];
        emitted = light.spotFalloff(dot(-wi, light.direction));
    }
    if (!(emitted > 0)) return Rgb(0.0f);
    target.wi = wi;
    target.distance = dist;
    const Rgb trLight = shadowTransmittance(m_rt, x, target, medium, rng);
    if (trLight.isBlack()) return Rgb(0.0f);
    const float phase = hgPhase(dot(-wi, -d), med.g);
    if (tCam) {  // the caller reads the camera's transmittance to t from the segment's tracker
        *tCam = t;
        return scattering * target.incident * trLight * (phase * emitted);
    }
    // The camera's transmittance to x: analytic, or residual ratio tracking in a grid.
    const Rgb trCam = estimateTransmittance(med, Ray{o, d, 0.0f, t}, t, rng);
    if (trCam.isBlack()) return Rgb(0.0f);
    return scattering * target.incident * trCam * trLight * (phase * emitted);
}

}  // namespace tyndall
