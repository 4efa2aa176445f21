#include "skyfuse/metrics/chi_square.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "metrics/monotone_inverse.hpp"

namespace skyfuse {
namespace {

constexpr double kEpsilon = 1e-15;
constexpr double kTiny = 1e-300;
constexpr int kMaxIterations = 100000;

// Lower regularised incomplete gamma P(a, x) by its power series; converges fast for x < a + 1.
double gamma_p_series(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < kMaxIterations; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * kEpsilon) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Upper regularised incomplete gamma Q(a, x) by its continued fraction (modified Lentz);
// converges fast for x >= a + 1.
double gamma_q_continued_fraction(double a, double x) {
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEpsilon) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

double regularized_gamma_p(double a, double x) {
  if (x <= 0.0) return 0.0;
  if (x < a + 1.0) return gamma_p_series(a, x);
  return 1.0 - gamma_q_continued_fraction(a, x);
}

}  // namespace

double chi_square_cdf(double x, double dof) {
  return regularized_gamma_p(0.5 * dof, 0.5 * x);
}

double chi_square_quantile(double probability, double dof) {
  if (!(probability > 0.0 && probability < 1.0) || !(dof > 0.0)) {
    throw std::invalid_argument("chi_square_quantile: probability must be in (0,1), dof > 0");
  }
  // The CDF is monotone: bisection to full double precision is simple and robust.
  double high = dof + 20.0 * std::sqrt(2.0 * dof) + 100.0;
  while (chi_square_cdf(high, dof) < probability) high *= 2.0;
  return detail::bisect_monotone([dof](double x) { return chi_square_cdf(x, dof); }, probability,
                                 0.0, high, 1e-12, 0.0);
}

ChiSquareBand average_chi_square_band(int dof, int samples, double confidence) {
  const double total_dof = static_cast<double>(dof) * samples;
  const double tail = 0.5 * (1.0 - confidence);
  return {chi_square_quantile(tail, total_dof) / samples,
          chi_square_quantile(1.0 - tail, total_dof) / samples};
}

}  // namespace skyfuse
