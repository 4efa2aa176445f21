#pragma once
/// \file
/// The code of a picture that its tracks' state size and its stations' sensors decide, not its
/// filter part: every station's registration (registration/station_bias.hpp), the routing and
/// hypotheses of a station's scan (station_hypotheses.hpp), and, where an EKF's picture has the
/// size, each detection's relinearised prior (fusion/relinearised_increment.hpp) and its terms
/// against the bias errors (registration/considered_biases.hpp). The pictures of one size (the
/// EKF's and the unscented filter's on one motion model, the IMM's mode sets) share it, so it is
/// compiled once per state size rather than in every picture's shard: the headers declare it,
/// the *_impl.hpp define it, and core/src/picture/state_size_code.cpp, compiled once for each
/// of the build's sizes (picture_state_sizes), names every part here by its address, which
/// makes the compiler compile it there and keep it for the linker.

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "skyfuse/fusion/relinearised_increment_impl.hpp"
#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/picture/station_hypotheses_impl.hpp"
#include "skyfuse/registration/considered_terms_impl.hpp"
#include "skyfuse/registration/station_bias_impl.hpp"

namespace skyfuse {

template <int N>
struct StateSizeCode {
  static void keep() {
    using Bias = StationBias<N>;
    [[gnu::used]] static constexpr auto kRegistration = std::tuple{&Bias::prior_estimate,
                                                                   &Bias::set_prior_covariance,
                                                                   &Bias::learn,
                                                                   &Bias::settle,
                                                                   &Bias::sigma,
                                                                   &Bias::estimated,
                                                                   &Bias::correction_noise,
                                                                   &Bias::offsets_noise,
                                                                   &Bias::offsets_factor,
                                                                   &Bias::corrected,
                                                                   &Bias::offsets_removed,
                                                                   &Bias::sums,
                                                                   &Bias::restore};
    [[gnu::used]] static constexpr auto kScan = &hypothesise_station_scan<N>;
    keep_corrections(std::type_identity<PictureSensor<N>>{});
  }
  /// What the EKF's pictures add at this size: each detection's relinearised prior and its
  /// terms against the bias errors, for every sensor.
  static void keep_linearisation() { keep_linearisation(std::type_identity<PictureSensor<N>>{}); }

 private:
  // StationBias::correction of every sensor of the picture (its callers know the sensor's type).
  template <typename... S>
  static void keep_corrections(std::type_identity<std::variant<S...>> /*sensors*/) {
    [[gnu::used]] static constexpr auto kCorrections =
        std::tuple{&StationBias<N>::template correction<S>...};
  }
  template <typename... S>
  static void keep_linearisation(std::type_identity<std::variant<S...>> /*sensors*/) {
    [[gnu::used]] static constexpr auto kLinearisation =
        std::tuple{&relinearised_prior<N, S>..., &considered_terms<N, S>...};
  }
};

/// Compiles the code of the build's state size at place `Slot` of picture_state_sizes(), nothing
/// where the build has fewer sizes: what core/src/picture/state_size_code.cpp compiles once per
/// slot.
template <std::size_t Slot>
void keep_state_size_slot() {
  constexpr PictureStateSizes kSizes = picture_state_sizes();
  if constexpr (Slot < kSizes.count) {
    StateSizeCode<kSizes.sizes[Slot]>::keep();
    if constexpr (kSizes.linearises[Slot]) {
      StateSizeCode<kSizes.sizes[Slot]>::keep_linearisation();
    }
  }
}

/// Compiles the code of the state sizes at places `Slot...`: with every place, what the pictures'
/// one shard does where the build has a single shard (SKYFUSE_STATE_SIZE_SLOTS 0, the demo's),
/// since no other file shares that code there, and beside the pictures' own arithmetic it
/// compiles in less (docs/testing.md#the-largest-files). A template, so that only a file that
/// calls it compiles the sizes.
template <std::size_t... Slot>
void keep_state_size_slots(std::index_sequence<Slot...> /*slots*/) {
  (keep_state_size_slot<Slot>(), ...);
}

}  // namespace skyfuse
