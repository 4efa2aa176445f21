#include "report/picture_report.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "report/registration_report.hpp"
#include "skyfuse/metrics/nees_over_runs.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse::harness {
namespace {

// The runs' ANEES, both tests of whether it is 1 (metrics/nees_over_runs.hpp).
std::optional<NeesOverRuns> anees_of_runs(const PictureReport& report) {
  std::vector<RunNees> runs;
  runs.reserve(report.runs.size());
  for (const PictureRunResult& run : report.runs) {
    runs.push_back({run.anees, run.nees_dof, run.nees_samples});
  }
  return nees_over_runs(runs);
}

}  // namespace

bool picture_guarantees_held(const PictureReport& report) {
  for (const auto& run : report.runs) {
    if (!run.peers_identical || run.association_flips != 0) return false;
  }
  return true;
}

void print_picture_table(const PictureReport& report, std::FILE* out) {
  const TrafficConfig& traffic = *report.scenario.traffic;
  const int stations = report.runs.empty() ? 0 : report.runs.front().stations;
  fmt::print(out, "scenario {}: {} aircraft, {} stations, {} steps of {} s\n", report.scenario.name,
             report.truth.targets.size(), stations, report.scenario.steps,
             report.scenario.time_step_s);
  if (report.truth.recorded) {
    const RecordedTraffic& r = *report.truth.recorded;
    fmt::print(out,
               "recorded file: {} rows; skipped {} on the ground, {} without position, {} stale, "
               "{} repeated; {} single-sample flights dropped\n",
               r.rows, r.rows_on_ground, r.rows_without_position, r.stale_rows,
               r.repeated_position_rows, r.single_sample_aircraft);
  }
  fmt::print(out,
             "{:>4} {:>8} {:>8} {:>8} {:>8} {:>8} {:>7} {:>7} {:>7} {:>6} {:>8} {:>7} {:>6} {:>6} "
             "{:>9}\n",
             "run", "GOSPA_m", "all_m", "loc_m", "missed", "false", "compl", "ambig", "spur", "ids",
             "confirm_s", "ANEES", "peers", "flips", "gap");
  for (std::size_t r = 0; r < report.runs.size(); ++r) {
    const PictureRunResult& run = report.runs[r];
    const PictureSummary& s = run.score;
    fmt::print(
        out,
        "{:>4} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.2f} {:>8.2f} {:>7.4f} {:>7.4f} {:>7.4f} {:>6} "
        "{:>8.2f} {:>7.3f} {:>6} {:>6} {:>9.2e}\n",
        r, s.in_view.distance, s.gospa_mean, s.localisation_per_pair_m, s.missed_mean, s.false_mean,
        s.completeness, s.ambiguity, s.spuriousness, s.track_number_changes,
        s.mean_time_to_confirm_s, run.anees / run.nees_dof, run.peers_identical ? "same" : "DIFF",
        run.association_flips, run.max_state_gap);
  }
  if (const auto anees = anees_of_runs(report)) {
    fmt::print(out,
               "ANEES per dof over {} samples: {:.3f} (95 % band of a consistent filter, the "
               "samples taken as independent: [{:.3f}, {:.3f}]; from the spread of the {} runs, "
               "the mean lies in [{:.3f}, {:.3f}], the runs varying {:.1f}x as independent "
               "samples would)\n",
               anees->samples, anees->over_runs.mean, anees->pooled_band.lower,
               anees->pooled_band.upper, anees->runs, anees->over_runs.lower,
               anees->over_runs.upper, anees->variance_over_independent);
  }
  fmt::print(out,
             "GOSPA: cut-off {} m, p = {}, alpha = 2, mean per step, over the aircraft in some "
             "station's view (all_m: over every aircraft); loc_m: the localisation error per "
             "assigned track (RMS for p = 2); missed/false: their parts over every aircraft, m^p "
             "per step\n",
             traffic.gospa.cutoff_m, traffic.gospa.order);
  fmt::print(out,
             "peers: every peer's picture bit-identical every round ({}); flips: "
             "association pairs the center decided otherwise; gap: max relative state "
             "difference center vs peers\n",
             picture_guarantees_held(report) ? "held" : "NOT HELD");
}

