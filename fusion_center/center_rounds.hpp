#pragma once
// The center's rounds as the DDS side sees them: measurements in, tracks out. What updates them
// (the run's filter part on the stations' sensor kind, in the fixed-lag chain) is behind this
// interface, compiled by shard of the configuration groups in files without DDS
// (typed_center_rounds.hpp, center_rounds_shard.cpp), so that the center's endpoints and round
// loop (center.hpp) are compiled once. docs/testing.md#build has what that saves.

#include <skyfuse/wire/skyfuse_wire.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::center {

/// Called for a measurement the round rule refused at fusion: (station id, why).
using OnRefused = std::function<void(int, DropKind)>;

class CenterRounds {
 public:
  CenterRounds() = default;
  CenterRounds(const CenterRounds&) = delete;
  CenterRounds& operator=(const CenterRounds&) = delete;
  virtual ~CenterRounds() = default;

  /// Checks a received measurement (garbage whoever sent it; then who it claims to be and when;
  /// then whether the writer really speaks for that station) and keeps it; why not if it did
  /// not.
  virtual std::optional<DropKind> receive(const wire::Measurement& sample,
                                          const transport::WriterId& writer) = 0;
  /// Every station's measurement of the current round is in.
  virtual bool round_complete() const = 0;
  /// Updates the current round with the measurements that arrived, screened by `gate` and
  /// stacked by the round rule (and, with a re-fusion lag, the rounds late ones came for).
  virtual NumericalStatus close_round(const NisGate& gate, const OnRefused& on_refused) = 0;
  /// Round `step`'s latest track, while it is in the lag (the current round's after
  /// close_round()).
  virtual const wire::TrackEstimate& track_of(std::uint64_t step) const = 0;
  /// The round whose track the last close_round() made final, if a lag holds one.
  virtual std::optional<std::uint64_t> settled_round() const = 0;
  /// Closes the round: the next one's measurements are awaited.
  virtual void advance() = 0;
  /// After the last round, with a re-fusion lag: the rounds late measurements came for, updated
  /// again; the rounds [first, second) whose tracks are final now.
  virtual std::pair<std::uint64_t, std::uint64_t> settle_rest(const NisGate& gate,
                                                              NumericalStatus& status) = 0;
  /// Measurements kept although their round had closed (re-fused), so far.
  virtual std::uint64_t late_used() const = 0;
  /// Logs what the fusion measured over the run, if it measures anything.
  virtual void report() const {}
};

/// The center's rounds for `plan`, whose filter part and motion model lie in shard `Shard` and
/// whose stations' sensor in sensor part `Part`. Defined in typed_center_rounds.hpp, instantiated
/// per shard and part by center_rounds_shard.cpp.
template <std::size_t Shard, std::size_t Part>
std::unique_ptr<CenterRounds> make_center_rounds_in_shard(const options::NodeOptions& options,
                                                          const RunPlan& plan);

}  // namespace skyfuse::center
