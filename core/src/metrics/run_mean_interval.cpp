#include "skyfuse/metrics/run_mean_interval.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "metrics/monotone_inverse.hpp"

namespace skyfuse {
namespace {

constexpr double kEpsilon = 1e-15;
constexpr double kTiny = 1e-300;
constexpr int kMaxTerms = 10000;

// The continued fraction of the regularised incomplete beta I_x(a, b), evaluated by the modified
// Lentz method; it converges fast for x < (a + 1) / (a + b + 2), and the symmetry
// I_x(a, b) = 1 - I_{1-x}(b, a) covers the rest.
double incomplete_beta_fraction(double a, double b, double x) {
  auto guarded = [](double v) { return std::fabs(v) < kTiny ? kTiny : v; };
  double c = 1.0;
  double d = 1.0 / guarded(1.0 - (a + b) * x / (a + 1.0));
  double h = d;
  for (int m = 1; m < kMaxTerms; ++m) {
    // The even and the odd coefficient of step m.
    const double even = m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
    d = 1.0 / guarded(1.0 + even * d);
    c = guarded(1.0 + even / c);
    h *= d * c;
    const double odd = -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
    d = 1.0 / guarded(1.0 + odd * d);
    c = guarded(1.0 + odd / c);
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEpsilon) break;
  }
  return h;
}

double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) {
    return std::exp(log_front) * incomplete_beta_fraction(a, b, x) / a;
  }
  return 1.0 - std::exp(log_front) * incomplete_beta_fraction(b, a, 1.0 - x) / b;
}

}  // namespace

double student_t_cdf(double t, double dof) {
  if (!(dof > 0.0)) throw std::invalid_argument("student_t_cdf: dof must be > 0");
  // P(|T| > |t|) = I_{dof / (dof + t^2)}(dof / 2, 1 / 2), and P(|T| < |t|) the same with
  // x -> 1 - x and the parameters swapped. Near t = 0 the first argument rounds to 1 and loses
  // t, so there the centre is computed from t^2 / (dof + t^2) directly.
  const double t2 = t * t;
  if (t2 < dof) {
    const double centre = regularized_incomplete_beta(0.5, 0.5 * dof, t2 / (dof + t2));
    return t >= 0.0 ? 0.5 + 0.5 * centre : 0.5 - 0.5 * centre;
  }
  const double both_tails = regularized_incomplete_beta(0.5 * dof, 0.5, dof / (dof + t2));
  return t >= 0.0 ? 1.0 - 0.5 * both_tails : 0.5 * both_tails;
}

double student_t_quantile(double probability, double dof) {
  if (!(probability > 0.0 && probability < 1.0) || !(dof > 0.0)) {
    throw std::invalid_argument("student_t_quantile: probability must be in (0,1), dof > 0");
  }
  // The CDF is monotone: widen until the bracket holds the probability, then bisect.
  double low = -1.0;
  double high = 1.0;
  while (student_t_cdf(low, dof) > probability) low *= 2.0;
  while (student_t_cdf(high, dof) < probability) high *= 2.0;
  return detail::bisect_monotone([dof](double t) { return student_t_cdf(t, dof); }, probability,
                                 low, high, 1e-13, 1.0);
}

RunMeanInterval run_mean_interval(const std::vector<double>& values, double confidence) {
  if (values.empty()) throw std::invalid_argument("run_mean_interval: no values");
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("run_mean_interval: confidence must be in (0, 1)");
  }
  const double n = static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) sum += v;
  RunMeanInterval interval;
  interval.mean = sum / n;
  if (values.size() < 2) {
    interval.lower = -std::numeric_limits<double>::infinity();
    interval.upper = std::numeric_limits<double>::infinity();
    return interval;
  }
  double squares = 0.0;
  for (double v : values) squares += (v - interval.mean) * (v - interval.mean);
  interval.standard_deviation = std::sqrt(squares / (n - 1.0));
  const double half_width = student_t_quantile(0.5 * (1.0 + confidence), n - 1.0) *
                            interval.standard_deviation / std::sqrt(n);
  interval.lower = interval.mean - half_width;
  interval.upper = interval.mean + half_width;
  return interval;
}

}  // namespace skyfuse
