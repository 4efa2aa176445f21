// The per-step hot paths allocate nothing: a station step (predict, measurement model,
// increment), the fusion of M increments, and the stacked EKF update once sized for M.
// This binary replaces the global operator new with one that counts, so the check is real.
// Eigen allocates dynamic storage with malloc, not operator new: EIGEN_RUNTIME_NO_MALLOC
// lets the test make any such allocation an assertion failure as well.
#define EIGEN_RUNTIME_NO_MALLOC
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/mixed_stacked_ekf.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/tracking/fixed_lag_peer.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/step_collector.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// The replacements below pair malloc with free by design; GCC sees only the free of a pointer
// that came from "operator new" and warns.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  ++g_allocations;
  const auto align = static_cast<std::size_t>(alignment);
  if (void* p = std::aligned_alloc(align, (size + align - 1) / align * align)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

namespace skyfuse {
namespace {

struct Problem {
  Scenario scenario = load_default_scenario();
  TruthTrajectory truth =
      generate_truth(scenario.target, scenario.target.speeds_mps[0], scenario.time_step_s, 600);
};

volatile std::uint64_t settled_sink = 0;  // keeps a value from being optimised away

TEST(HotPathAllocations, StationStepFusionAndStackedUpdateAllocateNothing) {
  const Problem p;
  const auto motion = make_motion_model<ConstantAcceleration3D>(p.scenario);
  for (int m : {1, 4, 10}) {
    const auto count = static_cast<std::size_t>(m);
    PeerTracker peer(motion,
                     initial_estimate<ConstantAcceleration3D>(p.scenario, p.truth.states[0], 0));
    GaussianState<9> central = peer.estimate();
    StackedEkf<9, RangeAzimuthElevation<9>> stacked;
    std::vector<StationObservation<RangeAzimuthElevation<9>>> observations(count);
    // A station's side as the process runs it: contributions (increment + prior) gathered by
    // a StepCollector, their increments copied into the round in id order and fused onto the
    // lowest id's prior.
    std::vector<int> ids;
    for (int i = 0; i < m; ++i) ids.push_back(p.scenario.stations[static_cast<std::size_t>(i)].id);
    StepCollector<PeerContribution<9>> collector(ids);
    std::vector<InformationIncrement<9>> round;
    round.reserve(count);
    const std::vector<double> weights(count, 1.0);
    for (int i = 0; i < m; ++i) {
      const StationConfig& s = p.scenario.stations[static_cast<std::size_t>(i)];
      observations[static_cast<std::size_t>(i)] = {s.id, RangeAzimuthElevation<9>(s.position_m),
                                                   Vector3::Zero(),
                                                   station_noise_covariance<3>(p.scenario, s, 0)};
    }

    auto step = [&](std::size_t k) {
      for (auto& obs : observations) {
        obs.z =
            simulate_measurement(obs.sensor, p.truth.states[k], obs.noise, 1, 0, obs.station_id, k);
      }
      for (const auto& obs : observations) {
        PeerContribution<9> c;
        c.prior = peer.estimate();
        ASSERT_EQ(peer.make_increment(obs.station_id, obs.sensor, obs.z, obs.noise, c.increment),
                  NumericalStatus::kOk);
        ASSERT_FALSE(collector.offer(k, obs.station_id, c).has_value());
      }
      round.clear();
      for (const PeerContribution<9>& c : collector.payloads()) round.push_back(c.increment);
      ASSERT_EQ(peer.fuse_round(collector.payloads().front().prior, round, weights).status,
                NumericalStatus::kOk);
      collector.advance();
      ASSERT_EQ(stacked.update(central, observations).status, NumericalStatus::kOk);
      peer.predict();
      predict(central, motion);
    };

    step(0);  // the stacked EKF sizes its buffers for M here, once
    Eigen::internal::set_is_malloc_allowed(false);
    const long before = g_allocations.load();
    for (std::size_t k = 1; k < 500; ++k) step(k);
    const long after = g_allocations.load();
    Eigen::internal::set_is_malloc_allowed(true);
    EXPECT_EQ(after - before, 0) << "heap allocations in 499 steps with M = " << m;
  }
}

// The center's update over mixed sensors (three radars and the aircraft's GPS): its stacked H,
// nu, R and every product keep their buffers from step to step.
TEST(HotPathAllocations, TheMixedStackedUpdateAllocatesNothingAfterItsFirstStep) {
  const Problem p;
  const auto motion = make_motion_model<ConstantAcceleration3D>(p.scenario);
  GaussianState<9> central =
      initial_estimate<ConstantAcceleration3D>(p.scenario, p.truth.states[0], 0);
  using Pack = AnySensor<9>;
  std::vector<Pack::Observation> observations;
  for (std::size_t i = 0; i < 3; ++i) {
    const StationConfig& s = p.scenario.stations[i];
    observations.emplace_back(StationObservation<RangeAzimuthElevation<9>>{
        s.id, RangeAzimuthElevation<9>(s.position_m), Vector3::Zero(),
        station_noise_covariance<3>(p.scenario, s, 0)});
  }
  StationObservation<PositionVelocity<9>> gps;
  gps.station_id = 11;
  gps.z.setZero();
  gps.noise = Vector<6>(9.0, 9.0, 9.0, 4.0, 4.0, 4.0).asDiagonal();
  observations.emplace_back(gps);
  MixedStackedEkf<9, Pack> stacked;

  auto step = [&](std::size_t k) {
    for (auto& observation : observations) {
      with_observation(observation, [&](auto& o) {
        o.z = simulate_measurement(o.sensor, p.truth.states[k], o.noise, 1, 0, o.station_id, k);
      });
    }
    ASSERT_EQ(stacked.update(central, observations).status, NumericalStatus::kOk);
    predict(central, motion);
  };

  step(0);  // the buffers take their size here, once
  Eigen::internal::set_is_malloc_allowed(false);
  const long before = g_allocations.load();
  for (std::size_t k = 1; k < 500; ++k) step(k);
  const long after = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(after - before, 0) << "heap allocations in 499 mixed stacked updates";
}

// Fixed-lag re-fusion: a round with a late contribution fused again over the lag, and settled
// rounds, keep to the buffers made at construction.
TEST(HotPathAllocations, AFixedLagPeerAllocatesNothingPerRound) {
  const Problem p;
  const auto motion = make_motion_model<ConstantAcceleration3D>(p.scenario);
  const std::vector<int> ids = {1, 2, 3, 4};
  const std::vector<double> weights(ids.size(), 1.0);
  FixedLagPeer<ConstantAcceleration3D> peer(
      motion, initial_estimate<ConstantAcceleration3D>(p.scenario, p.truth.states[0], 0), ids,
      weights, 3);
  const auto fuse_round = [&peer](std::uint64_t, auto slot_at) {
    return peer.round().fuse(peer.tracker(), slot_at);
  };
  PeerContribution<9> late;
  auto step = [&](std::uint64_t k) {
    if (k > 0 && k % 5 == 0) {  // station 4's contribution to the last round comes now
      ASSERT_FALSE(peer.collector().offer(k - 1, 4, late).has_value());
      peer.kept(k - 1);
    }
    ASSERT_EQ(peer.refresh_prior(fuse_round), NumericalStatus::kOk);
    for (int id : ids) {
      PeerContribution<9> c;
      c.prior = peer.tracker().estimate();
      c.increment.station_id = id;
      c.increment.delta_information(0, 0) = 1.0;
      c.increment.delta_vector(0) = static_cast<double>(k);
      if (id == 4 && k % 5 == 4) {
        late = c;  // held back
        continue;
      }
      ASSERT_FALSE(peer.collector().offer(k, id, c).has_value());
    }
    ASSERT_EQ(peer.fuse_current(fuse_round).status, NumericalStatus::kOk);
    settled_sink = peer.settled_round().value_or(0);
    peer.predict();
    peer.advance();
  };
  for (std::uint64_t k = 0; k < 10; ++k) step(k);
  Eigen::internal::set_is_malloc_allowed(false);
  const long before = g_allocations.load();
  for (std::uint64_t k = 10; k < 500; ++k) step(k);
  const long after = g_allocations.load();
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(after - before, 0) << "heap allocations in 490 rounds with a lag of 3";
  EXPECT_EQ(peer.late_used(), 99U);
}

TEST(HotPathAllocations, TheCounterSeesAnAllocation) {
  // The hook must be live, or the test above proves nothing.
  // The vector escapes through a volatile pointer: the compiler may not elide its object or
  // its buffer (it may elide both when nothing observes them).
  static std::vector<double>* volatile escaped = nullptr;
  const long before = g_allocations.load();
  escaped = new std::vector<double>(100);
  delete escaped;
  EXPECT_EQ(g_allocations.load() - before, 2);
}

}  // namespace
}  // namespace skyfuse

namespace skyfuse {
namespace {

TEST(HotPathAllocationsDeathTest, EigensMallocGuardIsLive) {
  // Eigen's dynamic matrices bypass operator new; the guard must abort on them.
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::MatrixXd m(40, 40);
        m.setZero();
      },
      "is_malloc_allowed");
}

}  // namespace
}  // namespace skyfuse
