#pragma once
/// \file
/// One in-process run of a scenario with many aircraft: every station's scan simulated, M peers
/// that each assign only their own station's scan and fuse everyone's reports
/// (picture/peer_picture.hpp), and the center on the raw scans
/// (picture/central_picture.hpp), all in one process, with the filter part, motion model
/// and sensor the scenario names. It checks as it goes that every peer holds the same picture
/// bit for bit and how far the center's is from it, and scores the peers' picture against the
/// truth (metrics/picture_score.hpp).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "skyfuse/metrics/picture_score.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/registration/bias_trace.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

struct PictureRunResult {
  PictureSummary score;
  std::vector<PictureStep> steps;
  int stations = 0;
  /// Every peer's picture (ids, statuses, histories, states) equal bit for bit every round.
  bool peers_identical = true;
  int first_divergent_step = -1;
  /// The first peer's picture digest after each round (TrackTable::digest): what a run over
  /// DDS compares its peers' with.
  std::vector<std::uint64_t> peer_digests;
  /// The center's picture digest after each round.
  std::vector<std::uint64_t> center_digests;
  /// Association pairs (station, detection, track) the center and the peers decided
  /// differently, over the run: 0 unless a decision at a gate's edge flipped.
  std::size_t association_flips = 0;
  std::size_t associations = 0;  ///< pairs the peers made
  /// max over rounds and tracks both hold of |x_center - x_p2p| / (1 + |x_center|).
  double max_state_gap = 0.0;
  std::size_t detections = 0;
  std::size_t false_alarms = 0;
  std::size_t dropped = 0;  ///< detections beyond the assignment's bound
  /// Addressed detections refused as possible spoofs (picture/identity.hpp).
  std::size_t refused_addresses = 0;
  /// Tracks without an address dropped as holding the aircraft of a track with one
  /// (picture/track_merge.hpp), the first peer's.
  std::size_t merged_tracks = 0;
  /// NEES of the confirmed tracks associated with an aircraft, averaged; dof per sample.
  double anees = 0.0;
  int nees_dof = 0;
  std::size_t nees_samples = 0;
  std::size_t confirmed_at_end = 0;
  std::size_t tentative_at_end = 0;
  /// Each station's registration round by round (the first peer's; every peer's is the same
  /// bits), where the scenario registers its stations; empty otherwise.
  std::vector<BiasTrace> registration;
  /// The largest difference between the center's bias estimates and the first peer's, over
  /// the run, relative to 1 + |peer's|.
  double max_bias_gap = 0.0;
};

/// What a run does to station `station`'s (index) simulated scan before any tracker sees it:
/// a run fed its own ASTERIX recording quantises each scan as the items hold it
/// (transport/scan_asterix.hpp), say. None by default.
using ScanFilter = std::function<void(std::size_t station, Scan& scan)>;

/// Runs `scenario` (a run of many aircraft, sim/run_kind.hpp) with its first `stations` stations
/// against `truth`, Monte-Carlo run `run`; `on_step` hears of each step's figures, and
/// `scan_filter`, where given, has each simulated scan first.
PictureRunResult run_picture(const Scenario& scenario, const std::vector<TargetTruth>& truth,
                             int stations, std::uint64_t run,
                             const std::function<void(const PictureStep&)>& on_step = {},
                             const ScanFilter& scan_filter = {});

}  // namespace skyfuse
