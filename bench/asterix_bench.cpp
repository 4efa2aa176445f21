// The ASTERIX codec at the scale of a large system's published capacity (docs/asterix.md):
// 4 000 system tracks out as CAT062 every 4 s. What one core spends encoding and decoding
// them, and numbering a picture; speed is reported here, never asserted.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/track_numbers.hpp"

namespace {

using namespace skyfuse::asterix;

// `count` tracks spread over a 200 km square, each with its accuracy and, one in two, an
// address.
std::vector<SystemTrack> tracks(int count) {
  std::vector<SystemTrack> out;
  for (int i = 0; i < count; ++i) {
    SystemTrack t;
    t.source = {0, 1};
    t.service_id = 1;
    t.track_number = static_cast<std::uint16_t>(1 + i);
    t.time_of_track_s = 43200.0 + 0.001 * i;
    t.x_m = -100000.0 + 50.0 * i;
    t.y_m = 100000.0 - 47.0 * i;
    t.latitude_deg = 48.0 + 1e-4 * i;
    t.longitude_deg = 11.0 + 1e-4 * i;
    t.vx_mps = 200.0 * std::cos(0.01 * i);
    t.vy_mps = 200.0 * std::sin(0.01 * i);
    t.geometric_altitude_m = 3000.0 + i % 1000;
    t.accuracy = TrackAccuracy{25.0, 30.0, 120.0, 2.0, 2.5, 15.0};
    if (i % 2 == 0) t.address = 0x400000u + static_cast<std::uint32_t>(i);
    out.push_back(t);
  }
  return out;
}

// 4 000 tracks, each record encoded, then framed in datagram-sized blocks, as `skyfuse run
// --asterix-record` sends them.
void Cat062Encode4000Tracks(benchmark::State& state) {
  const std::vector<SystemTrack> all = tracks(4000);
  std::vector<Bytes> records;
  std::size_t bytes = 0;
  for (auto _ : state) {
    records.clear();
    for (const SystemTrack& t : all) records.push_back(encode_cat062_record(t).bytes);
    std::optional<EncodeError> error;
    const std::vector<Bytes> blocks = encode_blocks(kCat062, records, 65'507, error);
    bytes = 0;
    for (const Bytes& block : blocks) bytes += block.size();
    benchmark::DoNotOptimize(blocks.data());
  }
  state.counters["tracks_per_s"] =
      benchmark::Counter(4000.0, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(Cat062Encode4000Tracks)->Unit(benchmark::kMicrosecond);

// The same tracks read back: what a display or a peer reading the stream spends.
void Cat062Decode4000Tracks(benchmark::State& state) {
  const std::vector<SystemTrack> all = tracks(4000);
  std::vector<Bytes> records;
  for (const SystemTrack& t : all) records.push_back(encode_cat062_record(t).bytes);
  std::optional<EncodeError> error;
  const std::vector<Bytes> blocks = encode_blocks(kCat062, records, 65'507, error);
  for (auto _ : state) {
    Decoded decoded;
    for (const Bytes& block : blocks) decode_datagram(block, decoded);
    benchmark::DoNotOptimize(decoded.tracks.data());
  }
  state.counters["tracks_per_s"] =
      benchmark::Counter(4000.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(Cat062Decode4000Tracks)->Unit(benchmark::kMicrosecond);

// A node numbering its picture each round (transport/picture_numbers.hpp), now done by every
// station and the center whether or not they send CAT062: 1 000 tracks, ascending id, one in a
// hundred replaced by a new track each round, so numbers are given back and taken again.
void TrackNumbers1000TracksARound(benchmark::State& state) {
  TrackNumbers numbers;
  std::vector<std::vector<std::uint64_t>> rounds(100);
  for (std::uint64_t k = 0; k < rounds.size(); ++k) {
    for (std::uint64_t i = 0; i < 1000; ++i) {
      // Track i is replaced in rounds k = i mod 100 by one with a later id.
      rounds[k].push_back(1'000'000 * (i + 1) + (i % 100 == k ? k + 1 : 0));
    }
  }
  std::uint64_t k = 0;
  for (auto _ : state) {
    numbers.update(rounds[k % rounds.size()], k);
    ++k;
  }
}
BENCHMARK(TrackNumbers1000TracksARound)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
