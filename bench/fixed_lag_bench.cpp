// Fixed-lag re-fusion (tracking/fixed_lag_peer.hpp): one round of a peer with four stations and
// a lag L. fixed_lag_round: nothing late, so only the current round is fused.
// fixed_lag_round_refused: station 4's contribution to every round comes L rounds late, so every
// round also fuses the L rounds before it again (the most a round can cost). The counter
// bytes_held is what the lag keeps: each round's collector row (a contribution per station) and
// the chain's prior, posterior and contributor list per round in the lag.

#include <benchmark/benchmark.h>

#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/tracking/fixed_lag_peer.hpp"

namespace skyfuse {
namespace {

void run_rounds(benchmark::State& bench, bool late) {
  using Model = ConstantAcceleration3D;
  const auto lag = static_cast<std::size_t>(bench.range(0));
  const std::vector<int> ids = {1, 2, 3, 4};
  const std::vector<double> weights(ids.size(), 1.0);
  GaussianState<9> start;
  start.mean << 100.0, 200.0, 50.0, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  start.covariance = Covariance<9>::Identity() * 25.0;
  FixedLagPeer<Model> peer(Model(0.02, {0.5, 0.1, 0.05}), start, ids, weights, lag);
  const auto fuse_round = [&peer](std::uint64_t, auto slot_at) {
    return peer.round().fuse(peer.tracker(), slot_at);
  };
  std::vector<PeerContribution<9>> held(lag + 1);  // station 4's, by round, L rounds late
  std::uint64_t k = 0;
  for (auto _ : bench) {
    if (late && k >= lag) {
      peer.collector().offer(k - lag, 4, held[(k - lag) % held.size()]);
      peer.kept(k - lag);
    }
    benchmark::DoNotOptimize(peer.refresh_prior(fuse_round));
    const GaussianState<9> prior = peer.tracker().estimate();
    for (int id : ids) {
      PeerContribution<9> c;
      c.increment.station_id = id;
      const int axis = (id - 1) % 3;
      c.increment.delta_information(axis, axis) = 4.0;
      c.increment.delta_vector(axis) = 4.0 * (100.0 + static_cast<double>(id));
      c.prior = prior;
      if (late && id == 4) {
        held[k % held.size()] = c;
        continue;
      }
      peer.collector().offer(k, id, c);
    }
    benchmark::DoNotOptimize(peer.fuse_current(fuse_round));
    peer.predict();
    peer.advance();
    ++k;
  }
  const double rows = static_cast<double>(lag + 2) * static_cast<double>(ids.size());
  const double per_round =
      2.0 * sizeof(GaussianState<9>) + static_cast<double>(ids.size() * sizeof(int));
  bench.counters["bytes_held"] =
      rows * sizeof(PeerContribution<9>) + static_cast<double>(lag + 1) * per_round;
}

void fixed_lag_round(benchmark::State& bench) {
  run_rounds(bench, false);
}
void fixed_lag_round_refused(benchmark::State& bench) {
  run_rounds(bench, true);
}
BENCHMARK(fixed_lag_round)->Arg(0)->Arg(1)->Arg(3)->Arg(10);
BENCHMARK(fixed_lag_round_refused)->Arg(1)->Arg(3)->Arg(10);

}  // namespace
}  // namespace skyfuse
