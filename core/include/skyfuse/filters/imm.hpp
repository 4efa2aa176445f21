#pragma once
/// \file
/// Interacting multiple model (IMM) estimator over modes of different state dimensions.
///
/// Each mode is a transition model with its own state; the modes meet in a common state
/// (`Common`, e.g. PlanarState) into which every mode declares where its components go
/// (`Mode::kCommonIndex`). A component a mode lacks counts as mean 0, variance 0 there: mixing
/// pulls a CA mode's acceleration towards 0 by the CV mode's weight rather than inventing a
/// spread it never estimated.
///
/// One cycle (Bar-Shalom, Li & Kirubarajan, "Estimation with Applications to Tracking and
/// Navigation", 11.6.6), with p_ij = P(mode j now | mode i before):
///   predict: c_j = sum_i p_ij mu_i,  mu_i|j = p_ij mu_i / c_j;
///            each mode j starts from the mixture sum_i mu_i|j N(x_i, P_i), moment-matched in
///            the common state and read back in mode j's components, then predicts with its
///            own model;
///   update:  each mode updates with the measurement; mu_j proportional to c_j Lambda_j, with
///            Lambda_j = N(nu_j; 0, S_j) computed in the log domain.
/// The output is the moment-matched mixture of the modes in the common state.
///
/// An IMM of a single mode runs exactly that mode's filter: every mixing weight is exactly 1 and
/// every spread exactly 0, so its estimate equals the plain filter's bit for bit.

#include <array>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/filters/kalman.hpp"

namespace skyfuse {

/// What one mode's measurement update reports to the IMM.
struct ModeUpdate {
  NumericalStatus status = NumericalStatus::kOk;
  double log_likelihood = 0.0;  ///< log N(nu; 0, S) of the measurement(s) under this mode
};

template <typename Common, typename... Modes>
class Imm {
 public:
  static constexpr int kModes = sizeof...(Modes);
  static constexpr int kCommonDim = Common::kDim;
  using Probabilities = Vector<kModes>;
  /// Row i, column j: p_ij, the probability of switching from mode i to mode j in one step.
  using Switching = Matrix<kModes, kModes>;
  using CommonState = GaussianState<kCommonDim>;
  using ModeStates = std::tuple<GaussianState<Modes::kDim>...>;

  /// `switching`'s rows must each sum to 1 and `probabilities` must sum to 1 (checked:
  /// std::invalid_argument). Every mode starts from `initial`, read in its own components.
  Imm(std::tuple<Modes...> models, const Switching& switching, const Probabilities& probabilities,
      const CommonState& initial);

  /// Mixing, then each mode's time update.
  void predict();

  /// Each mode's measurement update with `Sensor<Mode>`, then the mode probabilities.
  /// kNotPositiveDefinite, with nothing changed, if any mode's innovation covariance is not.
  template <template <typename> class Sensor, int M>
  NumericalStatus update(const Vector<M>& z, const Covariance<M>& noise);

  /// The same with each mode's update done by `mode_update(std::integral_constant<int, I>,
  /// GaussianState<dim of mode I>&)`, which updates the state and returns a ModeUpdate: the
  /// stacked or fused updates of a station network come in here. Nothing changes unless every
  /// mode's update succeeds.
  template <typename ModeUpdateFn>
  NumericalStatus update_with(ModeUpdateFn&& mode_update);

  /// Takes the given mode states and probabilities as its own: a peer of a station network
  /// taking another peer's prior (tracking/imm_network.hpp). `probabilities` must sum to 1.
  void restore(const ModeStates& states, const Probabilities& probabilities) {
    states_ = states;
    probabilities_ = probabilities;
  }

  /// The moment-matched mixture of the modes.
  CommonState estimate() const;
  const Probabilities& mode_probabilities() const { return probabilities_; }
  template <int I>
  const auto& mode_state() const {
    return std::get<I>(states_);
  }
  const ModeStates& mode_states() const { return states_; }

 private:
  template <typename Mode>
  static CommonState to_common(const GaussianState<Mode::kDim>& state);
  template <typename Mode>
  static GaussianState<Mode::kDim> from_common(const CommonState& state);
  using CommonStates = std::array<CommonState, kModes>;
  /// Every mode's state in the common state.
  CommonStates in_common() const;
  /// sum_i w_i N(x_i, P_i) moment-matched in the common state.
  static CommonState mixture(const CommonStates& commons, const Probabilities& weights);

