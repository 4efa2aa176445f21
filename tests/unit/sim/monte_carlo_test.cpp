#include "skyfuse/sim/monte_carlo.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse {
namespace {

TEST(MonteCarlo, CentralAndPeerToPeerAgreeAtEveryStepWithUnitWeights) {
  const Scenario scenario = load_default_scenario();
  for (double speed : scenario.target.speeds_mps) {
    const TruthTrajectory truth =
        generate_truth(scenario.target, speed, scenario.time_step_s, scenario.steps);
    for (int m : {1, 3, 10}) {
      double worst = 0.0;
      simulate_run(scenario, truth, m, 0, [&](const StepRecord& r) {
        worst = std::max(worst, (r.central.mean.head<3>() - r.decentralised.mean.head<3>()).norm());
      });
      EXPECT_LT(worst, 1e-6) << "M = " << m << ", speed " << speed;
    }
  }
}

// The largest distance, over one run of up to 10 stations, of the tree exchange's peers (clusters
// of `fanout`) from the central filter and from the flat exchange's peers.
struct TreeDistances {
  double from_central = 0.0;
  double from_flat = 0.0;
};
TreeDistances tree_against_flat(const Scenario& flat, int fanout) {
  Scenario tree = flat;
  apply_exchange_overrides(tree, ExchangeConfig::Kind::kTree, fanout);
  const TruthTrajectory truth =
      generate_truth(flat.target, flat.target.speeds_mps.front(), flat.time_step_s, flat.steps);
  std::vector<Vector3> flat_p2p;
  const int m = std::min(10, static_cast<int>(flat.stations.size()));
  simulate_run(flat, truth, m, 0,
               [&](const StepRecord& r) { flat_p2p.push_back(r.decentralised.mean.head<3>()); });
  TreeDistances d;
  std::size_t k = 0;
  simulate_run(tree, truth, m, 0, [&](const StepRecord& r) {
    const Vector3 p = r.decentralised.mean.head<3>();
    d.from_central = std::max(d.from_central, (r.central.mean.head<3>() - p).norm());
    d.from_flat = std::max(d.from_flat, (flat_p2p.at(k++) - p).norm());
  });
  EXPECT_EQ(k, flat_p2p.size());
  return d;
}

// The tree exchange: the peers sum in clusters, then the clusters' sums. The same fused filter in
// another order of summation: within 1e-9 m of the central filter and of the flat exchange's
// peers at every step, for the EKF and the unscented filter (clusters of 4), the IMM (clusters
// of 3: each mode's increments and likelihood terms) and paper 002's NCRKF (3 receivers in
// clusters of 2, by its TDOA round rule).
TEST(MonteCarlo, TheTreeExchangesPeersFollowTheCentralFilterAsTheFlatOnesDo) {
  for (const char* file : {"/scenarios/paper000.yaml", "/scenarios/paper000-ukf.yaml",
                           "/scenarios/paper000-imm.yaml", "/scenarios/paper002.yaml"}) {
    const Scenario flat = load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + file);
    const int fanout = flat.filter.kind == "imm" ? 3 : flat.filter.kind == "ncrkf" ? 2 : 4;
    const TreeDistances d = tree_against_flat(flat, fanout);
    EXPECT_LT(d.from_central, 1e-9) << file;
    // The NCRKF's compensated increments are nearly singular: another order of summation alone
    // moves its track by about 4e-8 m over paper 002's 5 000 steps (its center sums in the
    // peers' order, so central and peer-to-peer stay together).
    EXPECT_LT(d.from_flat, flat.filter.kind == "ncrkf" ? 1e-7 : 1e-9) << file;
    EXPECT_GT(d.from_flat, 0.0) << file << ": another order of summation, not the flat bits";
  }
}

// Filter kind "imm": the central stacked IMM and the peers' fused one agree to 1e-9 at every
// step, and through the turn the IMM beats the paper's CA filter on the same measurements.
TEST(MonteCarlo, AnImmScenarioRunsCentralAndPeerToPeerAlikeAndFollowsTheTurn) {
  const Scenario imm = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper000-imm.yaml");
  Scenario ca = imm;
  ca.filter.kind = "ekf";
  const TruthTrajectory truth =
      generate_truth(imm.target, imm.target.speeds_mps.front(), imm.time_step_s, imm.steps);
  const RunTrace t = simulate_run(imm, truth, 4, 0);
  EXPECT_LT(t.max_abs_diff_m, 1e-9);
  const RunTrace c = simulate_run(ca, truth, 4, 0);
  double imm_turn = 0.0;
  double ca_turn = 0.0;
  for (std::size_t k = 500; k < 900; ++k) {  // 10 s to 18 s
    imm_turn += t.sq_error_p2p[k];
    ca_turn += c.sq_error_p2p[k];
  }
  EXPECT_LT(imm_turn, 0.5 * ca_turn);
}

