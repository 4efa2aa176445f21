#pragma once
/// \file
/// One station's registration, for whichever of a picture's sensors it has
/// (picture/picture_sensor.hpp): its BiasEstimate, what it learns from a detection of a tracked
/// aircraft, and its detections corrected by the current estimate. The estimate moves only
/// when settle() is called (once a round), so that every detection of a round is corrected
/// alike whatever the order it is met in.

#include <optional>
#include <stdexcept>
#include <variant>

#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/registration/bias_estimate.hpp"

namespace skyfuse {

namespace detail {
template <typename Sensors>
struct BiasEstimateOf;
template <typename... S>
struct BiasEstimateOf<std::variant<S...>> {
  using type = std::variant<BiasEstimate<S>...>;
};
}  // namespace detail

template <int N>
class StationBias {
 public:
  using Sensor = PictureSensor<N>;
  using Estimate = typename detail::BiasEstimateOf<Sensor>::type;

  /// A station of `sensor` whose biases are a priori N(0, prior_std²), each entry > 0
  /// (prior_std names them as a scenario's `bias:` does; entries the sensor does not measure
  /// are not read).
  StationBias(const Sensor& sensor, const SensorBias& prior_std)
      : estimate_(std::visit(
            [&]<typename S>(const S&) -> Estimate {
              const auto prior = BiasEstimate<S>::from_sensor_bias(prior_std);
              if (!(prior.minCoeff() > 0.0)) {
                throw std::invalid_argument(
                    "StationBias: every prior standard deviation must be > 0");
              }
              return BiasEstimate<S>(prior);
            },
            sensor)) {}

  /// Adds detection `z` (noise `noise`) of the aircraft whose track has prior `prior`: z as
  /// the station measured it, biases and all. False, and nothing added, where S does not
  /// factor.
  bool learn(const Sensor& sensor, const GaussianState<N>& prior, const Detection& z,
             const DetectionNoise& noise) {
    return std::visit(
        [&]<typename S>(const S& typed) {
          constexpr int M = S::kMeasDim;
          return std::get<BiasEstimate<S>>(estimate_).add(typed, prior, fixed_detection<M>(z),
                                                          fixed_noise<M>(noise));
        },
        sensor);
  }

  /// Takes what was learnt into the estimate the corrections use; false, and the estimate as
  /// it was, where the information does not factor.
  bool settle() {
    return std::visit(
        [&]<typename S>(const BiasEstimate<S>& estimate) {
          const auto settled = estimate.estimate();
          if (!settled) return false;
          bias_ = BiasEstimate<S>::as_sensor_bias(settled->mean);
          return true;
        },
        estimate_);
  }

  /// The biases the corrections use (none learnt: zero).
  const SensorBias& bias() const { return bias_; }

  /// `z` corrected for the aircraft whose track's prior mean is `mean`: z − G(x̂) b̂, the
  /// clock's part included.
  Detection corrected(const Sensor& sensor, const Detection& z, const Vector<N>& mean) const {
    return std::visit(
        [&]<typename S>(const S& typed) -> Detection {
          constexpr int M = S::kMeasDim;
          const auto b = BiasEstimate<S>::from_sensor_bias(bias_);
          const auto g = BiasEstimate<S>::bias_jacobian(typed.jacobian(mean), mean);
          return S::to_reported(fixed_detection<M>(z) - g * b);
        },
        sensor);
  }

  /// `z` corrected by the offsets alone, for a detection no track has met (initiation): the
  /// clock's part needs the aircraft's velocity.
  Detection offsets_removed(const Sensor& sensor, const Detection& z) const {
    return std::visit(
        [&]<typename S>(const S&) -> Detection {
          constexpr int M = S::kMeasDim;
          return S::to_reported(fixed_detection<M>(z) - offsets_of<S>(bias_));
        },
        sensor);
  }

  const Estimate& estimate() const { return estimate_; }

 private:
  Estimate estimate_;
  SensorBias bias_;
};

}  // namespace skyfuse
