#include "report/registration_report.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace skyfuse::harness {
namespace {

// A registration's estimate is judged at 2σ, the band: a consistent estimator ends
// inside it in about 95 % of the runs per entry.
constexpr double kSigmas = 2.0;

}  // namespace

void print_registration_table(const PictureReport& report, std::FILE* out) {
  if (report.runs.empty() || report.runs.front().registration.empty()) return;
  const double dt = report.scenario.time_step_s;
  fmt::print(out, "registration: each station's estimate at the end (mean over {} runs)\n",
             report.runs.size());
  fmt::print(out, "{:>7} {:>13} {:>12} {:>12} {:>12} {:>9} {:>11} {:>11}\n", "station", "entry",
             "truth", "estimate", "sigma", "in_2sigma", "converged", "conv_s");
  const std::size_t stations = report.runs.front().registration.size();
  for (std::size_t s = 0; s < stations; ++s) {
    const BiasTrace& first = report.runs.front().registration[s];
    int within = 0;
    int converged = 0;
    double converged_s = 0.0;
    for (const PictureRunResult& run : report.runs) {
      const BiasTrace& trace = run.registration[s];
      if (trace.estimate.empty()) continue;
      within += within_sigmas(trace, trace.estimate.size() - 1, kSigmas) ? 1 : 0;
      const int from = converged_from(trace, kSigmas);
      if (from >= 0) {
        ++converged;
        converged_s += (from + 1) * dt;
      }
    }
    for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
      if (!first.estimated[e]) continue;
      double estimate = 0.0;
      double sigma = 0.0;
      for (const PictureRunResult& run : report.runs) {
        const BiasTrace& trace = run.registration[s];
        if (trace.estimate.empty()) continue;
        estimate += bias_entry(trace.estimate.back(), e);
        sigma += bias_entry(trace.sigma.back(), e);
      }
      const auto n = static_cast<double>(report.runs.size());
      fmt::print(
          out, "{:>7} {:>13} {:>12.6g} {:>12.6g} {:>12.6g} {:>9} {:>11} {:>11}\n", first.station_id,
          BiasTrace::kEntries[e], bias_entry(first.truth, e), estimate / n, sigma / n,
          fmt::format("{}/{}", within, report.runs.size()),
          fmt::format("{}/{}", converged, report.runs.size()),
          converged == 0 ? std::string("-") : fmt::format("{:.1f}", converged_s / converged));
    }
  }
  fmt::print(out,
             "in_2sigma: runs whose every entry of the station ends within 2 sigma of its truth; "
             "converged: runs where they stay so from some round on; conv_s: the mean time to "
             "that round\n");
}

void write_registration_csv(const PictureReport& report, const std::filesystem::path& path) {
  auto out = fmt::output_file(path.string());
  out.print("run,step,station,entry,estimate,sigma,truth\n");
  for (std::size_t r = 0; r < report.runs.size(); ++r) {
    for (const BiasTrace& trace : report.runs[r].registration) {
      for (std::size_t k = 0; k < trace.estimate.size(); ++k) {
        for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
          if (!trace.estimated[e]) continue;
          out.print("{},{},{},{},{:.9g},{:.9g},{:.9g}\n", r, k, trace.station_id,
                    BiasTrace::kEntries[e], bias_entry(trace.estimate[k], e),
                    bias_entry(trace.sigma[k], e), bias_entry(trace.truth, e));
        }
      }
    }
  }
}

nlohmann::json registration_json(const PictureRunResult& run, double time_step_s) {
  nlohmann::json stations = nlohmann::json::array();
  for (const BiasTrace& trace : run.registration) {
    nlohmann::json entries = nlohmann::json::object();
    for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
      if (!trace.estimated[e] || trace.estimate.empty()) continue;
      entries[BiasTrace::kEntries[e]] = {{"truth", bias_entry(trace.truth, e)},
                                         {"estimate", bias_entry(trace.estimate.back(), e)},
                                         {"sigma", bias_entry(trace.sigma.back(), e)}};
    }
    const int from = converged_from(trace, kSigmas);
    stations.push_back(
        {{"station", trace.station_id},
         {"entries", entries},
         {"within_2sigma_at_end",
          !trace.estimate.empty() && within_sigmas(trace, trace.estimate.size() - 1, kSigmas)},
         {"converged_from_step", from},
         {"converged_after_s",
          from < 0 ? nlohmann::json(nullptr) : nlohmann::json((from + 1) * time_step_s)}});
  }
  return {{"stations", stations}, {"max_center_gap", run.max_bias_gap}};
}

}  // namespace skyfuse::harness
