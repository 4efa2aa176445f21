// A registered picture (docs/registration.md): two biased radars and an ADS-B station, a peer
// each and the center. Every peer learns the same biases bit for bit (one of them restarted
// halfway, from another's picture and sums), the center the same within 1e-9; each radar's estimate
// ends within 3σ of its truth; and a batch least-squares estimate of the same biases, made
// independently of the filters from the same associations — each radar detection the picture paired
// with a track, against the ADS-B report paired with that track in the same round — agrees with the
// online one within their σ.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registration/bias_estimate.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"
#include "unit/picture/picture_round.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
constexpr int N = Model::kDim;
using Radar = RangeAzimuthElevation<N>;
using Broadcast = PositionVelocity<N>;
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using Peer = PeerPicture<PeerTracks>;
using Center = CentralPicture<CenterStackedTracks<Model>>;
using Station = KnownStation<N>;
using Estimate = BiasEstimate<Radar>;  // [range, azimuth, elevation, clock]

constexpr double kTimeStepS = 2.0;
constexpr std::uint64_t kSeed = 20261130;
constexpr int kRounds = 150;
constexpr int kAircraft = 12;
constexpr int kAdsb = 3;  // the ADS-B station's id

// The offsets, signs differing, and a clock 0.4 s late on radar 2.
const SensorBias kRadar1Bias{150.0, 0.002618, 0.001745, 0.0};
const SensorBias kRadar2Bias{-150.0, -0.002618, 0.001745, 0.4};

std::vector<Station> stations() {
  Covariance<3> radar = Covariance<3>::Zero();
  radar.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  Covariance<6> broadcast = Covariance<6>::Zero();
  broadcast.diagonal() << 225.0, 225.0, 225.0, 4.0, 4.0, 4.0;
  return {{1, Radar(Vector3(-20000.0, -15000.0, 50.0)), radar, 1.0, {}},
          {2, Radar(Vector3(22000.0, -10000.0, 80.0)), radar, 1.0, {}},
          {kAdsb, Broadcast(), broadcast, 1.0, {}}};
}

// Aircraft on straight legs across a 40 x 40 km area, each broadcasting its address.
std::vector<TargetTruth> aircraft() {
  std::vector<TargetTruth> truths;
  for (int i = 0; i < kAircraft; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / kAircraft;
    const Vector3 start(-18000.0 + 3000.0 * i, 15000.0 - 2500.0 * i, 1000.0 + 250.0 * i);
    const Vector3 velocity((90.0 + 5.0 * i) * std::cos(angle), (90.0 + 5.0 * i) * std::sin(angle),
                           0.0);
    TargetTruth truth{fmt::format("T{}", i), 0, {}, static_cast<Address>(0x4000 + i)};
    for (int k = 0; k < kRounds; ++k) {
      Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
      x.head<3>() = start + k * kTimeStepS * velocity;
      x.segment<3>(3) = velocity;
      truth.states.push_back(x);
    }
    truths.push_back(std::move(truth));
  }
  return truths;
}

DetectionConfig radar_sees(const SensorBias& bias) {
  DetectionConfig sees;
  sees.probability = 0.9;
  sees.field_of_view.max_range_m = 90000.0;
  sees.field_of_view.min_elevation_rad = 0.0;
  sees.clutter_per_scan = 1.0;
  sees.bias = bias;
  return sees;
}

DetectionConfig adsb_hears() {
  DetectionConfig hears;
  hears.probability = 0.95;
  hears.field_of_view.max_range_m = 200000.0;
  hears.reports_address = true;
  return hears;
}

// One radar detection the picture paired with a track, and the ADS-B report paired with the
// same track in the same round.
struct PairedWithReference {
  Vector3 z;
  Vector<6> reference;
};

// The batch least-squares estimate of one radar's biases from `pairs`: each residual against
// the reference's position, r = z - h(p) ≈ G b + H (x - p) + ν, whitened by R + H R_p Hᵀ and
// stacked under the same prior as the online estimate's, solved by QR. No filter, no track
// prior: only which detection the picture gave which aircraft.
GaussianState<4> batch_estimate(const Radar& radar, const std::vector<PairedWithReference>& pairs,
                                const Covariance<3>& noise, const Covariance<3>& reference_noise,
                                const Vector<4>& prior_std) {
  Eigen::MatrixXd a(3 * pairs.size() + 4, 4);
  Eigen::VectorXd b(3 * pairs.size() + 4);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Vector<N> x = pairs[i].reference;
    const Jacobian<3, N> h = radar.jacobian(x);
    const Matrix<3, 4> g = Estimate::bias_jacobian(h, x);
    const Covariance<3> s = noise + h.leftCols<3>() * reference_noise * h.leftCols<3>().transpose();
    const Eigen::LLT<Covariance<3>> factor(s);
    const auto row = static_cast<Eigen::Index>(3 * i);
    a.middleRows<3>(row) = factor.matrixL().solve(g);
    b.segment<3>(row) = factor.matrixL().solve(radar.residual(pairs[i].z, radar.predict(x)));
  }
  a.bottomRows<4>() = prior_std.cwiseInverse().asDiagonal().toDenseMatrix();
  b.tail<4>().setZero();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  const Eigen::MatrixXd r = qr.matrixQR().topRows<4>().triangularView<Eigen::Upper>();
  const Matrix<4, 4> r_inverse = r.triangularView<Eigen::Upper>().solve(Matrix<4, 4>::Identity());
  return {qr.solve(b), r_inverse * r_inverse.transpose()};
}