void write_picture_csv(const PictureReport& report, const std::filesystem::path& path) {
  auto out = fmt::output_file(path.string());
  out.print(
      "run,step,aircraft,confirmed_tracks,gospa_m,localisation,missed,false_tracks,tracked,"
      "spurious,gospa_in_view_m,localisation_in_view,missed_in_view,false_tracks_in_view\n");
  for (std::size_t r = 0; r < report.runs.size(); ++r) {
    for (const PictureStep& row : report.runs[r].steps) {
      const Gospa& seen = row.gospa_in_view;
      out.print("{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{:.6f},{:.6f},{:.6f},{:.6f}\n", r,
                row.step, row.aircraft, row.tracks, row.gospa.distance, row.gospa.localisation,
                row.gospa.missed, row.gospa.false_tracks, row.tracked, row.spurious, seen.distance,
                seen.localisation, seen.missed, seen.false_tracks);
    }
  }
}

void write_picture_json(const PictureReport& report, const std::filesystem::path& path) {
  nlohmann::json runs = nlohmann::json::array();
  for (const PictureRunResult& run : report.runs) {
    const PictureSummary& s = run.score;
    runs.push_back({{"gospa_mean_m", s.gospa_mean},
                    {"localisation_mean", s.localisation_mean},
                    {"localisation_per_pair_m", s.localisation_per_pair_m},
                    {"missed_mean", s.missed_mean},
                    {"false_mean", s.false_mean},
                    {"in_view",
                     {{"gospa_mean_m", s.in_view.distance},
                      {"localisation_mean", s.in_view.localisation},
                      {"missed_mean", s.in_view.missed},
                      {"false_mean", s.in_view.false_tracks}}},
                    {"addressed_in_view",
                     {{"gospa_mean_m", s.addressed_in_view.distance},
                      {"localisation_mean", s.addressed_in_view.localisation},
                      {"missed_mean", s.addressed_in_view.missed},
                      {"false_mean", s.addressed_in_view.false_tracks}}},
                    {"completeness", s.completeness},
                    {"ambiguity", s.ambiguity},
                    {"duplicate_track_steps", s.duplicate_track_steps},
                    {"duplicate_track_steps_addressed", s.duplicate_track_steps_addressed},
                    {"spuriousness", s.spuriousness},
                    {"track_number_changes", s.track_number_changes},
                    {"aircraft_detected", s.aircraft_detected},
                    {"aircraft_confirmed", s.aircraft_confirmed},
                    {"mean_time_to_confirm_s", s.mean_time_to_confirm_s},
                    {"anees", run.anees},
                    {"nees_dof", run.nees_dof},
                    {"nees_samples", run.nees_samples},
                    {"peers_identical", run.peers_identical},
                    {"association_flips", run.association_flips},
                    {"associations", run.associations},
                    {"max_state_gap", run.max_state_gap},
                    {"detections", run.detections},
                    {"false_alarms", run.false_alarms},
                    {"dropped_detections", run.dropped},
                    {"refused_addresses", run.refused_addresses},
                    {"merged_tracks", run.merged_tracks},
                    {"confirmed_at_end", run.confirmed_at_end},
                    {"tentative_at_end", run.tentative_at_end}});
    if (!run.registration.empty()) {
      runs.back()["registration"] = registration_json(run, report.scenario.time_step_s);
    }
  }
  const TrafficConfig& traffic = *report.scenario.traffic;
  nlohmann::json summary = {
      {"scenario", report.scenario.name},
      {"aircraft", report.truth.targets.size()},
      {"steps", report.scenario.steps},
      {"gospa", {{"cutoff_m", traffic.gospa.cutoff_m}, {"order", traffic.gospa.order}}},
      {"guarantees_held", picture_guarantees_held(report)},
      {"runs", runs}};
  if (const auto anees = anees_of_runs(report)) {
    summary["anees_per_dof"] = {
        {"mean", anees->over_runs.mean},
        {"samples", anees->samples},
        {"band_of_independent_samples", {anees->pooled_band.lower, anees->pooled_band.upper}},
        {"interval_from_runs", {anees->over_runs.lower, anees->over_runs.upper}},
        {"variance_over_independent", anees->variance_over_independent}};
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write", path.string()));
  out << summary.dump(2) << '\n';
}

}  // namespace skyfuse::harness
