#include "skyfuse/sim/picture_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "skyfuse/multitarget/central_picture.hpp"
#include "skyfuse/multitarget/peer_picture.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/tracking/increment_rules.hpp"

namespace skyfuse {
namespace {

template <int N>
bool same_bits(std::span<const Track<N>> a, std::span<const Track<N>> b) {
  if (a.size() != b.size()) return false;
  for (std::size_t t = 0; t < a.size(); ++t) {
    if (a[t].id != b[t].id || a[t].status != b[t].status || !(a[t].history == b[t].history) ||
        a[t].updated_by != b[t].updated_by || a[t].estimate.mean != b[t].estimate.mean ||
        a[t].estimate.covariance != b[t].estimate.covariance) {
      return false;
    }
  }
  return true;
}

// The EKF's center stacks its detections; another part's fuses its own increments of them.
template <typename Filter, typename Model, typename Sensor>
using CenterUpdateOf =
    std::conditional_t<std::is_same_v<Filter, EkfFilterPart>, StackedUpdate<Model::kDim, Sensor>,
                       IncrementUpdate<Model::kDim, Sensor, typename Filter::IncrementRule>>;

template <typename Filter, typename Model, typename Sensor>
class PictureRun {
 public:
  static constexpr int N = Model::kDim;
  static constexpr int M = Sensor::kMeasDim;
  using Rule = typename Filter::IncrementRule;
  using Peer = PeerPicture<Model, Sensor>;
  using Center = CentralPicture<Model, Sensor, CenterUpdateOf<Filter, Model, Sensor>>;
  using TruthSensor = TruthSensorOf<Sensor>;

  PictureRun(const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
             std::uint64_t run)
      : scenario_(scenario),
        traffic_(*scenario.traffic),
        truth_(truth),
        run_(run),
        known_(known_stations(scenario, stations, run)),
        score_(traffic_.gospa, truth.size(), scenario.time_step_s) {
    const Model motion = make_motion_model<Model>(scenario);
    const Vector<N> variance = scenario.filter.initial_covariance_diag;
    peers_.assign(known_.size(), Peer(motion, known_, traffic_.tracker, variance));
    center_.emplace(motion, known_, traffic_.tracker, variance);
    for (int s = 0; s < stations; ++s) {
      const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
      detection_.push_back(station.detection.value_or(traffic_.detection));
    }
  }

  PictureRunResult run(const std::function<void(const PictureStep&)>& on_step) {
    result_.stations = static_cast<int>(known_.size());
    for (int k = 0; k < scenario_.steps; ++k) {
      round(k);
      const PictureStep& row = score_.add_step(k, aircraft_at(k), confirmed_tracks());
      score_nees(k);
      if (on_step) on_step(row);
    }
    result_.score = score_.summary();
    result_.steps = score_.steps();
    result_.anees =
        result_.nees_samples == 0 ? 0.0 : nees_sum_ / static_cast<double>(result_.nees_samples);
    result_.nees_dof = N;
    for (const auto& track : peers_.front().tracks()) {
      ++(track.status == TrackStatus::kConfirmed ? result_.confirmed_at_end
                                                 : result_.tentative_at_end);
    }
    return result_;
  }

 private:
  static std::vector<KnownStation<Sensor>> known_stations(const Scenario& scenario, int stations,
                                                          std::uint64_t run) {
    std::vector<KnownStation<Sensor>> known;
    for (int s = 0; s < stations; ++s) {
      const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
      known.push_back({station.id, make_sensor<Sensor>(station),
                       station_noise_covariance<M>(scenario, station, run), station.weight});
    }
    return known;
  }

  void round(int k) {
    const auto step = static_cast<std::uint64_t>(k);
    scans_.clear();
    for (std::size_t s = 0; s < known_.size(); ++s) {
      const StationConfig& station = scenario_.stations[s];
      ScanOrigins origins;
      scans_.push_back(simulate_scan(station.id, make_sensor<TruthSensor>(station),
                                     station.position_m, known_[s].noise, detection_[s], truth_, k,
                                     scenario_.seed, run_, &origins));
      result_.detections += scans_.back().detections.size();
      for (const int o : origins.target) {
        if (o < 0) {
          ++result_.false_alarms;
        } else {
          score_.detected(static_cast<std::size_t>(o), k);
        }
      }
    }
    for (Peer& peer : peers_) peer.predict();
    center_->predict();
    reports_.clear();
    for (std::size_t s = 0; s < known_.size(); ++s) {
      reports_.push_back(station_report<Rule>(peers_[s], known_[s], scans_[s], work_));
      result_.dropped += reports_.back().dropped;
    }
    for (Peer& peer : peers_) peer.fuse(step, reports_);
    center_->update(step, scans_);
    compare(k);
  }

