// The merge of a track held twice (picture/track_merge.hpp): which tracks it drops, its distance
// against the hand-computed one, and its search by east against every pair tried.

#include "skyfuse/picture/track_merge.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "skyfuse/metrics/chi_square.hpp"

namespace skyfuse {
namespace {

constexpr int N = 6;
using TestTrack = Track<GaussianState<N>>;

GaussianState<N> estimate(const Vector3& p, const Vector3& v, double position_var,
                          double velocity_var) {
  GaussianState<N> x;
  x.mean << p, v;
  x.covariance = Covariance<N>::Zero();
  x.covariance.diagonal() << Vector3::Constant(position_var), Vector3::Constant(velocity_var);
  return x;
}

TestTrack track(TrackId id, TrackStatus status, Address address, const GaussianState<N>& x) {
  TestTrack t{id, status, {}, x, {}};
  t.address = address;
  return t;
}

std::vector<GaussianState<N>> estimates_of(const std::vector<TestTrack>& tracks) {
  std::vector<GaussianState<N>> out;
  for (const TestTrack& t : tracks) out.push_back(t.filter);
  return out;
}

// Which of `tracks` are held twice.
std::vector<char> held_twice(const std::vector<TestTrack>& tracks, double gate) {
  const std::vector<GaussianState<N>> estimates = estimates_of(tracks);
  MergeWork work;
  const std::size_t found = find_tracks_held_twice(
      std::span<const TestTrack>(tracks), std::span<const GaussianState<N>>(estimates), gate, work);
  EXPECT_EQ(found,
            static_cast<std::size_t>(std::count(work.dropped.begin(), work.dropped.end(), 1)));
  return work.dropped;
}

TEST(TrackMerge, TheDistanceIsThePositionAndVelocityDifferenceUnderBothSpreads) {
  const GaussianState<N> a = estimate({0.0, 0.0, 300.0}, {30.0, 0.0, 0.0}, 16.0, 1.0);
  const GaussianState<N> b = estimate({6.0, 8.0, 300.0}, {31.0, 0.0, 2.0}, 9.0, 3.0);
  // (36 + 64) / 25 + (1 + 4) / 4
  EXPECT_NEAR(merge_distance(a, b), 100.0 / 25.0 + 5.0 / 4.0, 1e-12);
  EXPECT_EQ(merge_distance(a, b), merge_distance(b, a));
}

TEST(TrackMerge, OnlyAConfirmedUnaddressedTrackOnAConfirmedAddressedTracksAircraftIsDropped) {
  const double gate = chi_square_quantile(0.99, kMergeDim);
  const Vector3 p(1000.0, -500.0, 300.0);
  const Vector3 v(30.0, 5.0, 0.0);
  const auto on = [&](const Vector3& dp, const Vector3& dv) {
    return estimate(p + dp, v + dv, 25.0, 1.0);
  };
  constexpr auto kConfirmed = TrackStatus::kConfirmed;
  const std::vector<TestTrack> tracks = {
      track(1, kConfirmed, 0xA1, on({0, 0, 0}, {0, 0, 0})),           // the aircraft's own
      track(2, kConfirmed, kNoAddress, on({4, -3, 6}, {0.5, 0, 0})),  // the same aircraft again
      track(3, kConfirmed, kNoAddress, on({2, 1, 0}, {0, 12, 0})),    // an aircraft crossing
      track(4, TrackStatus::kTentative, kNoAddress, on({1, 1, 1}, {0, 0, 0})),  // not yet sure
      track(5, kConfirmed, 0xB2, on({1, 0, 0}, {0, 0, 0})),  // another address: never merged
      track(6, kConfirmed, kNoAddress, on({400, 0, 0}, {0, 0, 0})),  // far off
  };
  EXPECT_EQ(held_twice(tracks, gate), (std::vector<char>{0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(held_twice(tracks, 0.0), std::vector<char>(tracks.size(), 0)) << "merge off";

  // A tentative addressed track (a spoof's first report, say) takes nothing.
  std::vector<TestTrack> tentative = tracks;
  tentative[0].status = TrackStatus::kTentative;
  tentative[4].status = TrackStatus::kTentative;
  EXPECT_EQ(held_twice(tentative, gate), std::vector<char>(tracks.size(), 0));
}

// The search looks only at addressed tracks within reach by east; it must find what trying every
// pair finds, over tracks of unequal, correlated spreads.
TEST(TrackMerge, TheSearchByEastFindsWhatEveryPairTriedFinds) {
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> spread(1.0, 400.0);
  const double gate = chi_square_quantile(0.99, kMergeDim);
  std::size_t found = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<TestTrack> tracks;
    for (std::uint64_t t = 0; t < 60; ++t) {
      GaussianState<N> x;
      // Crowded: 60 tracks in 300 m × 300 m, so that many pairs are near the gate.
      x.mean << 150.0 * unit(rng), 150.0 * unit(rng), 300.0 + 20.0 * unit(rng), 3.0 * unit(rng),
          3.0 * unit(rng), unit(rng);
      Matrix<N, N> root;
      for (int i = 0; i < N; ++i) {
        for (int j = 0; j < N; ++j) root(i, j) = unit(rng);
      }
      x.covariance = root * root.transpose() * spread(rng) / N + Covariance<N>::Identity();
      const Address address = t % 3 == 0 ? static_cast<Address>(0x100 + t) : kNoAddress;
      tracks.push_back(track(t + 1, TrackStatus::kConfirmed, address, x));
    }
    const std::vector<char> searched = held_twice(tracks, gate);
    for (std::size_t u = 0; u < tracks.size(); ++u) {
      bool twice = false;
      if (tracks[u].address == kNoAddress) {
        for (const TestTrack& a : tracks) {
          if (a.address != kNoAddress && merge_distance(tracks[u].filter, a.filter) <= gate) {
            twice = true;
          }
        }
      }
      EXPECT_EQ(searched[u] != 0, twice) << "trial " << trial << ", track " << u;
      found += twice ? 1U : 0U;
    }
  }
  EXPECT_GT(found, 40U) << "the trials test the search only if they hold tracks held twice";
}

}  // namespace
}  // namespace skyfuse
