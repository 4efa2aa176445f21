#pragma once
/// \file
/// Which filter part and motion model a picture runs, as types: the peers' and the center's
/// track filters (track_filters.hpp) of the scenario's filter part on its model. The stations'
/// sensors are values (picture_sensor.hpp), so a picture is compiled once per filter part and
/// model, whatever sensors its stations carry. The in-process picture (sim/picture_run.hpp) and
/// the station and center processes pick them by the same rule, so that they run the same
/// arithmetic.

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "skyfuse/models/state_position.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/increment_rules.hpp"

namespace skyfuse {

/// The peers' and the center's track filters of filter part `Filter` on `Model`: a part with an
/// increment rule by that rule (the EKF's center stacks, another part's fuses its own
/// increments), the IMM by its network form.
template <typename Filter, typename Model>
struct PictureParts {
  using Rule = typename Filter::IncrementRule;
  using Peer = PeerModelTracks<Model, Rule>;
  using Center = std::conditional_t<std::is_same_v<Filter, EkfFilterPart>,
                                    CenterStackedTracks<Model>, CenterIncrementTracks<Model, Rule>>;
  static Peer peer(const Scenario& s) {
    return Peer(make_motion_model<Model>(s), s.filter.initial_covariance_diag,
                s.tracker.updater.relinearisations);
  }
  static Center center(const Scenario& s) {
    return Center(make_motion_model<Model>(s), s.filter.initial_covariance_diag,
                  s.tracker.updater.relinearisations);
  }
};
template <typename Set, typename Model>
struct PictureParts<ImmFilterPart<Set>, Model> {
  using Peer = PeerImmTracks<Set>;
  using Center = CenterImmTracks<Set>;
  static Peer peer(const Scenario& s) { return Peer(s); }
  static Center center(const Scenario& s) { return Center(s); }
};

/// Whether a picture runs filter part `Filter` on `Model`: a part with an increment rule or the
/// IMM, that names no sensor of its own, on a model that keeps a 3-D position (a picture's sensors
/// read one: fixes_position.hpp). No other pair is compiled for a picture.
template <typename Filter, typename Model>
constexpr bool picture_runs() {
  constexpr bool kIncrements = requires {
    typename Filter::IncrementRule;
  };
  constexpr bool kImm = !Filter::kModeNames.empty();
  return (kIncrements || kImm) && Filter::kSensor.empty() &&
         filter_runs_on_model<Filter, Model>() && position_dim<Model>() == 3;
}

/// Calls f(std::type_identity<PictureParts<...>>{}) for `scenario`'s filter part on its motion
/// model, if that group lies in shard `Shard` and a picture runs it (picture_runs). Returns
/// whether it called f.
template <std::size_t Shard, typename F>
bool visit_picture_parts_in_shard(const Scenario& scenario, F&& f) {
  bool called = false;
  visit_group_in_shard<Shard>(
      scenario.filter,
      [&]<typename Filter, typename Model>(std::type_identity<Filter>, std::type_identity<Model>) {
        if constexpr (picture_runs<Filter, Model>()) {
          f(std::type_identity<PictureParts<Filter, Model>>{});
          called = true;
        }
      });
  return called;
}

/// Calls f(std::type_identity<PictureParts<...>>{}) for every group of shard `Shard` that a
/// picture runs: what the shard compiles the pictures for.
template <std::size_t Shard, typename F>
constexpr void for_each_picture_parts_in_shard(F&& f) {
  for_each_group_in_shard<Shard>(
      [&]<typename Filter, typename Model>(std::type_identity<Filter>, std::type_identity<Model>) {
        if constexpr (picture_runs<Filter, Model>()) {
          f(std::type_identity<PictureParts<Filter, Model>>{});
        }
      });
}

/// The state sizes of the tracks of every picture this build compiles (peers' and center's,
/// every shard), ascending, each once: what the code a size alone decides is compiled for
/// (state_size_code.hpp); and at each, whether a picture of it relinearises and keeps its tracks'
/// cross-covariances with the bias errors (the EKF's: PeerModelTracks::kRelinearises).
struct PictureStateSizes {
  std::array<int, 2 * kConfigurationGroups> sizes{};
  std::array<bool, 2 * kConfigurationGroups> linearises{};
  std::size_t count = 0;
};
constexpr PictureStateSizes picture_state_sizes() {
  PictureStateSizes out;
  const auto add = [&](int size, bool linearises) {
    std::size_t at = 0;
    while (at < out.count && out.sizes[at] < size) ++at;
    if (at == out.count || out.sizes[at] != size) {
      for (std::size_t i = out.count; i > at; --i) {
        out.sizes[i] = out.sizes[i - 1];
        out.linearises[i] = out.linearises[i - 1];
      }
      out.sizes[at] = size;
      out.linearises[at] = false;
      ++out.count;
    }
    out.linearises[at] = out.linearises[at] || linearises;
  };
  [&]<std::size_t... Shard>(std::index_sequence<Shard...>) {
    (for_each_picture_parts_in_shard<Shard>([&]<typename Parts>(std::type_identity<Parts>) {
       using Peer = typename Parts::Peer;
       constexpr bool kLinearises = [] {
         if constexpr (requires { Peer::kRelinearises; }) {
           return Peer::kRelinearises;
         } else {
           return false;
         }
       }();
       add(Peer::kDim, kLinearises);
       add(Parts::Center::kDim, kLinearises);
     }),
     ...);
  }
  (std::make_index_sequence<kFilterShards>{});
  return out;
}

}  // namespace skyfuse