  void compare(int k) {
    for (std::size_t p = 1; p < peers_.size() && result_.peers_identical; ++p) {
      if (!same_bits<N>(peers_.front().tracks(), peers_[p].tracks())) {
        result_.peers_identical = false;
        result_.first_divergent_step = k;
      }
    }
    peer_associations_.clear();
    for (const auto& report : reports_) {
      for (const auto& update : report.updates) {
        peer_associations_.push_back({report.station_id, update.detection, update.track});
      }
    }
    result_.associations += peer_associations_.size();
    differing_.clear();
    std::set_symmetric_difference(peer_associations_.begin(), peer_associations_.end(),
                                  center_->associations().begin(), center_->associations().end(),
                                  std::back_inserter(differing_));
    result_.association_flips += differing_.size();
    // Tracks both hold, matched by id (both tables are in ascending id).
    const auto mine = peers_.front().tracks();
    const auto theirs = center_->tracks();
    for (std::size_t i = 0, j = 0; i < mine.size() && j < theirs.size();) {
      if (mine[i].id < theirs[j].id) {
        ++i;
      } else if (theirs[j].id < mine[i].id) {
        ++j;
      } else {
        const auto& x = theirs[j].estimate.mean;
        result_.max_state_gap =
            std::max(result_.max_state_gap, (mine[i].estimate.mean - x).norm() / (1.0 + x.norm()));
        ++i;
        ++j;
      }
    }
  }

  const std::vector<TruthPoint>& aircraft_at(int k) {
    aircraft_.clear();
    for (std::size_t t = 0; t < truth_.size(); ++t) {
      if (!truth_[t].present_at(k)) continue;
      const Vector3 p = truth_[t].at(k).template head<3>();
      bool in_view = false;
      for (std::size_t s = 0; s < known_.size() && !in_view; ++s) {
        in_view = detection_[s].field_of_view.contains(scenario_.stations[s].position_m, p);
      }
      aircraft_.push_back({t, p, in_view});
    }
    return aircraft_;
  }

  const std::vector<TrackPoint>& confirmed_tracks() {
    tracks_.clear();
    for (const auto& track : peers_.front().tracks()) {
      if (track.status == TrackStatus::kConfirmed) {
        tracks_.push_back({track.id, track.estimate.mean.template head<3>()});
      }
    }
    return tracks_;
  }

  // NEES of each confirmed track associated with an aircraft, in the model's state.
  void score_nees(int k) {
    const auto& associated = score_.last_association();
    std::size_t c = 0;
    for (const auto& track : peers_.front().tracks()) {
      if (track.status != TrackStatus::kConfirmed) continue;
      const auto target = associated[c++];
      if (!target) continue;
      const Vector<N> error = track.estimate.mean - Model::from_kinematics(truth_[*target].at(k));
      SmallCholesky<N> factor;
      if (!factor.compute(track.estimate.covariance)) continue;
      nees_sum_ += error.dot(factor.solve(error));
      ++result_.nees_samples;
    }
  }

  const Scenario& scenario_;
  const TrafficConfig& traffic_;
  const std::vector<TargetTruth>& truth_;
  std::uint64_t run_;
  std::vector<KnownStation<Sensor>> known_;
  std::vector<DetectionConfig> detection_;
  std::vector<Peer> peers_;
  std::optional<Center> center_;
  PictureScore score_;
  AssignmentWork work_;
  std::vector<Scan<M>> scans_;
  std::vector<typename Peer::Report> reports_;
  std::vector<Association> peer_associations_;
  std::vector<Association> differing_;
  std::vector<TruthPoint> aircraft_;
  std::vector<TrackPoint> tracks_;
  double nees_sum_ = 0.0;
  PictureRunResult result_;
};

}  // namespace

PictureRunResult run_picture(const Scenario& scenario, const std::vector<TargetTruth>& truth,
                             int stations, std::uint64_t run,
                             const std::function<void(const PictureStep&)>& on_step) {
  if (!scenario.traffic) throw std::logic_error("run_picture: a scenario with one target");
  if (stations < 1 || stations > static_cast<int>(scenario.stations.size())) {
    throw std::invalid_argument(
        fmt::format("run_picture: {} stations of {}", stations, scenario.stations.size()));
  }
  std::optional<PictureRunResult> result;
  visit_filter(scenario.filter, [&]<typename Filter>(std::type_identity<Filter>) {
    if constexpr (requires { typename Filter::IncrementRule; }) {
      visit_model_kind<MotionModels>(
          scenario.filter.motion_model.kind, [&]<typename Model>(std::type_identity<Model>) {
            visit_sensor_kind<Sensors, Model::kDim>(
                scenario.stations.front().sensor.kind,
                [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
                  using Sensor = SensorOf<Model::kDim>;
                  if constexpr (FixesPosition<Sensor> && filter_runs_on<Filter, Model, Sensor>()) {
                    result = PictureRun<Filter, Model, Sensor>(scenario, truth, stations, run)
                                 .run(on_step);
                  }
                });
          });
    }
  });
  if (!result) {
    throw std::logic_error(fmt::format(
        "run_picture: no picture for filter '{}' on '{}' with {} stations (the loader refuses "
        "these)",
        scenario.filter.kind, scenario.filter.motion_model.kind,
        scenario.stations.front().sensor.kind));
  }
  return *result;
}

}  // namespace skyfuse
