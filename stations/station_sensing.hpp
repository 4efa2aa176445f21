#pragma once
// A station's sensor, where its measurements come from (simulated or replayed) and the filter
// part's rule that turns one into the station's contribution, behind an interface that names
// only what the fusion fuses. The station's rounds (station.hpp: the DDS endpoints, the
// exchange, the fusion) are thereby compiled once per fusion, not once per filter part × model
// × sensor kind, and the sensors' arithmetic apart from them, in files without DDS
// (sensing_parts.hpp, sensing_shard.cpp). docs/testing.md#build has what that saves.

#include <skyfuse/wire/skyfuse_wire.h>

#include <cstdint>
#include <memory>

#include "skyfuse/filters/parts/imm_part.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "station_process.hpp"

namespace skyfuse::station {

/// Any station's sensing, as the factory makes it; the station takes it as the interface its
/// fusion names (SensingOf).
class AnyStationSensing {
 public:
  AnyStationSensing() = default;
  AnyStationSensing(const AnyStationSensing&) = delete;
  AnyStationSensing& operator=(const AnyStationSensing&) = delete;
  virtual ~AnyStationSensing() = default;
};

/// The sensing of a fusion that computes a `Contribution` against `Against`: the common prior
/// (a single-model filter, the NCRKF), or the IMM's peer, whose mode priors it mixes.
template <typename AgainstT, typename ContributionT>
class StationSensing : public AnyStationSensing {
 public:
  using Against = AgainstT;
  using Contribution = ContributionT;

  /// The station whose sensing this is.
  virtual int station_id() const = 0;
  /// Takes the measurement of round k; its wire form, for the center and the recorder. Throws
  /// if the source has none for k.
  virtual wire::Measurement measure(std::uint64_t k, std::uint64_t run_id) = 0;
  /// This station's contribution for the measurement last taken, against `prior`: its increment
  /// if the measurement passes `gate`, a zero increment and the reason if it does not.
  virtual OwnContribution contribute(const Against& prior, const NisGate& gate,
                                     Contribution& out) const = 0;
};

/// The sensing of a fusion of one increment per station against the common prior of an N-state
/// (SingleModelFusion, NcrkfFusion).
template <int N>
using IncrementSensing = StationSensing<GaussianState<N>, InformationIncrement<N>>;

/// The sensing of the network IMM of `ModeSet` (ImmFusion): every mode's increment against the
/// peer's mode priors.
template <typename ModeSet>
using ImmSensing = StationSensing<typename NetworkImm<ModeSet>::Peer,
                                  typename NetworkImm<ModeSet>::Peer::Contribution>;

/// The sensing interface of the run's filter part `Filter` on motion model `Model`: the one its
/// fusion (station_fusions.hpp) takes.
template <typename Filter, typename Model>
struct SensingOf {
  using type = IncrementSensing<Model::kDim>;
};
template <typename ModeSet, typename Model>
struct SensingOf<ImmFilterPart<ModeSet>, Model> {
  using type = ImmSensing<ModeSet>;
};

/// Station `me`'s sensing for the run's filter part, model and its own sensor kind: simulated,
/// or replayed from `options.replay_path`. Throws std::invalid_argument if its noise or site is
/// unusable (checked once: they are fixed for the run). Defined in sensing_shard.cpp, per shard
/// of the filter parts.
template <std::size_t Shard>
std::unique_ptr<AnyStationSensing> make_sensing_in_shard(const StationOptions& options,
                                                         const RunPlan& plan,
                                                         const StationConfig& me);

}  // namespace skyfuse::station