// Filter kind "ncrkf" (paper 002's receivers): the center fuses the same bias-compensated
// increments onto its own prior, so central and peer-to-peer hold the same bits; two receivers
// cannot fix the target, three can.
TEST(MonteCarlo, AnNcrkfScenarioRunsCentralAndPeerToPeerAlike) {
  const Scenario s = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  const TruthTrajectory truth =
      generate_truth(s.target, s.target.speeds_mps.front(), s.time_step_s, s.steps);
  const RunTrace three = simulate_run(s, truth, 3, 0);
  EXPECT_EQ(three.max_abs_diff_m, 0.0);
  EXPECT_EQ(three.refused_p2p, three.refused_central);
  double late = 0.0;
  for (std::size_t k = 2500; k < 5000; ++k) late += three.sq_error_p2p[k];
  EXPECT_LT(std::sqrt(late / 2500.0), 20.0);
  const RunTrace two = simulate_run(s, truth, 2, 0);
  double late_two = 0.0;
  for (std::size_t k = 2500; k < 5000; ++k) late_two += two.sq_error_p2p[k];
  EXPECT_GT(std::sqrt(late_two / 2500.0), 3.0 * std::sqrt(late / 2500.0));
}

// The NEES scores an estimate's error against that estimate's covariance. With one TDOA
// receiver the NCRKF's rounds fuse nothing (its increment is indefinite and the fused
// information would not be positive definite, so the round rule refuses it): the estimate is the
// predicted one, and the information of the last fusion, from before that prediction (or the
// identity the tracker starts with, when none has fused yet), would score it against the wrong
// covariance (the sweep's ANEES at M = 1 was 187 071 that way, 3.85 against P).
TEST(MonteCarlo, TheNeesOfARoundThatFusedNothingIsAgainstThePredictedCovariance) {
  const Scenario s = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  const TruthTrajectory truth =
      generate_truth(s.target, s.target.speeds_mps.front(), s.time_step_s, s.steps);
  std::vector<double> expected;
  const RunTrace one = simulate_run(s, truth, 1, 0, [&](const StepRecord& r) {
    const Vector<9> error = TdoaRelativeMotion::from_kinematics(r.truth) - r.decentralised.mean;
    const Covariance<9> p = r.decentralised.covariance;
    expected.push_back(error.dot(p.ldlt().solve(error)));
  });
  ASSERT_GT(one.refused_p2p, 0) << "no round fused nothing: the test shows nothing";
  ASSERT_EQ(expected.size(), one.nees_p2p.size());
  int off = 0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (std::abs(one.nees_p2p[k] - expected[k]) > 1e-4 * expected[k]) {
      if (off++ == 0) {
        ADD_FAILURE() << "step " << k << ": " << one.nees_p2p[k] << " vs " << expected[k];
      }
    }
  }
  EXPECT_EQ(off, 0) << "of " << one.refused_p2p << " rounds that fused nothing";
}

TEST(MonteCarlo, ReproducesThePapersRmseBoundForThreeOrMoreStations) {
  // A smaller version of the README sweep (which uses 50 runs): 20 runs, full length.
  const Scenario scenario = load_default_scenario();
  for (double speed : scenario.target.speeds_mps) {
    for (int m : {3, 4}) {
      const MonteCarloSummary s = run_monte_carlo(scenario, {{m}, speed, 20, 2}).front();
      EXPECT_LT(s.rmse_central_m, 0.3) << "M = " << m << ", " << speed * 3.6 << " km/h";
      EXPECT_LT(s.rmse_p2p_m, 0.3) << "M = " << m << ", " << speed * 3.6 << " km/h";
      EXPECT_LT(s.max_abs_diff_m, 1e-6);
    }
  }
}

TEST(MonteCarlo, OneStationCannotReachTheBound) {
  // The sweep must be able to show a failure: one station's 0.01 rad angles are metres wide.
  const Scenario scenario = load_default_scenario();
  const MonteCarloSummary s =
      run_monte_carlo(scenario, {{1}, scenario.target.speeds_mps[0], 5, 2}).front();
  EXPECT_GT(s.rmse_p2p_m, 1.0);
}

