// The EKF center's stacked update of a track's detections (picture/track_filters.hpp),
// once for each motion model an EKF's picture runs on.
#include <optional>
#include <span>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse {

template <typename Model>
bool CenterStackedTracks<Model>::update(State& state,
                                        std::span<const PictureObservation<kDim>> observations,
                                        std::span<const double> weights) {
  if (relinearisations_ > 0) {
    return relinearised_.update(state, observations, weights, [&](const auto& o, auto& out) {
      return compute_increment(o.station_id, relinearised_prior(state, o, relinearisations_),
                               o.sensor, o.z, o.noise, out);
    });
  }
  State updated = state;
  const UpdateReport report = by_sensor_kind<kDim>(
      observations, buffers_,
      [&]<typename Sensor>(std::span<const StationObservation<Sensor>> one_kind) {
        return std::get<StackedEkf<kDim, Sensor>>(stacked_).update(updated, one_kind);
      },
      [&] { return mixed_.update(updated, observations); });
  if (report.status != NumericalStatus::kOk) return false;
  state = updated;
  return true;
}

template <typename Model>
bool CenterStackedTracks<Model>::update_considered(
    State& state, ConsideredBiases& considered,
    std::span<const PictureObservation<kDim>> observations,
    std::span<const ConsideredObservation> registered, std::span<const double> weights) {
  // Each observation's increment and, for a registered station's, its terms, as a peer's
  // report computes them (PeerPicture::add_considered), against this track's prior linearised
  // where the tracker says (the prior itself unless it relinearises).
  auto& increments = considered_work_.increments;
  auto& terms = considered_work_.terms;
  auto& term_weights = considered_work_.term_weights;
  increments.resize(observations.size());
  terms.clear();
  term_weights.clear();
  auto next = registered.begin();
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const bool ok = std::visit(
        [&](const auto& o) {
          // The prior itself unless the tracker relinearises: no copy on the default path.
          std::optional<State> moved;
          if (relinearisations_ > 0) moved = relinearised_prior(state, o, relinearisations_);
          const State& at = moved ? *moved : state;
          if (compute_increment(o.station_id, at, o.sensor, o.z, o.noise, increments[i]) !=
              NumericalStatus::kOk) {
            return false;
          }
          if (next == registered.end() || next->observation != i) return true;
          ConsideredTerms one;
          if (!considered_terms(o.station_id, at, o.sensor, o.z, o.noise, next->g_scaled, one)) {
            return false;
          }
          ++next;
          // A station with several detections of the track (JPDA's) adds theirs up.
          if (!terms.empty() && terms.back().station_id == one.station_id) {
            terms.back().add_weighted(one, 1.0);
          } else {
            terms.push_back(std::move(one));
            term_weights.push_back(weights[i]);
          }
          return true;
        },
        observations[i]);
    if (!ok) return false;
  }
  return fuse_considered(state, considered, std::span<const InformationIncrement<kDim>>(increments),
                         weights, terms, term_weights) == NumericalStatus::kOk;
}

// Compiled for every motion model an EKF's picture runs on (picture_parts.hpp, picture_runs),
// where this build compiles the EKF: naming the rounds by their address makes the compiler
// compile them here, and `used` keeps them for the linker.
void keep_center_stacked_tracks() {
  []<typename... Models>(ModelList<Models...>) {
    const auto keep = []<typename Model>(std::type_identity<Model>) {
      if constexpr (picture_runs<EkfFilterPart, Model>() &&
                    filter_part_compiled(EkfFilterPart::kKind)) {
        [[gnu::used]] static constexpr auto kRounds = std::tuple{
            &CenterStackedTracks<Model>::update, &CenterStackedTracks<Model>::update_considered};
      }
    };
    (keep(std::type_identity<Models>{}), ...);
  }(MotionModels{});
}

}  // namespace skyfuse
