// One shard of the in-process picture's runs (registry/filter_shards.hpp): cmake/FilterShards.cmake
// compiles this file once per shard, with SKYFUSE_SHARD set.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "sim/picture_shards.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_stations.hpp"
#include "skyfuse/sim/picture_truth.hpp"
#include "skyfuse/tracking/increment_rules.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"

namespace skyfuse {
namespace {

template <typename State>
bool same_bits(const State& a, const State& b) {
  if constexpr (requires { a.mean; }) {
    return a.mean == b.mean && a.covariance == b.covariance;
  } else {
    // An IMM: every mode's state and the mode probabilities.
    const auto& fa = a.filter();
    const auto& fb = b.filter();
    bool same = fa.mode_probabilities() == fb.mode_probabilities();
    State::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      const auto& ma = fa.template mode_state<I>();
      const auto& mb = fb.template mode_state<I>();
      same = same && ma.mean == mb.mean && ma.covariance == mb.covariance;
    });
    return same;
  }
}

template <typename Track>
bool same_bits(std::span<const Track> a, std::span<const Track> b) {
  if (a.size() != b.size()) return false;
  for (std::size_t t = 0; t < a.size(); ++t) {
    if (a[t].id != b[t].id || a[t].status != b[t].status || !(a[t].history == b[t].history) ||
        a[t].updated_by != b[t].updated_by || a[t].address != b[t].address ||
        !same_bits(a[t].filter, b[t].filter)) {
      return false;
    }
  }
  return true;
}

template <typename Parts>
class PictureRun {
 public:
  using PeerTracks = typename Parts::Peer;
  static constexpr int N = PeerTracks::kDim;
  using Peer = PeerPicture<PeerTracks>;
  using Center = CentralPicture<typename Parts::Center>;

  PictureRun(const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
             std::uint64_t run, const ScanFilter& scan_filter)
      : scan_filter_(scan_filter),
        scenario_(scenario),
        traffic_(*scenario.traffic),
        truth_(truth),
        run_(run),
        known_(known_stations<N>(scenario, stations, run)),
        score_(traffic_.gospa, truth.size(), scenario.time_step_s) {
    peers_.assign(known_.size(), Peer(Parts::peer(scenario), known_, scenario.tracker));
    center_.emplace(Parts::center(scenario), known_, scenario.tracker);
    for (int s = 0; s < stations; ++s) {
      const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
      detection_.push_back(station.detection.value());
      truth_sensors_.push_back(make_picture_sensor<kKinematicsDim>(station));
      if (peers_.front().registers(station.id)) {
        result_.registration.push_back({station.id,
                                        peers_.front().bias_of(station.id).estimated(),
                                        detection_.back().bias,
                                        {},
                                        {}});
      }
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
    result_.nees_dof = PeerTracks::kNeesDof;
    for (const auto& track : peers_.front().tracks()) {
      ++(track.status == TrackStatus::kConfirmed ? result_.confirmed_at_end
                                                 : result_.tentative_at_end);
    }
    return result_;
  }

 private:
  void round(int k) {
    const auto step = static_cast<std::uint64_t>(k);
    scans_.clear();
    for (std::size_t s = 0; s < known_.size(); ++s) {
      const StationConfig& station = scenario_.stations[s];
      ScanOrigins origins;
      scans_.push_back(simulate_scan(station.id, truth_sensors_[s], station.position_m,
                                     known_[s].noise, detection_[s], truth_, k, scenario_.seed,
                                     run_, &origins));
      if (scan_filter_) scan_filter_(s, scans_.back());
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
      reports_.push_back(peers_[s].report(known_[s], scans_[s], work_));
      result_.dropped += reports_.back().dropped;
      result_.refused_addresses += reports_.back().refused_addresses;
    }
    for (Peer& peer : peers_) {
      const RoundOutcome outcome = peer.fuse(step, reports_);
      if (&peer == &peers_.front()) result_.merged_tracks += outcome.merged;
    }
    center_->update(step, scans_);
    result_.peer_digests.push_back(peers_.front().digest());
    result_.center_digests.push_back(center_->digest());
    compare(k);
    trace_registration();
  }

  // Each station's estimate as the round settled it, and how far the center's is from it.
  void trace_registration() {
    for (BiasTrace& trace : result_.registration) {
      const auto& mine = peers_.front().bias_of(trace.station_id);
      trace.estimate.push_back(mine.bias());
      trace.sigma.push_back(mine.sigma());
      const SensorBias& theirs = center_->bias_of(trace.station_id).bias();
      for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
        const double peer = bias_entry(mine.bias(), e);
        result_.max_bias_gap = std::max(
            result_.max_bias_gap, std::abs(bias_entry(theirs, e) - peer) / (1.0 + std::abs(peer)));
      }
    }
  }

