#include "core/radius_schedule.h"

#include <cmath>

#include "core/error.h"

namespace tyndall {

RadiusSchedule::RadiusSchedule(double alpha, uint64_t offset) : m_alpha(alpha), m_offset(offset) {
    TYNDALL_CHECK(alpha > 0.0 && alpha < 1.0, "alpha must lie in (0, 1)");
    m_logR0 = logR(alpha, double(offset) + 1.0);
}

double RadiusSchedule::logR(double alpha, double n) {
    // R(n) = Gamma(n + alpha) / (Gamma(1 + alpha) Gamma(n + 1)). lgamma differences lose digits as
    // n grows (lgamma(1e5) ~ 1e6, so ~1e-10 absolute), so from n = 1000 on use the asymptotic
    // series of ln Gamma(n+a) - ln Gamma(n+b) in Bernoulli polynomials, exact to O(n^-4).
    double c = -std::lgamma(1.0 + alpha);
    if (n < 1000.0) return std::lgamma(n + alpha) - std::lgamma(n + 1.0) + c;
    auto b2 = [](double x) { return x * x - x + 1.0 / 6.0; };
    auto b3 = [](double x) { return x * x * x - 1.5 * x * x + 0.5 * x; };
    auto b4 = [](double x) { return x * x * x * x - 2.0 * x * x * x + x * x - 1.0 / 30.0; };
    const double a = alpha, b = 1.0;
    return (a - b) * std::log(n) + (b2(a) - b2(b)) / (2.0 * n) - (b3(a) - b3(b)) / (6.0 * n * n) +
           (b4(a) - b4(b)) / (12.0 * n * n * n) + c;
}

double RadiusSchedule::beamFactor(uint64_t j) const {
    return std::exp(logR(m_alpha, double(j) + double(m_offset) + 1.0) - m_logR0);
}

double RadiusSchedule::surfaceFactor(uint64_t j) const { return std::sqrt(beamFactor(j)); }

}  // namespace tyndall
