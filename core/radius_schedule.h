#pragma once
// The progressive radius reduction of PPB (Jarosz et al. 2011, after Knaus & Zwicker 2011),
// applied once per stored photon path so an image depends only on how many photon paths were
// traced, not on how they were split into passes.
//
// With n = 1, 2, ... counting photon paths, the global beam-radius factor is
//     R(1) = 1,  R(n+1) / R(n) = (n + alpha) / (n + 1)
//     R(n)  = Gamma(n + alpha) / (Gamma(1 + alpha) Gamma(n + 1))      (closed form)
// which makes the per-path variance grow as (n+1)/(n+alpha): the running mean then has
// variance ~ N^-alpha and bias ~ N^(alpha-1). Surface photons use a 2D kernel, so their radius
// factor is sqrt(R(n)).
//
// User-facing radius: R falls from 1 to ~0.02 over the first thousand paths (alpha = 0.5), so a
// radius defined at n = 1 would be meaningless after the first pass. Tyndall starts the schedule
// at n0 = `offset` + 1 and normalises there: path j (0-based, counted over the whole render) uses
//     factor(j) = R(j + n0) / R(n0),
// so `--radius` is the radius of the very first photon path and later paths shrink from it
// exactly as the PPB sequence does from its n0-th step. Convergence is unaffected (only the
// start of the sequence is skipped). The default offset is planned (cpu/radius_defaults.h).
#include <cstdint>

namespace tyndall {

class RadiusSchedule {
public:
    RadiusSchedule(double alpha, uint64_t offset);

    /// Beam (1D kernel) radius factor for photon path `j` (0-based over the whole render); 1 at j=0.
    double beamFactor(uint64_t j) const;
    /// Surface photon (2D kernel) radius factor: sqrt(beamFactor(j)).
    double surfaceFactor(uint64_t j) const;

    double alpha() const { return m_alpha; }
    uint64_t offset() const { return m_offset; }

    /// log R(n) for the unnormalised sequence (n >= 1), stable for n up to ~1e18.
    static double logR(double alpha, double n);

    /// The smallest offset whose schedule has shrunk the beam radius to at least `ratio` (in (0, 1])
    /// of its first value after `paths` photon paths: beamFactor(paths) >= ratio. A pure function
    /// (bisection over exact evaluations), so a plan resolves to the same offset on every machine.
    /// Capped at 2^50 (a near-constant radius) when even that shrinks too fast.
    static uint64_t offsetForRatio(double alpha, uint64_t paths, double ratio);

private:
    /// logR with its n-independent terms precomputed (the same values, so the same result).
    struct LogRTerms {
        double alpha, c, k2, k3, k4;  // c = -ln Gamma(1 + alpha); k = Bernoulli-polynomial differences
        explicit LogRTerms(double alpha);
        double operator()(double n) const;
    };

    double m_alpha;
    uint64_t m_offset;
    LogRTerms m_terms;
    double m_logR0;
};

}  // namespace tyndall
