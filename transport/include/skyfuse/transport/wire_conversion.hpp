#pragma once
/// \file
/// Conversion between wire samples and core types, at the edge of every process. Doubles are
/// copied bit for bit and symmetric matrices travel as their upper triangle, so a value that
/// crosses the wire is the value that was sent: the DDS path adds no rounding.
///
/// The wire carries any sensor and any state dimension; a receiver asks for the types its run
/// uses, and a sample whose sensor kind or lengths do not fit them converts to nothing (the
/// receiver refuses it as out of range).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/registry/sensor_pack.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"
#include "skyfuse/transport/topics.hpp"

namespace skyfuse::transport {

/// Row-major upper triangle of a symmetric n x n matrix, n (n + 1) / 2 values (n = N, or the
/// matrix's size with N = Eigen::Dynamic).
template <int N>
std::vector<double> pack_upper(const Covariance<N>& m) {
  const auto n = static_cast<int>(m.rows());
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n * (n + 1) / 2));
  for (int r = 0; r < n; ++r) {
    for (int c = r; c < n; ++c) out.push_back(m(r, c));
  }
  return out;
}
/// The symmetric n x n matrix of an upper triangle; nothing unless it has n (n + 1) / 2 values.
/// n is N, or given at run time with N = Eigen::Dynamic.
template <int N>
std::optional<Covariance<N>> unpack_upper(const std::vector<double>& in, int n = N) {
  const auto size = static_cast<std::size_t>(n);
  if (n < 1 || in.size() != size * (size + 1) / 2) return std::nullopt;
  Covariance<N> m;
  m.resize(n, n);
  std::size_t k = 0;
  for (int r = 0; r < n; ++r) {
    for (int c = r; c < n; ++c) m(r, c) = m(c, r) = in[k++];
  }
  return m;
}
template <int N>
std::vector<double> pack_vector(const Vector<N>& v) {
  return std::vector<double>(v.data(), v.data() + N);
}
/// The vector of n values; nothing unless there are n. n is N, or given at run time with
/// N = Eigen::Dynamic.
template <int N>
std::optional<Vector<N>> unpack_vector(const std::vector<double>& in, int n = N) {
  if (n < 1 || in.size() != static_cast<std::size_t>(n)) return std::nullopt;
  return Vector<N>(Eigen::Map<const Vector<N>>(in.data(), n));
}

template <typename Sensor>
wire::Measurement to_wire(const StationObservation<Sensor>& observation, std::uint64_t run_id,
                          std::uint32_t step) {
  wire::Measurement sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(observation.station_id);
  sample.sensor(std::string(Sensor::kKind));
  sample.z(pack_vector<Sensor::kMeasDim>(observation.z));
  sample.noise(pack_upper<Sensor::kMeasDim>(observation.noise));
  const Vector3 site = observation.sensor.site();
  sample.station_position({site.x(), site.y(), site.z()});
  return sample;
}

/// The observation of a `Sensor` a measurement carries; nothing if it names another sensor kind
/// or its lengths are not that sensor's. The wire carries the sensor's site; a sensor the
/// scenario configures further (a multilateration group's other receivers, a 2-D radar's
/// heights: registry/make_parts.hpp) takes the rest from `station`, the sending station as the
/// scenario every node loaded describes it, and without it is nothing.
template <typename Sensor>
std::optional<StationObservation<Sensor>> observation_from_wire(
    const wire::Measurement& sample, const StationConfig* station = nullptr) {
  if (std::string_view(sample.sensor().c_str()) != Sensor::kKind) return std::nullopt;
  const auto z = unpack_vector<Sensor::kMeasDim>(sample.z());
  const auto noise = unpack_upper<Sensor::kMeasDim>(sample.noise());
  if (!z || !noise) return std::nullopt;
  const auto& p = sample.station_position();
  const Vector3 site(p[0], p[1], p[2]);
  if constexpr (ConfiguredByScenario<Sensor>) {
    if (station == nullptr || station->sensor.kind != Sensor::kKind) return std::nullopt;
    return StationObservation<Sensor>{sample.station_id(), make_sensor_at<Sensor>(site, *station),
                                      *z, *noise};
  } else {
    return StationObservation<Sensor>{sample.station_id(), Sensor(site), *z, *noise};
  }
}

