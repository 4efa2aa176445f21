#pragma once
// `skyfuse run` of a scenario with many aircraft: one station process per participant and the
// fusion center over DDS, in lock-step or in real time. Each round the harness publishes the tick
// (lock-step) and waits for every node's picture (every track and the picture's digest); it
// compares the digests of every peer with each other and with the in-process run's
// (sim/picture_run.hpp), the center's with its in-process twin's and its states with the peers',
// round by round, and writes them, and with --record every round's picture, scans and scores
// (report/picture_recording.hpp). With --loss, or a station killed and restarted, peers part
// when they miss different scans and come together again by taking the lowest station's picture
// (stations/picture_station.cpp). The options a run of many aircraft does not take yet are
// refused with a message.

#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <string>

#include "run/lockstep_driver.hpp"
#include "run/run_figures.hpp"
#include "run/run_options.hpp"
#include "run/run_stopped_early.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/asterix_replay.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// Many aircraft's figures beside the house's (run/run_figures.hpp).
struct PictureRunSummary : RunFigures {
  std::string scenario;
  /// Every station's picture digest equal in every round.
  bool peers_identical = true;
  int first_divergent_step = -1;
  /// Rounds in which some station's picture differed from another's, and the last of them.
  int rounds_peers_apart = 0;
  int last_round_peers_apart = -1;
  bool loss = false;          ///< --loss: stations and center missed samples
  bool faults = false;        ///< --loss or --kill: the pictures part from the in-process run
  bool realtime = false;      ///< on the wall clock: a late scan parts the pictures too
  std::uint64_t lost = 0;     ///< samples the simulated loss removed, every node
  std::uint32_t resyncs = 0;  ///< rounds a station took the lowest station's picture
  /// Samples each node (0: the center) refused, by kind, as it reported when it finished.
  std::map<int, DropCounts> dropped_by_node;
  /// GOSPA of the first station's confirmed tracks, mean over rounds, and the in-process run's.
  double gospa_mean = 0.0;
  double in_process_gospa_mean = 0.0;
  /// The same over the aircraft in some station's view (metrics/picture_score.hpp).
  double gospa_in_view_mean = 0.0;
  double in_process_gospa_in_view_mean = 0.0;
  /// Every round's digest equal to the in-process run's.
  bool equals_in_process = true;
  int first_step_apart_from_in_process = -1;
  /// The center's digest equal to its in-process run's in every round.
  bool center_equals_in_process = true;
  int first_step_center_apart_from_in_process = -1;
  /// Over rounds and the tracks both hold: |x_center - x_p2p| / (1 + |x_center|).
  double max_state_gap_center_vs_p2p = 0.0;
  /// Rounds whose center holds other tracks (ids, statuses) than the peers.
  int rounds_center_tracks_differ = 0;
  /// Rounds whose every node's picture came and every station fused every station's scan
  /// (in real time: in time), and rounds no station's picture came for.
  int rounds_in_time = 0;
  int rounds_without_a_picture = 0;
  std::size_t tracks_at_end = 0;
  std::size_t confirmed_at_end = 0;
  std::uint64_t digest_at_end = 0;
  /// `--asterix-replay`: what the feed file held and what of it was refused, by kind.
  std::optional<transport::AsterixFeedCounts> asterix_feed;
};

/// Runs `plan` as `o` says, writing picture_rounds.csv and
/// summary.json into o.out_dir. Throws std::invalid_argument for an option it does not take,
/// RunAborted when the run fails, StoppedEarlyWith<PictureRunSummary> when its rounds began
/// but did not all complete (with the files of the rounds recorded).
PictureRunSummary execute_picture_run(const RunOptions& o, const PicturePlan& plan);

}  // namespace skyfuse::harness
