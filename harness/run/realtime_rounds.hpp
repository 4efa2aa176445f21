#pragma once
// The bookkeeping of a real-time run. Nodes step on their own clocks, so the tracks and
// measurements of several steps arrive interleaved; each step is held until every node's track
// and every station's measurement is in, and complete steps leave in step order. A sample can
// be lost for good (best-effort measurements, a reliable writer's history overrun under load),
// so a step also leaves, with what it has, once a step kLostAfterSteps later has every track:
// what has not come by then is not coming. No DDS: the driver reads the samples and screens
// their content; this decides where each one goes.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "run/round_record.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

class RealtimeRounds {
 public:
  /// How far a later step must have got (every node's track in) before an incomplete step is
  /// given up on: 1 s at 50 Hz, far beyond any deadline a node closes its rounds at.
  static constexpr std::uint64_t kLostAfterSteps = 50;

  /// `station_ids` ascending; the run has steps 0 .. steps - 1.
  RealtimeRounds(std::vector<int> station_ids, std::uint64_t steps);

  /// Why a track of `source` (kCenterNodeId or a station) for `step` cannot be kept, if it
  /// cannot: an unknown source, a step past the run's end, a step already handed over. Every
  /// other step of the run is open: in real time the nodes run ahead of each other by design.
  std::optional<DropKind> check_track(int source, std::uint64_t step) const;
  /// check_track, then keeps the track unless the source's track for the step is already in
  /// (kDuplicate). `age_us`: scheduled step start -> received. A track that fused fewer than
  /// every station marks its step as not all inputs in time.
  std::optional<DropKind> offer_track(int source, std::uint64_t step, ReceivedTrack track,
                                      double age_us);

  /// The same for a station's measurement (the center has none).
  std::optional<DropKind> check_measurement(int station, std::uint64_t step) const;
  std::optional<DropKind> offer_measurement(int station, std::uint64_t step,
                                            const Eigen::VectorXd& z);

  /// Appends to `done` every complete step next in order, its latency the age of its oldest
  /// track; returns how many steps have been handed over in all.
  std::uint64_t hand_over(std::vector<RoundRecord>& done);
  /// When the run stops early: hands over every step up to the furthest any track reached,
  /// complete or not (what has not arrived is lost), so that the files hold what arrived.
  std::uint64_t hand_over_rest(std::vector<RoundRecord>& done);

  /// Samples given up on so far: tracks (a node's round that never reached the harness; its
  /// step counts as not all inputs in time) and measurements.
  std::uint64_t tracks_lost() const { return tracks_lost_; }
  /// How many steps the nodes have got to: one past the furthest step any track was kept for.
  std::uint64_t steps_reached() const { return steps_reached_; }
  std::uint64_t measurements_lost() const { return measurements_lost_; }

 private:
  struct Pending {
    RoundRecord record;
    std::size_t tracks = 0;
    std::size_t measurements = 0;
  };
  /// 0 for the center, 1..M for the stations by id; nothing for an id not in the run.
  std::optional<std::size_t> slot(int node) const;
  std::optional<DropKind> check_step(std::uint64_t step) const;
  // Hands over the next step, whatever it holds.
  void hand_over_next(std::vector<RoundRecord>& done);
  Pending& pending_step(std::uint64_t step);

  std::vector<int> station_ids_;
  std::uint64_t steps_;
  std::uint64_t handed_over_ = 0;
  std::map<std::uint64_t, Pending> pending_;
  std::uint64_t tracks_lost_ = 0;
  std::uint64_t measurements_lost_ = 0;
  std::uint64_t steps_reached_ = 0;
};

}  // namespace skyfuse::harness
