#include "core/radius_schedule.h"

#include <cmath>

#include "core/error.h"

namespace tyndall {

namespace {
double b2(double x) {
    return x * x - x + 1.0 / 6.0;
}
double b3(double x) {
    return x * x * x - 1.5 * x * x + 0.5 * x;
}
double b4(double x) {
    return x * x * x * x - 2.0 * x * x * x + x * x - 1.0 / 30.0;
}
}  // namespace

RadiusSchedule::LogRTerms::LogRTerms(double a)
    : alpha(a), c(-std::lgamma(1.0 + a)), k2(b2(a) - b2(1.0)), k3(b3(a) - b3(1.0)), k4(b4(a) - b4(1.0)) {}

double RadiusSchedule::LogRTerms::operator()(double n) const {
    // R(n) = Gamma(n + alpha) / (Gamma(1 + alpha) Gamma(n + 1)). lgamma differences lose digits as
    // n grows (lgamma(1e5) ~ 1e6, so ~1e-10 absolute), so from n = 1000 on use the asymptotic
    // series of ln Gamma(n+a) - ln Gamma(n+b) in Bernoulli polynomials, exact to O(n^-4).
    if (n < 1000.0) return std::lgamma(n + alpha) - std::lgamma(n + 1.0) + c;
    const double b = 1.0;
    return (alpha - b) * std::log(n) + k2 / (2.0 * n) - k3 / (6.0 * n * n) + k4 / (12.0 * n * n * n) + c;
}

RadiusSchedule::RadiusSchedule(double alpha, uint64_t offset) : m_alpha(alpha), m_offset(offset), m_terms(alpha) {
    TYNDALL_CHECK(alpha > 0.0 && alpha < 1.0, "alpha must lie in (0, 1)");
    m_logR0 = m_terms(double(offset) + 1.0);
}

double RadiusSchedule::logR(double alpha, double n) {
    return LogRTerms(alpha)(n);
}

double RadiusSchedule::beamFactor(uint64_t j) const {
    return std::exp(m_terms(double(j) + double(m_offset) + 1.0) - m_logR0);
}

uint64_t RadiusSchedule::offsetForRatio(double alpha, uint64_t paths, double ratio) {
    TYNDALL_CHECK(ratio > 0.0 && ratio <= 1.0, "offsetForRatio: ratio must lie in (0, 1]");
    // beamFactor(paths) rises monotonically towards 1 as the offset grows.
    auto factor = [&](uint64_t offset) { return RadiusSchedule(alpha, offset).beamFactor(paths); };
    uint64_t lo = 0, hi = uint64_t(1) << 50;
    if (factor(lo) >= ratio) return lo;
    if (factor(hi) < ratio) return hi;
    while (hi - lo > 1) {
        uint64_t mid = lo + (hi - lo) / 2;
        (factor(mid) >= ratio ? hi : lo) = mid;
    }
    return hi;
}

double RadiusSchedule::surfaceFactor(uint64_t j) const { return std::sqrt(beamFactor(j)); }

}  // namespace tyndall
