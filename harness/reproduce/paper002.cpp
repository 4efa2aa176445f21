// Paper 002: TDOA from a UAV formation. The NCRKF, the nominal KF, the optimal KF and an EKF on
// the same measurements over 200 Monte-Carlo runs (Figs. 3-4 have no numbers: the claims are
// the paper's statements, each decided by a number of this run).
#include "skyfuse/experiments/paper002.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "report/output_files.hpp"
#include "reproduce/papers.hpp"

namespace skyfuse::harness {
namespace {

constexpr double kPrintTimesS[] = {0.0, 0.02, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0};
constexpr std::size_t kNcrkf = static_cast<std::size_t>(Paper002Filter::kNcrkf);
constexpr std::size_t kNominal = static_cast<std::size_t>(Paper002Filter::kNominal);
constexpr std::size_t kOptimal = static_cast<std::size_t>(Paper002Filter::kOptimal);
constexpr std::size_t kEkf = static_cast<std::size_t>(Paper002Filter::kEkf);

std::size_t step_at(const Paper002Result& r, double t) {
  const auto found = std::lower_bound(r.time_s.begin(), r.time_s.end(), t - 1e-9);
  return static_cast<std::size_t>(std::min<std::ptrdiff_t>(
      found - r.time_s.begin(), static_cast<std::ptrdiff_t>(r.time_s.size()) - 1));
}

// How biased a filter stays: over the second half of the run, the mean of |mean error| of the
// x-position, and the value an unbiased filter would show from Monte-Carlo scatter alone
// (E|mean of N errors| = RMSE sqrt(2 / (pi N)) for zero-mean Gaussian errors).
struct LateBias {
  double bias_m = 0.0;
  double unbiased_floor_m = 0.0;
  double ratio() const { return bias_m / unbiased_floor_m; }
};

LateBias late_bias(const ErrorSeries& e, int runs) {
  const std::size_t half = e.mean_error_x_m.size() / 2;
  LateBias out;
  for (std::size_t k = half; k < e.mean_error_x_m.size(); ++k) {
    out.bias_m += std::abs(e.mean_error_x_m[k]);
    out.unbiased_floor_m += e.rmse_x_m[k];
  }
  const auto n = static_cast<double>(e.mean_error_x_m.size() - half);
  out.bias_m /= n;
  out.unbiased_floor_m *= std::sqrt(2.0 / (std::numbers::pi * runs)) / n;
  return out;
}

// Convergence: the first time the x-position RMSE falls below kConvergedFraction of its value
// at t = 0 (from about 290 m to 29 m); infinity if it never does.
constexpr double kConvergedFraction = 0.1;
double convergence_time(const Paper002Result& r, const ErrorSeries& e) {
  for (std::size_t k = 0; k < e.rmse_x_m.size(); ++k) {
    if (e.rmse_x_m[k] < kConvergedFraction * e.rmse_x_m.front()) return r.time_s[k];
  }
  return std::numeric_limits<double>::infinity();
}

void print_table(const Paper002Result& r) {
  fmt::print("\nmean error / RMSE of the relative x-position (m) and x-velocity (m/s)\n{:>6}",
             "t s");
  for (std::string_view name : kPaper002FilterNames) fmt::print(" | {:^33}", name);
  fmt::print("\n");
  for (double t : kPrintTimesS) {
    const std::size_t k = step_at(r, t);
    fmt::print("{:>6.2f}", r.time_s[k]);
    for (const ErrorSeries& e : r.filters) {
      fmt::print(" | {:>8.2f} {:>7.2f} {:>8.2f} {:>7.2f}", e.mean_error_x_m[k], e.rmse_x_m[k],
                 e.mean_error_vx_mps[k], e.rmse_vx_mps[k]);
    }
    fmt::print("\n");
  }
}

void write_csv(const Paper002Result& r, const std::filesystem::path& path) {
  std::string csv = "t_s";
  for (std::string_view name : kPaper002FilterNames) {
    csv += fmt::format(",{0}_mean_x_m,{0}_rmse_x_m,{0}_mean_vx_mps,{0}_rmse_vx_mps", name);
  }
  csv += '\n';
  for (std::size_t k = 0; k < r.time_s.size(); ++k) {
    csv += fmt::format("{:.6g}", r.time_s[k]);
    for (const ErrorSeries& e : r.filters) {
      csv += fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g}", e.mean_error_x_m[k], e.rmse_x_m[k],
                         e.mean_error_vx_mps[k], e.rmse_vx_mps[k]);
    }
    csv += '\n';
  }
  write_file_atomically(path, csv);
}

