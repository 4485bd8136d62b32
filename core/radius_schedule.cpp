#include "core/radius_schedule.h"

#include <cmath>

#include "core/error.h"

namespace tyndall {

RadiusSchedule::RadiusSchedule(double alpha, uint64_t offset) : m_alpha(alpha), m_offset(offset) {
    TYNDALL_CHECK(alpha > 0.0 && alpha < 1.0, "alpha must lie in (0, 1)");
    m_logR0 = logR(alpha, double(offset) + 1.0);
}

double RadiusSchedule::logR(double alpha, double n) {
    // lgamma differences lose digits once n is large (lgamma(1e12) ~ 2.6e13); there the
    // asymptotic expansion of ln Gamma(n+a) - ln Gamma(n+1) is exact to O(1/n^2).
    double c = -std::lgamma(1.0 + alpha);
    if (n < 1e5) return std::lgamma(n + alpha) - std::lgamma(n + 1.0) + c;
    double a = alpha, b = 1.0;
    return (a - b) * std::log(n) + (a - b) * (a + b - 1.0) / (2.0 * n) + c;
}

double RadiusSchedule::beamFactor(uint64_t j) const {
    return std::exp(logR(m_alpha, double(j) + double(m_offset) + 1.0) - m_logR0);
}

double RadiusSchedule::surfaceFactor(uint64_t j) const { return std::sqrt(beamFactor(j)); }

}  // namespace tyndall
