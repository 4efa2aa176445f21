#pragma once
/// \file
/// Counter-based random numbers: every draw is a pure function of a key (seed, Monte-Carlo run,
/// station, step, stream) and its index within that key. No process shares a stream with
/// another, so the order in which stations run, in one process or many, changes nothing.

#include <cstdint>

namespace skyfuse {

/// Independent uses of randomness; each gets its own stream so adding draws to one never
/// shifts another.
enum class NoiseStream : std::uint64_t {
  kMeasurement = 1,   ///< sensor noise nu_{k,i}
  kNoiseScale = 2,    ///< per-station variance scale 1 + delta_i
  kInitialState = 3,  ///< error of the filter's initial estimate
  kProcess = 4,       ///< process noise of a simulated truth (tests)
  kLinkLoss = 5,      ///< simulated loss of a sample on one link (`skyfuse run --loss`)
  kLinkDelay = 6,     ///< simulated delay of a sample on one link (`--link-delay-ms`)
  kDetection = 7,     ///< whether a station detects each target in a scan
  kClutter = 8,       ///< a scan's false alarms: how many, and where
  kScanOrder = 9,     ///< the order a scan lists its detections in
  kTraffic = 10,      ///< the traffic generator's aircraft (station 0, step = aircraft index)
  kEquipage = 11,     ///< whether an aircraft is cooperative (station 0, step = target index)
};

struct NoiseKey {
  std::uint64_t seed = 0;
  std::uint64_t run = 0;
  std::uint64_t station = 0;
  std::uint64_t step = 0;
  NoiseStream stream = NoiseStream::kMeasurement;
  /// Which target of a scenario with many (its index); 0, the first or only one, leaves the
  /// key as it was before there were many, so a one-target run draws the same numbers.
  std::uint64_t target = 0;
};

class CounterRng {
 public:
  explicit CounterRng(const NoiseKey& key);

  std::uint64_t next_u64();
  /// Uniform on the open interval (0, 1): never exactly 0, so log() is always finite.
  double uniform();
  /// Standard normal by the Box-Muller transform.
  double normal();

 private:
  std::uint64_t state_;
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace skyfuse