// The test's body, for a tracker whose updater relinearises `relinearisations` times.
void expect_one_estimate_near_the_truths_and_the_batch(int relinearisations) {
  const std::vector<TargetTruth> truths = aircraft();
  const std::vector<Station> known = stations();
  const Model motion(kTimeStepS, {5.0, 5.0});
  const Vector<N> initial_variance = Vector<N>::Constant(100.0);
  TrackerConfig config;
  config.registration.kind = "least_squares";
  config.updater.relinearisations = relinearisations;
  const PeerTracks peer_tracks(motion, initial_variance, relinearisations);
  std::vector<Peer> peers(known.size(), Peer(peer_tracks, known, config));
  Center center(CenterStackedTracks<Model>(motion, initial_variance, relinearisations), known,
                config);
  const std::vector<DetectionConfig> sees = {radar_sees(kRadar1Bias), radar_sees(kRadar2Bias),
                                             adsb_hears()};

  std::vector<std::vector<PairedWithReference>> paired(2);
  double worst_center_gap = 0.0;
  double worst_track_gap = 0.0;
  std::size_t considering = 0;       // track-rounds with cross-covariances kept
  std::size_t started_by_radar = 0;  // (new track, radar that started it) pairs
  for (int k = 0; k < kRounds; ++k) {
    if (k == kRounds / 2) {
      // Station 3's peer restarts: a fresh one takes the picture and the registration's sums
      // from peer 1, and from then on holds the same bits as every other.
      Peer fresh(peer_tracks, known, config);
      fresh.restore({peers[0].tracks().begin(), peers[0].tracks().end()});
      ASSERT_TRUE(fresh.restore_biases(peers[0].bias_sums()));
      peers[2] = std::move(fresh);
    }
    std::vector<Scan> scans;
    for (std::size_t s = 0; s < known.size(); ++s) {
      scans.push_back(simulate_scan(known[s].id, test::truth_sensor_of(known[s]),
                                    test::site_of(known[s]), known[s].noise, sees[s], truths, k,
                                    kSeed, 0));
    }
    const auto reports =
        test::play_picture_round(static_cast<std::uint64_t>(k), peers, center,
                                 std::span<const Station>(known), std::span<const Scan>(scans));
    for (std::size_t p = 1; p < peers.size(); ++p) {
      ASSERT_EQ(peers[0].digest(), peers[p].digest()) << "round " << k;
      for (const Station& station : known) {
        const SensorBias& mine = peers[0].bias_of(station.id).bias();
        const SensorBias& theirs = peers[p].bias_of(station.id).bias();
        ASSERT_TRUE(mine.range_m == theirs.range_m && mine.azimuth_rad == theirs.azimuth_rad &&
                    mine.elevation_rad == theirs.elevation_rad && mine.time_s == theirs.time_s)
            << "round " << k << ", peer " << p << ", station " << station.id;
      }
    }
    // The center's tracks and their cross-covariances with the bias errors (registration/
    // considered_biases.hpp), against the peers'.
    ASSERT_EQ(center.tracks().size(), peers[0].tracks().size()) << "round " << k;
    for (std::size_t t = 0; t < center.tracks().size(); ++t) {
      const auto& mine = peers[0].tracks()[t];
      const auto& theirs = center.tracks()[t];
      ASSERT_EQ(mine.id, theirs.id);
      worst_track_gap = std::max(worst_track_gap, (mine.filter.mean - theirs.filter.mean).norm() /
                                                      (1.0 + mine.filter.mean.norm()));
      ASSERT_EQ(mine.considered.size(), theirs.considered.size()) << "round " << k;
      for (std::size_t c = 0; c < mine.considered.size(); ++c) {
        ASSERT_EQ(mine.considered[c].station_id, theirs.considered[c].station_id);
        const double scale = 1.0 + mine.considered[c].cross.norm();
        worst_track_gap =
            std::max(worst_track_gap,
                     (mine.considered[c].cross - theirs.considered[c].cross).norm() / scale);
      }
      if (!mine.considered.empty()) ++considering;
      // A track started this round (history of one round; updated_by: the stations that
      // started it) holds a C̃ for each registered radar among them, from its first fix.
      if (mine.history.rounds() == 1 && k > 0) {
        for (const int station : mine.updated_by) {
          if (station == kAdsb) continue;
          ++started_by_radar;
          const bool held = std::any_of(mine.considered.begin(), mine.considered.end(),
                                        [&](const auto& c) { return c.station_id == station; });
          EXPECT_TRUE(held) << "round " << k << ", track " << mine.id << ", radar " << station;
        }
      }
    }
    for (const Station& station : known) {
      const Vector<4> mine = Estimate::from_sensor_bias(peers[0].bias_of(station.id).bias());
      const Vector<4> theirs = Estimate::from_sensor_bias(center.bias_of(station.id).bias());
      worst_center_gap = std::max(worst_center_gap, (mine - theirs).norm() / (1.0 + mine.norm()));
    }
    // The associations: each radar's paired detection, beside the ADS-B report of its track.
    const auto& adsb = reports[2];
    for (std::size_t r = 0; r < 2; ++r) {
      const auto& report = reports[r];
      for (std::size_t p = 0; p < report.pairs.size(); ++p) {
        const auto heard = std::find_if(adsb.pairs.begin(), adsb.pairs.end(), [&](const auto& a) {
          return a.track == report.pairs[p].track;
        });
        if (heard == adsb.pairs.end()) continue;
        paired[r].push_back({report.paired_detections[p].head<3>(),
                             scans[2].detections[heard->detection].head<6>()});
      }
    }
  }
  EXPECT_LT(worst_center_gap, 1e-9);
  EXPECT_LT(worst_track_gap, 1e-9);
  EXPECT_GT(considering, 0U) << "the EKF's tracks keep their registered stations' bias errors";
  EXPECT_GT(started_by_radar, 0U);

  const Vector<4> prior_std(config.registration.range_std_m, config.registration.azimuth_std_rad,
                            config.registration.elevation_std_rad, config.registration.time_std_s);
  const std::vector<SensorBias> truth = {kRadar1Bias, kRadar2Bias};
  for (std::size_t r = 0; r < 2; ++r) {
    const StationBias<N>& online = peers[0].bias_of(known[r].id);
    const Vector<4> estimate = Estimate::from_sensor_bias(online.bias());
    const Vector<4> sigma = Estimate::from_sensor_bias(online.sigma());
    const Vector<4> truth_r = Estimate::from_sensor_bias(truth[r]);
    const GaussianState<4> batch = batch_estimate(
        std::get<Radar>(known[r].sensor), paired[r], known[r].noise.topLeftCorner<3, 3>(),
        Covariance<3>(Vector3::Constant(225.0).asDiagonal()), prior_std);
    const Vector<4> batch_sigma = batch.covariance.diagonal().cwiseSqrt();
    ASSERT_GT(paired[r].size(), 500U) << "radar " << known[r].id;
    for (int e = 0; e < 4; ++e) {
      SCOPED_TRACE(testing::Message()
                   << "radar " << known[r].id << ", entry " << e << ": truth " << truth_r(e)
                   << ", online " << estimate(e) << " ± " << sigma(e) << ", batch " << batch.mean(e)
                   << " ± " << batch_sigma(e) << " from " << paired[r].size());
      // It learnt: its σ is a tenth of the prior's or less.
      EXPECT_LT(sigma(e), 0.1 * prior_std(e));
      EXPECT_LT(std::abs(estimate(e) - truth_r(e)), 3.0 * sigma(e));
      EXPECT_LT(std::abs(batch.mean(e) - truth_r(e)), 3.0 * batch_sigma(e));
      EXPECT_LT(std::abs(estimate(e) - batch.mean(e)), std::hypot(sigma(e), batch_sigma(e)));
    }
  }
}

TEST(RegisteredPicture, PeersLearnOneEstimateTheTruthsAndABatchSolutionAgree) {
  expect_one_estimate_near_the_truths_and_the_batch(0);
}

// With each detection's increment and terms linearised at its own point (fusion/
// relinearised_increment.hpp), peers and center alike.
TEST(RegisteredPicture, ARelinearisingTrackerLearnsAlikeAtEveryNode) {
  expect_one_estimate_near_the_truths_and_the_batch(1);
}

}  // namespace
}  // namespace skyfuse