// Convergence time and late bias of each filter at one range, for the printout and the file.
nlohmann::json figures(const Paper002Result& r, int runs) {
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t f = 0; f < r.filters.size(); ++f) {
    const LateBias bias = late_bias(r.filters[f], runs);
    const double t = convergence_time(r, r.filters[f]);
    out[std::string(kPaper002FilterNames[f])] = {
        {"convergence_time_s", std::isfinite(t) ? nlohmann::json(t) : nlohmann::json(nullptr)},
        {"late_abs_mean_error_x_m", bias.bias_m},
        {"unbiased_floor_x_m", bias.unbiased_floor_m},
        {"final_rmse_x_m", r.filters[f].rmse_x_m.back()},
        {"final_rmse_vx_mps", r.filters[f].rmse_vx_mps.back()},
        {"not_positive_definite_steps", r.not_positive_definite[f]}};
    fmt::print(
        "  {:>10}: converged (RMSE_x < {} x its start) at {:>6.3f} s; late |mean error| "
        "{:>7.3f} m (unbiased: {:.3f}); RMSE at {:.0f} s {:.2f} m; not PD {}\n",
        kPaper002FilterNames[f], kConvergedFraction, t, bias.bias_m, bias.unbiased_floor_m,
        r.time_s.back(), r.filters[f].rmse_x_m.back(), r.not_positive_definite[f]);
  }
  return out;
}

}  // namespace

Reproduction reproduce_paper002(const ReproduceSettings& settings) {
  Paper002Setup setup;
  if (settings.runs) setup.runs = *settings.runs;
  if (settings.seed) setup.seed = *settings.seed;
  fmt::print(
      "paper 002 setup: {} runs x {} steps of {} s; sigma {} m; {} receivers around UAV 1 "
      "({} m baseline); target at {} m, bearing {} rad\n",
      setup.runs, setup.steps, setup.time_step_s, setup.range_difference_std_m,
      setup.receiver_offsets_m.size(), setup.receiver_offsets_m.front().norm(),
      setup.target_range_m, setup.target_bearing_rad);
  const Paper002Result r = run_paper002(setup);
  print_table(r);
  fmt::print("\nat {} m:\n", setup.target_range_m);
  const nlohmann::json near = figures(r, setup.runs);
  // The same formation at twice the range: where the claims stop holding.
  Paper002Setup far_setup = setup;
  far_setup.target_range_m = 2.0 * setup.target_range_m;
  const Paper002Result far = run_paper002(far_setup);
  fmt::print("at {} m (twice the range; not a claim, where it goes):\n", far_setup.target_range_m);
  const nlohmann::json far_figures = figures(far, setup.runs);

  const LateBias nominal = late_bias(r.filters[kNominal], setup.runs);
  const LateBias ncrkf = late_bias(r.filters[kNcrkf], setup.runs);
  const LateBias optimal = late_bias(r.filters[kOptimal], setup.runs);
  const double t_ncrkf = convergence_time(r, r.filters[kNcrkf]);
  const double t_ekf = convergence_time(r, r.filters[kEkf]);
  const double t_nominal = convergence_time(r, r.filters[kNominal]);

  write_csv(r, settings.out_dir / "errors.csv");
  write_csv(far, settings.out_dir / "errors_twice_the_range.csv");
  if (settings.plot &&
      !run_plot_script("plot_paper002.py", {(settings.out_dir / "errors.csv").string(),
                                            (settings.out_dir / "paper002.png").string()})) {
    fmt::print(stderr, "skyfuse: warning: plot not written (needs python3-matplotlib)\n");
  }

  Reproduction out;
  out.paper = "002";
  out.title = fmt::format("TDOA from a UAV formation: NCRKF, nominal, optimal KF and EKF ({} runs)",
                          setup.runs);
  out.claims.push_back(
      {"nominal_kf_biased",
       "the nominal KF is biased: late |mean error| of x / what an unbiased filter shows",
       "degrades sharply", nominal.ratio(), "", nominal.ratio() >= 5.0});
  out.claims.push_back(
      {"ncrkf_unbiased_like_the_optimal_kf",
       "NCRKF matches the optimal KF in mean error: its late |mean error| / an unbiased filter's",
       "NCRKF = optimal", ncrkf.ratio(), "", ncrkf.ratio() <= 2.0 && optimal.ratio() <= 2.0});
  out.claims.push_back({"ekf_converges_slowly",
                        "the EKF converges slowly: its convergence time / the NCRKF's", "slow",
                        t_ekf / t_ncrkf, "", t_ekf > t_ncrkf});
  out.claims.push_back(
      {"ncrkf_converges_fast_at_long_range",
       fmt::format("NCRKF converges fast at {} baselines: fastest implementable filter (s)",
                   setup.target_range_m / setup.receiver_offsets_m.front().norm()),
       "fast", t_ncrkf, "s", t_ncrkf < t_ekf && t_ncrkf < t_nominal});
  out.details = {
      {"runs", setup.runs},
      {"steps", setup.steps},
      {"time_step_s", setup.time_step_s},
      {"seed", setup.seed},
      {"converged_fraction_of_initial_rmse", kConvergedFraction},
      {"range_m", setup.target_range_m},
      {"filters", near},
      {"twice_the_range", {{"range_m", far_setup.target_range_m}, {"filters", far_figures}}},
      {"files", {"errors.csv", "errors_twice_the_range.csv", "paper002.png"}}};
  return out;
}

}  // namespace skyfuse::harness