TEST(MonteCarlo, ResultDoesNotDependOnTheThreadCount) {
  Scenario scenario = load_default_scenario();
  scenario.steps = 300;
  const double speed = scenario.target.speeds_mps[1];
  const MonteCarloSummary one = run_monte_carlo(scenario, {{4}, speed, 6, 1}).front();
  const MonteCarloSummary three = run_monte_carlo(scenario, {{4}, speed, 6, 3}).front();
  EXPECT_EQ(one.rmse_central_m, three.rmse_central_m);
  EXPECT_EQ(one.rmse_p2p_m, three.rmse_p2p_m);
  EXPECT_EQ(one.anees, three.anees);
  EXPECT_EQ(one.max_abs_diff_m, three.max_abs_diff_m);
}

TEST(MonteCarlo, StationCountsRunTogetherEqualEachRunAlone) {
  // The sweep simulates each run's measurements once for every M; each M must still get
  // exactly the numbers it gets on its own.
  Scenario scenario = load_default_scenario();
  scenario.steps = 300;
  const double speed = scenario.target.speeds_mps[1];
  const std::vector<MonteCarloSummary> together =
      run_monte_carlo(scenario, {{5, 2, 9}, speed, 3, 2});
  ASSERT_EQ(together.size(), 3U);
  for (const MonteCarloSummary& t : together) {
    const MonteCarloSummary alone = run_monte_carlo(scenario, {{t.stations}, speed, 3, 1}).front();
    EXPECT_EQ(t.rmse_central_m, alone.rmse_central_m) << "M = " << t.stations;
    EXPECT_EQ(t.rmse_p2p_m, alone.rmse_p2p_m) << "M = " << t.stations;
    EXPECT_EQ(t.anees, alone.anees) << "M = " << t.stations;
    EXPECT_EQ(t.anis_per_dof, alone.anis_per_dof) << "M = " << t.stations;
  }
  EXPECT_NE(together[0].rmse_p2p_m, together[1].rmse_p2p_m);
}

TEST(MonteCarlo, DifferentSeedsGiveDifferentResults) {
  Scenario scenario = load_default_scenario();
  scenario.steps = 200;
  const double speed = scenario.target.speeds_mps[0];
  const MonteCarloSummary a = run_monte_carlo(scenario, {{3}, speed, 4, 1}).front();
  scenario.seed += 1;
  const MonteCarloSummary b = run_monte_carlo(scenario, {{3}, speed, 4, 1}).front();
  EXPECT_NE(a.rmse_p2p_m, b.rmse_p2p_m);
}

TEST(MonteCarlo, RefusesMoreStationsThanTheScenarioHas) {
  const Scenario scenario = load_default_scenario();
  EXPECT_THROW(run_monte_carlo(scenario, {{11}, 10.0, 1, 1}), std::invalid_argument);
  EXPECT_THROW(run_monte_carlo(scenario, {{0}, 10.0, 1, 1}), std::invalid_argument);
}

// Paper 000's radars and the aircraft's own GPS report in one network: the stacked update over
// mixed sensors and the fused increments agree, and the GPS adds what one radar lacks.
TEST(MonteCarlo, ARadarAndTheAircraftsGpsRunCentralAndPeerToPeerAlike) {
  std::string yaml(default_scenario_yaml());
  const std::string first_radar_end = "noise_std: [0.1, 0.01, 0.01]}\n";
  const auto at = yaml.find(first_radar_end);
  ASSERT_NE(at, std::string::npos);
  yaml.insert(at + first_radar_end.size(),
              "  - {id: 11, sensor: {kind: position_velocity, noise_std: [3, 3, 3, 2, 2, 2]}}\n");
  Scenario scenario = parse_scenario(yaml, "gps.yaml");
  scenario.steps = 500;
  ASSERT_EQ(scenario.stations[1].sensor.kind, "position_velocity");
  const double speed = scenario.target.speeds_mps[0];
  const MonteCarloSummary radar_alone = run_monte_carlo(scenario, {{1}, speed, 4, 2}).front();
  const MonteCarloSummary with_gps = run_monte_carlo(scenario, {{2}, speed, 4, 2}).front();
  EXPECT_LT(with_gps.max_abs_diff_m, 1e-6);
  EXPECT_LT(with_gps.rmse_p2p_m, 0.8 * radar_alone.rmse_p2p_m);
  EXPECT_GT(with_gps.anis_per_dof, 0.0);
}

}  // namespace
}  // namespace skyfuse