  std::tuple<Modes...> models_;
  Switching switching_;
  Probabilities probabilities_;
  ModeStates states_;
};

template <typename Common, typename... Modes>
Imm<Common, Modes...>::Imm(std::tuple<Modes...> models, const Switching& switching,
                           const Probabilities& probabilities, const CommonState& initial)
    : models_(std::move(models)), switching_(switching), probabilities_(probabilities) {
  constexpr double kTolerance = 1e-12;
  const bool rows_sum_to_one =
      ((switching.rowwise().sum().array() - 1.0).abs() <= kTolerance).all() &&
      (switching.array() >= 0.0).all();
  if (!rows_sum_to_one || std::abs(probabilities.sum() - 1.0) > kTolerance ||
      (probabilities.array() < 0.0).any()) {
    throw std::invalid_argument(
        "IMM: every row of the switching matrix and the mode probabilities must be "
        "non-negative and sum to 1");
  }
  std::apply([&](auto&... state) { ((state = from_common<Modes>(initial)), ...); }, states_);
}

template <typename Common, typename... Modes>
template <typename Mode>
auto Imm<Common, Modes...>::to_common(const GaussianState<Mode::kDim>& state) -> CommonState {
  CommonState out{Vector<kCommonDim>::Zero(), Covariance<kCommonDim>::Zero()};
  for (int r = 0; r < Mode::kDim; ++r) {
    out.mean(Mode::kCommonIndex[r]) = state.mean(r);
    for (int c = 0; c < Mode::kDim; ++c) {
      out.covariance(Mode::kCommonIndex[r], Mode::kCommonIndex[c]) = state.covariance(r, c);
    }
  }
  return out;
}

template <typename Common, typename... Modes>
template <typename Mode>
auto Imm<Common, Modes...>::from_common(const CommonState& state) -> GaussianState<Mode::kDim> {
  GaussianState<Mode::kDim> out;
  for (int r = 0; r < Mode::kDim; ++r) {
    out.mean(r) = state.mean(Mode::kCommonIndex[r]);
    for (int c = 0; c < Mode::kDim; ++c) {
      out.covariance(r, c) = state.covariance(Mode::kCommonIndex[r], Mode::kCommonIndex[c]);
    }
  }
  return out;
}

template <typename Common, typename... Modes>
auto Imm<Common, Modes...>::in_common() const -> CommonStates {
  return std::apply([](const auto&... state) { return CommonStates{to_common<Modes>(state)...}; },
                    states_);
}

template <typename Common, typename... Modes>
auto Imm<Common, Modes...>::mixture(const CommonStates& commons, const Probabilities& weights)
    -> CommonState {
  CommonState out{Vector<kCommonDim>::Zero(), Covariance<kCommonDim>::Zero()};
  for (int i = 0; i < kModes; ++i) out.mean += weights(i) * commons[i].mean;
  for (int i = 0; i < kModes; ++i) {
    const Vector<kCommonDim> spread = commons[i].mean - out.mean;
    out.covariance += weights(i) * (commons[i].covariance + spread * spread.transpose());
  }
  return out;
}

template <typename Common, typename... Modes>
void Imm<Common, Modes...>::predict() {
  const Probabilities predicted = switching_.transpose() * probabilities_;
  Matrix<kModes, kModes> mixing;  // column j: mu_i|j over i
  for (int j = 0; j < kModes; ++j) {
    for (int i = 0; i < kModes; ++i) {
      mixing(i, j) = predicted(j) > 0.0 ? switching_(i, j) * probabilities_(i) / predicted(j) : 0.0;
    }
  }
  std::array<CommonState, kModes> mixed;
  const CommonStates commons = in_common();
  for (int j = 0; j < kModes; ++j) mixed[j] = mixture(commons, mixing.col(j));

  int j = 0;
  std::apply([&](auto&... state) { ((state = from_common<Modes>(mixed[j++])), ...); }, states_);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (skyfuse::predict(std::get<I>(states_), std::get<I>(models_)), ...);
  }
  (std::index_sequence_for<Modes...>{});
  probabilities_ = predicted;
}

template <typename Common, typename... Modes>
template <template <typename> class Sensor, int M>
NumericalStatus Imm<Common, Modes...>::update(const Vector<M>& z, const Covariance<M>& noise) {
  return update_with([&](auto mode, auto& state) {
    using Mode = std::tuple_element_t<decltype(mode)::value, std::tuple<Modes...>>;
    const UpdateReport report = update_with_likelihood(state, Sensor<Mode>{}, z, noise);
    return ModeUpdate{report.status, report.log_likelihood(M)};
  });
}

template <typename Common, typename... Modes>
template <typename ModeUpdateFn>
NumericalStatus Imm<Common, Modes...>::update_with(ModeUpdateFn&& mode_update) {
  ModeStates updated = states_;
  Probabilities log_weights;
  bool ok = true;
  [&]<int... I>(std::integer_sequence<int, I...>) {
    (
        [&] {
          const ModeUpdate report =
              mode_update(std::integral_constant<int, I>{}, std::get<I>(updated));
          ok = ok && report.status == NumericalStatus::kOk;
          log_weights(I) = std::log(probabilities_(I)) + report.log_likelihood;
        }(),
        ...);
  }
  (std::make_integer_sequence<int, kModes>{});
  if (!ok) return NumericalStatus::kNotPositiveDefinite;

  // mu_j = c_j Lambda_j / sum, by log-sum-exp so that no likelihood underflows to 0/0.
  const double largest = log_weights.maxCoeff();
  const Probabilities weights = (log_weights.array() - largest).exp().matrix();
  states_ = updated;
  probabilities_ = weights / weights.sum();
  return NumericalStatus::kOk;
}

template <typename Common, typename... Modes>
auto Imm<Common, Modes...>::estimate() const -> CommonState {
  return mixture(in_common(), probabilities_);
}

}  // namespace skyfuse