/// The observation a measurement carries for stations of `Sensor`: one sensor type, or a
/// SensorPack (then the alternative of the kind the sample names); nothing if it fits none.
template <typename Sensor>
std::optional<ObservationFor<Sensor>> observation_for(const wire::Measurement& sample,
                                                      const StationConfig* station = nullptr) {
  if constexpr (IsSensorPack<Sensor>::value) {
    return [&]<int N, template <int> class... S>(std::type_identity<SensorPack<N, S...>>) {
      std::optional<ObservationFor<Sensor>> out;
      ((!out ? [&] {
         if (auto o = observation_from_wire<S<N>>(sample, station)) out = std::move(*o);
       }()
             : void()),
       ...);
      return out;
    }
    (std::type_identity<Sensor>{});
  } else {
    return observation_from_wire<Sensor>(sample, station);
  }
}

template <int N>
wire::InformationIncrement to_wire(const PeerContribution<N>& contribution, std::uint64_t run_id,
                                   std::uint32_t step) {
  wire::InformationIncrement sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(contribution.increment.station_id);
  sample.delta_information(pack_upper<N>(contribution.increment.delta_information));
  sample.delta_vector(pack_vector<N>(contribution.increment.delta_vector));
  sample.prior_x(pack_vector<N>(contribution.prior.mean));
  sample.prior_covariance(pack_upper<N>(contribution.prior.covariance));
  return sample;
}

/// The contribution an increment carries for an N-state; nothing if its lengths are not N's.
template <int N>
std::optional<PeerContribution<N>> contribution_from_wire(
    const wire::InformationIncrement& sample) {
  const auto dq = unpack_upper<N>(sample.delta_information());
  const auto dy = unpack_vector<N>(sample.delta_vector());
  const auto x = unpack_vector<N>(sample.prior_x());
  const auto p = unpack_upper<N>(sample.prior_covariance());
  if (!dq || !dy || !x || !p) return std::nullopt;
  PeerContribution<N> contribution;
  contribution.increment.station_id = sample.station_id();
  contribution.increment.delta_information = *dq;
  contribution.increment.delta_vector = *dy;
  contribution.prior.mean = *x;
  contribution.prior.covariance = *p;
  return contribution;
}

template <int N>
wire::TrackEstimate to_wire(const GaussianState<N>& estimate, std::uint64_t run_id,
                            std::uint32_t step, int source_id, wire::TrackSource mode,
                            std::span<const int> contributors) {
  wire::TrackEstimate sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.source_id(source_id);
  sample.track_id(0);  // the one aircraft's track
  sample.confirmed(true);
  sample.mode(mode);
  sample.x(pack_vector<N>(estimate.mean));
  sample.covariance(pack_upper<N>(estimate.covariance));
  sample.contributors().assign(contributors.begin(), contributors.end());
  return sample;
}

/// The estimate a track carries for an N-state; nothing if its lengths are not N's.
template <int N>
std::optional<GaussianState<N>> estimate_from_wire(const wire::TrackEstimate& sample) {
  const auto x = unpack_vector<N>(sample.x());
  const auto p = unpack_upper<N>(sample.covariance());
  if (!x || !p) return std::nullopt;
  return GaussianState<N>{*x, *p};
}

/// The track's estimate as an n-entry state, n known only at run time (the run's motion model's);
/// nothing if its lengths are not n's.
inline std::optional<DynamicGaussianState> estimate_from_wire(const wire::TrackEstimate& sample,
                                                              int n) {
  auto x = unpack_vector<Eigen::Dynamic>(sample.x(), n);
  auto p = unpack_upper<Eigen::Dynamic>(sample.covariance(), n);
  if (!x || !p) return std::nullopt;
  return DynamicGaussianState{std::move(*x), std::move(*p)};
}

}  // namespace skyfuse::transport
