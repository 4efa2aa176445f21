#pragma once
/// \file
/// The scan simulator, beside the truth it sees: a station's scan (picture/scan.hpp) made
/// from the aircraft's true kinematics, its sensor and its detection settings
/// (detection_model.hpp), as a pure function of (seed, run, station, step), so any process
/// order gives the same bits.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "skyfuse/traffic/detection_model.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

/// Where each detection of a simulated scan came from: for metrics and tests, never for a
/// tracker.
struct ScanOrigins {
  std::vector<int> target;   ///< per detection: the index of its target, or -1 for clutter
  std::uint32_t missed = 0;  ///< targets in the field of view not detected
};

/// A recorded broadcast as `Sensor` measures it: only a receiver of the aircraft's own position
/// and velocity replays one (the scenario loader allows no other).
template <typename Sensor>
Vector<Sensor::kMeasDim> replayed(const HeardBroadcast& heard) {
  if constexpr (std::is_same_v<Sensor, PositionVelocity<kKinematicsDim>>) {
    return heard.position_velocity;
  } else {
    throw std::logic_error("only a position_velocity sensor replays recorded broadcasts");
  }
}

/// The scan of the station `station_id`, whose sensor `sensor` (of the true kinematics, a
/// 9-entry state) stands at `site`, at `step`: each target present and in the field of view
/// detected with probability P_D (its value h(x) + nu, nu ~ N(0, R)), then the false alarms,
/// then all of them shuffled. A cooperative sensor (`detection.reports_address`) hears only the
/// targets with an address and lists each detection's address and identification (a false
/// alarm's are none; a scan in which none has an identification lists none). A
/// receiver of recorded broadcasts (`detection.replays_broadcasts`) takes each aircraft's own
/// report of the step instead of drawing one. A station's bias (`detection.bias`) moves each
/// aircraft's detection by its clock offset and its components' offsets before the noise; a
/// false alarm, uniform over the field of view, is none the worse for it. A target's noise is drawn
/// from its own stream, the first target's from the one a one-target run uses, so that with P_D = 1
/// and no clutter its values are today's.
template <typename Sensor>
Scan simulate_scan(int station_id, const Sensor& sensor, const Vector3& site,
                   const Covariance<Sensor::kMeasDim>& noise, const DetectionConfig& detection,
                   std::span<const TargetTruth> truths, int step, std::uint64_t seed,
                   std::uint64_t run, ScanOrigins* origins = nullptr) {
  static_assert(Sensor::kStateDim == kKinematicsDim, "scans are simulated from the kinematics");
  constexpr int M = Sensor::kMeasDim;
  const auto station = static_cast<std::uint64_t>(station_id);
  const auto at = static_cast<std::uint64_t>(step);
  Scan scan{station_id, noise, {}};
  std::vector<int> origin;
  std::uint32_t missed = 0;

  CounterRng detect({seed, run, station, at, NoiseStream::kDetection});
  const bool cooperative = detection.reports_address;
  const SensorBias& bias = detection.bias;
  const bool biased = bias.any();
  const Vector<M> offset = offsets_of<Sensor>(bias);
  for (std::size_t t = 0; t < truths.size(); ++t) {
    if (!truths[t].present_at(step)) continue;
    if (cooperative && truths[t].address == kNoAddress) continue;
    const Vector<kKinematicsDim>& x = truths[t].at(step);
    if (!detection.field_of_view.contains(site, x.head<3>())) continue;
    // Drawn for every target in view, so one target's draw never shifts another's.
    const double u = detect.uniform();
    if (detection.probability < 1.0 && u >= detection.probability) {
      ++missed;
      continue;
    }
    Vector<M> z;
    if (detection.replays_broadcasts) {
      const HeardBroadcast* heard = truths[t].broadcast_at(step);
      if (heard == nullptr) {  // the recording's own gap
        ++missed;
        continue;
      }
      z = replayed<Sensor>(*heard);
    } else {
      CounterRng rng({seed, run, station, at, NoiseStream::kMeasurement, t});
      if (biased) {
        // Where its clock's stamp puts the aircraft, then the offsets: the same noise after.
        z = sensor.predict(bias.time_s != 0.0 ? kinematics_after(x, bias.time_s) : x) + offset;
      } else {
        z = sensor.predict(x);
      }
      for (int i = 0; i < M; ++i) z(i) += std::sqrt(noise(i, i)) * rng.normal();
    }
    scan.detections.emplace_back(Sensor::to_reported(z));
    if (cooperative) {
      scan.addresses.push_back(truths[t].address);
      scan.identifications.push_back(truths[t].identification);
    }
    origin.push_back(static_cast<int>(t));
  }

  if (detection.clutter_per_scan > 0.0) {
    CounterRng clutter({seed, run, station, at, NoiseStream::kClutter});
    const std::uint32_t count = draw_poisson(detection.clutter_per_scan, clutter);
    for (std::uint32_t c = 0; c < count; ++c) {
      Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
      x.head<3>() = detection.field_of_view.draw_point(site, clutter);
      if constexpr (Sensor::kJacobianCols >= 6) {  // it measures the velocity too
        for (int i = 3; i < 6; ++i) {
          x(i) = detection.clutter_max_speed_mps * (2.0 * clutter.uniform() - 1.0);
        }
      }
      scan.detections.emplace_back(Sensor::to_reported(sensor.predict(x)));
      if (cooperative) {
        scan.addresses.push_back(kNoAddress);
        scan.identifications.push_back(kNoIdentification);
      }
      origin.push_back(-1);
    }
  }

  // Fisher-Yates, from its own stream: the order says nothing of the origin.
  CounterRng order({seed, run, station, at, NoiseStream::kScanOrder});
  for (std::size_t i = scan.detections.size(); i > 1; --i) {
    const auto j = static_cast<std::size_t>(order.next_u64() % i);
    std::swap(scan.detections[i - 1], scan.detections[j]);
    if (cooperative) {
      std::swap(scan.addresses[i - 1], scan.addresses[j]);
      std::swap(scan.identifications[i - 1], scan.identifications[j]);
    }
    std::swap(origin[i - 1], origin[j]);
  }
  if (std::ranges::all_of(scan.identifications,
                          [](Identification i) { return i == kNoIdentification; })) {
    scan.identifications.clear();
  }
  if (origins != nullptr) *origins = {std::move(origin), missed};
  return scan;
}

/// The same, for a station whose sensor is one of several kinds (picture/picture_sensor.hpp
/// on the true kinematics) and whose noise is of that sensor's size.
template <typename... Sensors>
Scan simulate_scan(int station_id, const std::variant<Sensors...>& sensor, const Vector3& site,
                   const DetectionNoise& noise, const DetectionConfig& detection,
                   std::span<const TargetTruth> truths, int step, std::uint64_t seed,
                   std::uint64_t run, ScanOrigins* origins = nullptr) {
  return std::visit(
      [&]<typename Sensor>(const Sensor& one) {
        return simulate_scan(station_id, one, site, fixed_noise<Sensor::kMeasDim>(noise), detection,
                             truths, step, seed, run, origins);
      },
      sensor);
}

}  // namespace skyfuse
