#include "cpu/free_flight.h"

#include <algorithm>
#include <cmath>

namespace tyndall {

namespace {
float expSample(float sigma, float u) {
    return sigma > 0 ? -std::log(1.0f - u) / sigma : kInfinity;
}  // u < 1

/// Delta tracking: tentative collisions of a Poisson process at rate majorant * sigma_t, each real
/// with probability density / majorant. One exponential optical-depth target carries across
/// piece boundaries (memorylessness), so a ray costs one log per tentative collision.
/// Returns the distance of the first real collision in [0, tEnd), or +infinity.
float deltaTrack(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    const DensityGrid& grid = *medium.density;
    const float sigmaT = medium.sigmaT().r;
    if (!(sigmaT > 0)) return kInfinity;
    MajorantPieces pieces(grid, ray, tEnd);
    // The first target is drawn at the first piece that can collide: a ray through empty space
    // (an empty grid, its empty parts) draws nothing, so an empty medium is clear air bit for bit.
    float tau = -1.0f;
    float t0, t1, maj;
    while (pieces.next(&t0, &t1, &maj)) {
        const float mu = maj * sigmaT;
        if (!(mu > 0)) continue;
        if (tau < 0) tau = -std::log(1.0f - rng.uniform());
        float t = t0;
        while (true) {
            float dt = tau / mu;
            if (!(t + dt < t1)) {
                tau = std::max(0.0f, tau - mu * (t1 - t));
                break;
            }
            t += dt;
            if (rng.uniform() * maj < grid.density(ray.at(t))) return t;
            tau = -std::log(1.0f - rng.uniform());
        }
    }
    return kInfinity;
}

/// Ratio tracking (Novak et al. 2014) over [0, tEnd] of a grid medium with sigma_t > 0: tentative
/// collisions at rate majorant * sigma_t, the running transmittance taking the factor
/// 1 - density / majorant at each. `atCollision(x, density, majorant, tr)` sees each collision
/// before its factor is taken. Returns the transmittance (may round below 0; callers clamp).
template <class AtCollision>
float ratioTrack(const Medium& medium, const Ray& ray, float tEnd, Rng& rng, AtCollision&& atCollision) {
    const DensityGrid& grid = *medium.density;
    const float sigmaT = medium.sigmaT().r;
    MajorantPieces pieces(grid, ray, tEnd);
    float tr = 1.0f;
    float t0, t1, maj;
    while (tr > 0 && pieces.next(&t0, &t1, &maj)) {
        const float mu = maj * sigmaT;
        if (!(mu > 0)) continue;
        float t = t0;
        while (tr > 0) {
            t += expSample(mu, rng.uniform());
            if (!(t < t1)) break;
            const Vec3 x = ray.at(t);
            const float dx = grid.density(x);
            atCollision(x, dx, maj, tr);
            tr *= 1.0f - dx / maj;
        }
    }
    return tr;
}
}  // namespace

FreeFlight sampleFreeFlightSpectralOrGrid(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    FreeFlight ff;
    if (medium.homogeneous()) {
        Rgb st = medium.sigmaT();
        int channel = std::min(int(rng.uniform() * 3.0f), 2);
        float t = expSample(st[channel], rng.uniform());
        if (t < tEnd) {
            Rgb tr = medium.transmittance(t);
            float pdf = (st.r * tr.r + st.g * tr.g + st.b * tr.b) / 3.0f;
            ff.scattered = true;
            ff.t = t;
            ff.weight = medium.sigmaS * tr / pdf;
        } else {
            Rgb tr = medium.transmittance(tEnd);
            float pass = tr.average();
            ff.t = tEnd;
            ff.weight = pass > 0 ? tr / pass : Rgb(0.0f);
        }
        return ff;
    }
    // A real collision scatters with weight sigma_s / sigma_t = the albedo (grey extinction);
    // passing has probability Tr(tEnd) and weight 1.
    float t = deltaTrack(medium, ray, tEnd, rng);
    if (t < tEnd) {
        ff.scattered = true;
        ff.t = t;
        ff.weight = medium.albedo();
    } else {
        ff.t = tEnd;
    }
    return ff;
}

float sampleCollisionDistance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (medium.homogeneous()) {
        float t = expSample(medium.sigmaT().r, rng.uniform());
        return t < tEnd ? t : kInfinity;
    }
    return deltaTrack(medium, ray, tEnd, rng);
}

