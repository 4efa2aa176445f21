// The IMM over modes of different dimensions (paper 001's CV + CA + CT).

#include "skyfuse/filters/imm.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "skyfuse/models/planar/constant_acceleration_2d.hpp"
#include "skyfuse/models/planar/constant_velocity_2d.hpp"
#include "skyfuse/models/planar/coordinated_turn_2d.hpp"
#include "skyfuse/models/planar/position_2d.hpp"

namespace skyfuse {
namespace {

constexpr double kDt = 0.1;
constexpr double kSigmaQ2 = 10.0;
const Covariance<2> kR = 9.0 * Covariance<2>::Identity();

using PlanarImm = Imm<PlanarState, ConstantVelocity2D, ConstantAcceleration2D, CoordinatedTurn2D>;

PlanarImm::CommonState start_at(double vx, double vy) {
  PlanarImm::CommonState s;
  s.mean << 0.0, vx, 0.0, vy, 0.0, 0.0, 0.0;
  s.covariance = Covariance<7>::Identity();
  return s;
}

// Paper 001's IMM, except that the CT mode's turn rate wanders with 0.01 (rad/s)^2/s rather than
// sigma_Q^2 = 10: at the paper's value its turn rate moves by 1 rad/s per step, so the CT mode
// can hardly tell a turn from noise and no mode clearly wins.
PlanarImm three_mode_imm(const PlanarImm::CommonState& start) {
  Matrix<3, 3> switching = Matrix<3, 3>::Constant(0.025);
  switching.diagonal().setConstant(0.95);
  return PlanarImm({ConstantVelocity2D(kDt, kSigmaQ2), ConstantAcceleration2D(kDt, kSigmaQ2),
                    CoordinatedTurn2D(kDt, kSigmaQ2, 0.01)},
                   switching, Vector<3>::Constant(1.0 / 3.0), start);
}

// A deterministic stand-in for N(0, 3^2) noise: the same sequence for every filter compared.
Vector<2> noise(int k) {
  return 3.0 * Vector<2>(std::sin(12.9898 * k), std::cos(78.233 * k));
}

TEST(Imm, OfOneModeIsThatModesFilterBitForBit) {
  using OneMode = Imm<PlanarState, CoordinatedTurn2D>;
  const CoordinatedTurn2D model(kDt, kSigmaQ2);
  OneMode::CommonState start = start_at(15.0, 2.0);
  start.mean(PlanarState::kTurnRate) = 0.2;
  OneMode imm({model}, Matrix<1, 1>::Identity(), Vector<1>::Ones(), start);

  GaussianState<5> plain;
  plain.mean << 0.0, 15.0, 0.0, 2.0, 0.2;
  plain.covariance = Covariance<5>::Identity();
  Vector<5> truth = plain.mean;
  for (int k = 0; k < 200; ++k) {
    truth = model.propagate(truth);
    const Vector<2> z = Vector<2>(truth(0), truth(2)) + noise(k);
    imm.predict();
    predict(plain, model);
    ASSERT_EQ((imm.update<Position2D>(z, kR)), NumericalStatus::kOk);
    update(plain, Position2D<CoordinatedTurn2D>{}, z, kR);
    ASSERT_EQ(imm.mode_state<0>().mean, plain.mean) << "step " << k;
    ASSERT_EQ(imm.mode_state<0>().covariance, plain.covariance) << "step " << k;
    const auto combined = imm.estimate();
    ASSERT_EQ(combined.mean(PlanarState::kX), plain.mean(0));
    ASSERT_EQ(combined.mean(PlanarState::kY), plain.mean(2));
    ASSERT_EQ(imm.mode_probabilities()(0), 1.0);
  }
}

// Flies straight for `straight` steps, then turns at `turn_rate` for `turning` steps, and
// returns the mode probabilities averaged over each phase's last half.
struct PhaseProbabilities {
  Vector<3> straight = Vector<3>::Zero();
  Vector<3> turning = Vector<3>::Zero();
};
PhaseProbabilities fly(PlanarImm& imm, int straight, int turning, double turn_rate) {
  const CoordinatedTurn2D truth_model(kDt, 0.0);
  Vector<5> truth;
  truth << 0.0, 20.0, 0.0, 0.0, 0.0;
  PhaseProbabilities out;
  for (int k = 0; k < straight + turning; ++k) {
    if (k == straight) truth(4) = turn_rate;
    truth = truth_model.propagate(truth);
    imm.predict();
    const Vector<2> z = Vector<2>(truth(0), truth(2)) + noise(k);
    EXPECT_EQ((imm.update<Position2D>(z, kR)), NumericalStatus::kOk);
    EXPECT_NEAR(imm.mode_probabilities().sum(), 1.0, 1e-12);
    EXPECT_TRUE((imm.mode_probabilities().array() >= 0.0).all());
    if (k >= straight / 2 && k < straight)
      out.straight += imm.mode_probabilities() / (straight / 2);
    if (k >= straight + turning / 2)
      out.turning += imm.mode_probabilities() / (turning - turning / 2);
  }
  return out;
}

TEST(Imm, CvModeDominatesAStraightPathAndCtModeATurn) {
  PlanarImm imm = three_mode_imm(start_at(20.0, 0.0));
  const PhaseProbabilities p = fly(imm, 200, 200, 0.4);  // 20 m/s at 0.4 rad/s: 8 m/s^2
  Vector<3>::Index straight_mode = 0;
  Vector<3>::Index turning_mode = 0;
  p.straight.maxCoeff(&straight_mode);
  p.turning.maxCoeff(&turning_mode);
  EXPECT_EQ(straight_mode, 0) << "mean probabilities on the straight: " << p.straight.transpose();
  EXPECT_EQ(turning_mode, 2) << "mean probabilities in the turn: " << p.turning.transpose();
}

TEST(Imm, ModesOfDifferentDimensionsMixInTheCommonState) {
  PlanarImm imm = three_mode_imm(start_at(20.0, 0.0));
  fly(imm, 50, 100, 0.4);
  // CV and CA hold no turn rate and mix in as omega = 0 with variance 0, which pulls the CT
  // mode's estimate of the true 0.4 rad/s towards 0 by their mixing weights each step; the CT
  // mode still carries most of it.
  const double ct_turn_rate = imm.mode_state<2>().mean(CoordinatedTurn2D::kTurnRate);
  EXPECT_GT(ct_turn_rate, 0.2);
  EXPECT_LT(ct_turn_rate, 0.45);
  const PlanarImm::CommonState combined = imm.estimate();
  EXPECT_EQ(combined.covariance, combined.covariance.transpose());
  EXPECT_GE(
      Eigen::SelfAdjointEigenSolver<Covariance<7>>(combined.covariance).eigenvalues().minCoeff(),
      -1e-12);
  // The combined turn rate is the CT mode's, weighted by its probability (CV and CA add 0).
  EXPECT_NEAR(combined.mean(PlanarState::kTurnRate),
              imm.mode_probabilities()(2) * imm.mode_state<2>().mean(CoordinatedTurn2D::kTurnRate),
              1e-12);
}

TEST(Imm, RefusesSwitchingRowsThatDoNotSumToOne) {
  Matrix<3, 3> switching = Matrix<3, 3>::Constant(0.1);
  EXPECT_THROW(PlanarImm({ConstantVelocity2D(kDt, 1.0), ConstantAcceleration2D(kDt, 1.0),
                          CoordinatedTurn2D(kDt, 1.0)},
                         switching, Vector<3>::Constant(1.0 / 3.0), start_at(1.0, 0.0)),
               std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
