#pragma once

// What a DDS run leaves behind, and the numbers that summarise it.
//   steps.csv         per step: truth, central and peer-to-peer position, their errors, and the
//                     spread between the peers' tracks
//   tracks.csv        per step and source: the full state, printed to round-trip exactly
//   measurements.csv  every station's measurement, in the format `skyfuse-station --replay` reads
//   rounds.csv        per step: round latency (timing: the only file that differs run to run)
//   summary.json      the figures below
// In a lock-step run, everything but rounds.csv and the timing fields and run id of
// summary.json is a pure function of the scenario, the seed and the options: two runs give
// the same bytes. (A real-time run fuses what arrived by each deadline: not reproducible.)

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "run/lockstep_driver.hpp"
#include "run/run_figures.hpp"
#include "skyfuse/random/link_loss.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// Fixed-lag re-fusion: the figures of the settled tracks, each round's final estimate.
struct SettledFigures {
  int tracks = 0;  ///< the center's and the stations'
  int rounds = 0;  ///< rounds with at least one station's settled track
  double rmse_p2p_m = 0.0;
  double rmse_central_m = 0.0;  ///< the center's settled tracks (out-of-sequence updates)
  double max_abs_diff_between_peers = 0.0;
  double peer_spread_end = 0.0;  ///< at the last settled round
};

/// One aircraft's figures beside the house's (run/run_figures.hpp).
struct RunSummary : RunFigures {
  double speed_kmh = 0.0;
  double rmse_central_m = 0.0;
  double rmse_p2p_m = 0.0;
  double max_abs_diff_central_vs_p2p = 0.0;  ///< m, position
  /// Whether the run's filter is the IMM, and the largest difference of a mode probability,
  /// central vs peer-to-peer.
  bool imm = false;
  double max_abs_diff_mode_probability_central_vs_p2p = 0.0;
  /// Over every state and covariance entry, and an IMM run's mode probabilities.
  double max_abs_diff_between_peers = 0.0;
  double peer_spread_end = 0.0;  ///< the same, at the last step only
  /// Per station: rounds in which no peer's track contained it (it was down, restarting, or
  /// every peer lost its increment).
  std::map<int, int> rounds_missing_by_station;
  /// Per restarted station: the first step at which a peer's track contained it again.
  std::map<int, std::uint64_t> rejoin_step_by_station;
  /// Rounds in which some node's track was missing, for whatever reason (a station the run
  /// killed on purpose included).
  int rounds_closed_incomplete = 0;
  double round_latency_us_p50 = 0.0;
  double round_latency_us_p99 = 0.0;
  double round_latency_us_max = 0.0;
  /// Real-time mode (deadline > 0): the share of rounds in which every node fused all M inputs
  /// by the deadline, and the age of the tracks on arrival at the harness (scheduled start of
  /// the step -> received).
  double realtime_deadline_ms = 0.0;
  double rounds_all_inputs_in_time = 0.0;
  double track_age_ms_p50 = 0.0;
  double track_age_ms_p90 = 0.0;
  double track_age_ms_p99 = 0.0;
  double track_age_ms_max = 0.0;
  /// How many tracks arrived within each age (ms, ascending upper bounds; the last unbounded).
  std::vector<std::pair<double, int>> track_age_ms_histogram;
  /// Real time: the steps the schedule had reached when the rounds ended, the furthest any
  /// node's track reached, and how long ago the first step not complete then was due (0 for a
  /// run that completed).
  std::uint64_t realtime_steps_scheduled = 0;
  std::uint64_t realtime_steps_reached = 0;
  double realtime_behind_s = 0.0;
  /// What each node reported when it finished (0: the center): samples refused by kind,
  /// samples lost to the simulated loss, rounds resynchronised.
  std::map<int, NodeCounts> node_counts;
  /// The settings that shape the rounds, echoed into summary.json.
  double round_deadline_ms = 0.0;
  LinkLoss loss;
  bool best_effort = false;
  int hosts = 0;  ///< simulated hosts the processes ran on (0: this host)
  std::size_t refusion_lag = 0;
  std::optional<SettledFigures> settled;  ///< none: no station re-fused
};

/// A station the harness kills (SIGKILL) or starts again, before the round of `step`.
struct StationEvent {
  int station_id = 0;
  std::uint64_t step = 0;
};

class RunRecorder {
 public:
  /// `restarts`: the stations started again during the run, for rejoin_step_by_station.
  RunRecorder(const RunPlan& plan, std::vector<int> station_ids,
              std::vector<StationEvent> restarts = {});
  void add(RoundRecord round);

  RunSummary summarise(double discovery_s, double rounds_elapsed_s) const;
  /// The settled (re-fused) tracks of a run with --refusion-lag, by (step, source id):
  /// tracks.csv lists them after the live ones.
  void set_settled(std::map<std::pair<std::uint64_t, int>, ReceivedTrack> settled);
  /// Refusals reported after the last round (the nodes' last statuses): refusals.csv lists
  /// them after the rounds', as reported in round `steps`.
  void set_refusals_after_run(std::vector<Refusal> refused) {
    refusals_after_run_ = std::move(refused);
  }
  /// The settled tracks' figures, none if there are none.
  std::optional<SettledFigures> summarise_settled() const;
  void write(const std::filesystem::path& dir, const RunSummary& summary,
             std::uint64_t run_id) const;
  /// summary.json's text.
  std::string summary_json(const RunSummary& summary, std::uint64_t run_id) const;

  // What a recording of the run reads (report/run_channels.hpp).
  const RunPlan& plan() const { return plan_; }
  const std::vector<int>& station_ids() const { return station_ids_; }  ///< ascending
  const std::vector<RoundRecord>& rounds() const { return rounds_; }
  const std::vector<std::string_view>& mode_names() const { return mode_names_; }
  int position_dim() const { return model_.position_dim; }
  Vector3 position_of(const ReceivedTrack& track) const;
  Vector3 truth_position(std::uint64_t step) const;

 private:
  const RunPlan& plan_;
  std::vector<int> station_ids_;
  std::vector<StationEvent> restarts_;
  TruthTrajectory truth_;
  // The run's motion model: every track's state dimension, and its leading entries that are the
  // position (models/state_position.hpp).
  MotionModelInfo model_;
  std::vector<std::string_view> mode_names_;  // the filter's modes (none: one model)
  std::vector<RoundRecord> rounds_;
  std::map<std::pair<std::uint64_t, int>, ReceivedTrack> settled_;
  std::vector<Refusal> refusals_after_run_;

  // measurements.csv: `step,station_id,` and the sensor's components when every participant
  // has the same sensor (what --replay reads), else `step,station_id,sensor,z0,z1,...`.
  bool one_sensor_kind() const;
  std::string sensor_kind_of(int station_id) const;
  std::string measurements_header() const;
};

void print_run_table(const RunSummary& s, std::FILE* out);

}  // namespace skyfuse::harness