  void compare(int k) {
    for (std::size_t p = 1; p < peers_.size() && result_.peers_identical; ++p) {
      if (!same_bits(peers_.front().tracks(), peers_[p].tracks())) {
        result_.peers_identical = false;
        result_.first_divergent_step = k;
      }
    }
    peer_associations_.clear();
    for (const auto& report : reports_) {
      for (const ReportedPair& pair : report.pairs) {
        peer_associations_.push_back({report.station_id, pair.detection, pair.track});
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
        const auto& x = center_->estimates()[j].mean;
        result_.max_state_gap =
            std::max(result_.max_state_gap,
                     (peers_.front().estimates()[i].mean - x).norm() / (1.0 + x.norm()));
        ++i;
        ++j;
      }
    }
  }

  const std::vector<TruthPoint>& aircraft_at(int k) {
    aircraft_at_step(scenario_, static_cast<int>(known_.size()), truth_, k, aircraft_);
    return aircraft_;
  }

  const std::vector<TrackPoint>& confirmed_tracks() {
    tracks_.clear();
    const auto tracks = peers_.front().tracks();
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (tracks[t].status == TrackStatus::kConfirmed) {
        tracks_.push_back({tracks[t].id, peers_.front().estimates()[t].mean.template head<3>()});
      }
    }
    return tracks_;
  }

  // NEES of each confirmed track associated with an aircraft, over the estimate's leading
  // kNeesDof entries.
  void score_nees(int k) {
    constexpr int D = PeerTracks::kNeesDof;
    const auto& associated = score_.last_association();
    const auto tracks = peers_.front().tracks();
    std::size_t c = 0;
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (tracks[t].status != TrackStatus::kConfirmed) continue;
      const auto target = associated[c++];
      if (!target) continue;
      const GaussianState<N>& estimate = peers_.front().estimates()[t];
      const Vector<D> error =
          (estimate.mean - PeerTracks::from_kinematics(truth_[*target].at(k))).template head<D>();
      SmallCholesky<D> factor;
      if (!factor.compute(estimate.covariance.template topLeftCorner<D, D>())) continue;
      nees_sum_ += error.dot(factor.solve(error));
      ++result_.nees_samples;
    }
  }

  const ScanFilter& scan_filter_;
  const Scenario& scenario_;
  const TrafficConfig& traffic_;
  const std::vector<TargetTruth>& truth_;
  std::uint64_t run_;
  std::vector<KnownStation<N>> known_;
  std::vector<DetectionConfig> detection_;
  std::vector<PictureSensor<kKinematicsDim>> truth_sensors_;  // each station's, on the truth
  std::vector<Peer> peers_;
  std::optional<Center> center_;
  PictureScore score_;
  AssociationWork work_;
  std::vector<Scan> scans_;
  std::vector<typename Peer::Report> reports_;
  std::vector<Association> peer_associations_;
  std::vector<Association> differing_;
  std::vector<TruthPoint> aircraft_;
  std::vector<TrackPoint> tracks_;
  double nees_sum_ = 0.0;
  PictureRunResult result_;
};

}  // namespace

template <std::size_t Shard>
std::optional<PictureRunResult> run_picture_in_shard(
    const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
    std::uint64_t run, const std::function<void(const PictureStep&)>& on_step,
    const ScanFilter& scan_filter) {
  std::optional<PictureRunResult> result;
  visit_picture_parts_in_shard<Shard>(scenario, [&]<typename Parts>(std::type_identity<Parts>) {
    result = PictureRun<Parts>(scenario, truth, stations, run, scan_filter).run(on_step);
  });
  return result;
}

template std::optional<PictureRunResult> run_picture_in_shard<SKYFUSE_SHARD>(
    const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
    std::uint64_t run, const std::function<void(const PictureStep&)>& on_step,
    const ScanFilter& scan_filter);

}  // namespace skyfuse