Rgb homogeneousEmission(const Medium& medium, float d) {
    if (!medium.emissive() || !(d > 0)) return Rgb(0.0f);
    const Rgb st = medium.sigmaT(), source = medium.sigmaA * medium.constantEmission();
    Rgb e;
    for (int c = 0; c < 3; ++c) {
        const float x = st[c] * d;
        e[c] = x > 0 ? source[c] * float(-std::expm1(-double(x))) / st[c] : source[c] * d;
    }
    return e;
}

void sampleCollisionDistances(const Medium& medium, const Ray& ray, float tEnd, Rng& rng, int n, float* out) {
    n = std::min(n, kMaxFreeFlights);
    if (medium.homogeneous()) {
        for (int k = 0; k < n; ++k) out[k] = sampleCollisionDistance(medium, ray, tEnd, rng);
        return;
    }
    // n delta trackers advanced piece by piece: the same process as n separate calls (each
    // tracker has its own optical-depth targets), with one walk of the majorant grid.
    const DensityGrid& grid = *medium.density;
    const float sigmaT = medium.sigmaT().r;
    float tau[kMaxFreeFlights];
    int live[kMaxFreeFlights];
    int active = 0;
    for (int k = 0; k < n; ++k) {
        out[k] = kInfinity;
        live[active++] = k;
    }
    if (!(sigmaT > 0)) return;
    MajorantPieces pieces(grid, ray, tEnd);
    float t0, t1, maj;
    bool drawn = false;  // targets drawn at the first piece that can collide (as in deltaTrack)
    while (active > 0 && pieces.next(&t0, &t1, &maj)) {
        const float mu = maj * sigmaT;
        if (!(mu > 0)) continue;
        if (!drawn) {
            for (int k = 0; k < n; ++k) tau[k] = -std::log(1.0f - rng.uniform());
            drawn = true;
        }
        for (int i = 0; i < active;) {
            const int k = live[i];
            float t = t0;
            bool collided = false;
            while (true) {
                float dt = tau[k] / mu;
                if (!(t + dt < t1)) {
                    tau[k] = std::max(0.0f, tau[k] - mu * (t1 - t));
                    break;
                }
                t += dt;
                if (rng.uniform() * maj < grid.density(ray.at(t))) {
                    out[k] = t;
                    collided = true;
                    break;
                }
                tau[k] = -std::log(1.0f - rng.uniform());
            }
            if (collided) {
                live[i] = live[--active];
            } else {
                ++i;
            }
        }
    }
}

Rgb estimateEmission(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (!medium.emissive()) return Rgb(0.0f);
    if (medium.homogeneous()) return homogeneousEmission(medium, tEnd);
    const float sigmaT = medium.sigmaT().r;
    if (!(sigmaT > 0)) return Rgb(0.0f);
    const Rgb sourceScale = medium.sigmaA / sigmaT;
    Rgb sum(0.0f);
    ratioTrack(medium, ray, tEnd, rng, [&](const Vec3& x, float dx, float maj, float tr) {
        if (dx > 0) sum += sourceScale * medium.emissionAt(x) * (tr * dx / maj);
    });
    return sum;
}

Rgb ratioTrackingTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (medium.homogeneous()) return medium.transmittance(tEnd);
    if (!(medium.sigmaT().r > 0)) return Rgb(1.0f);
    const float tr = ratioTrack(medium, ray, tEnd, rng, [](const Vec3&, float, float, float) {});
    return Rgb(std::max(tr, 0.0f));
}

float combPointsPerUnit(const DensityGrid& grid, const Ray& ray, float tEnd) {
    const MajorantGrid* mg = grid.majorantGrid();
    if (!mg) return float(kMaxCombPoints) / tEnd;
    const Vec3 v = mg->worldToCell().vector(ray.d);
    return kCombPointsPerCell * std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
}

float residualTransmittanceAlong(const Medium& medium, const Ray& ray, float tEnd, const float* at, int n, float* out,
                                 Rng& rng) {
    const DensityGrid& grid = *medium.density;
    const float sigmaT = medium.sigmaT().r;
    int read = 0;  // the reads before `read` are done
    if (!(sigmaT > 0) || !(tEnd > 0)) {
        for (; read < n; ++read) out[read] = 1.0f;
        return 1.0f;
    }
    const float combPerUnit = combPointsPerUnit(grid, ray, tEnd);
    float offset = -1.0f;  // the comb's offset, drawn at the first piece that has one
    double depth = 0;      // sigma_t times the control's integral over the pieces passed
    float residual = 1.0f;
    float comb[kMaxCombPoints];
    double prefix[kMaxCombPoints];  // (reads only) the control's integral from t0 to each point
    // The reads before t (or at it, `through`): the running estimate with the control's depth
    // `depthAt(t)` on the current piece.
    auto readBefore = [&](float t, bool through, auto&& depthAt) {
        for (; read < n && (at[read] < t || (through && at[read] <= t)); ++read)
            out[read] = std::max(residual, 0.0f) * float(std::exp(-(depth + depthAt(at[read]))));
    };
    auto none = [](float) { return 0.0; };
    MajorantPieces pieces(grid, ray, tEnd);
    float t0, t1, maj;
    while (residual > 0 && pieces.next(&t0, &t1, &maj)) {
        readBefore(t0, true, none);
        const float mu = maj * sigmaT, length = t1 - t0;
        if (!(mu > 0 && length > 0)) continue;
        auto step = [&]() { return -std::log(1.0f - rng.uniform()) / mu; };
        if (mu * length < kMinCombDepth) {
            for (float t = t0 + step(); residual > 0 && t < t1; t += step()) {
                readBefore(t, false, none);
                residual *= 1.0f - grid.density(ray.at(t)) / maj;
            }
            readBefore(t1, true, none);
            continue;
        }
        if (offset < 0) offset = rng.uniform();
        const int m = clampValue(int(std::ceil(std::min(length * combPerUnit, kCombPointsPerDepth * mu * length))), 1,
                                 kMaxCombPoints);
        const float h = length / float(m);
        double integral = 0;
        for (int j = 0; j < m; ++j) {
            comb[j] = grid.density(ray.at(t0 + (float(j) + offset) * h));
            if (j > 0) integral += 0.5 * double(h) * (double(comb[j - 1]) + comb[j]);
        }
        integral += double(offset) * h * comb[0] + (1.0 - double(offset)) * h * comb[m - 1];
        auto control = [&](float t) {
            const float x = (t - t0) / h - offset;
            if (!(x > 0)) return comb[0];
            const int j = int(x);
            if (j >= m - 1) return comb[m - 1];
            return comb[j] + (x - float(j)) * (comb[j + 1] - comb[j]);
        };
        // sigma_t times the control's integral from t0 to t (closed form: linear between the
        // points, constant beyond the ends).
        auto partialDepth = [&](float t) {
            const double x = std::clamp((double(t) - t0) / h, 0.0, double(m)) - offset;
            if (!(x > 0)) return double(sigmaT) * (x + offset) * h * comb[0];
            const int j = int(x);
            if (j >= m - 1) return double(sigmaT) * (prefix[m - 1] + (x - (m - 1)) * h * comb[m - 1]);
            const double f = x - j;
            return double(sigmaT) * (prefix[j] + h * (f * comb[j] + 0.5 * f * f * (double(comb[j + 1]) - comb[j])));
        };
        if (read < n) {
            prefix[0] = double(offset) * h * comb[0];
            for (int j = 1; j < m; ++j) prefix[j] = prefix[j - 1] + 0.5 * double(h) * (double(comb[j - 1]) + comb[j]);
        }
        for (float t = t0 + step(); residual > 0 && t < t1; t += step()) {
            readBefore(t, false, partialDepth);
            residual *= 1.0f - (grid.density(ray.at(t)) - control(t)) / maj;
        }
        readBefore(t1, true, partialDepth);
        depth += double(sigmaT) * integral;
    }
    const float tr = std::max(residual, 0.0f) * float(std::exp(-depth));
    for (; read < n; ++read) out[read] = tr;
    return tr;
}

float residualTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    return residualTransmittanceAlong(medium, ray, tEnd, nullptr, 0, nullptr, rng);
}

Rgb estimateTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (medium.homogeneous()) return medium.transmittance(tEnd);
    return Rgb(residualTransmittance(medium, ray, tEnd, rng));
}

}  // namespace tyndall
