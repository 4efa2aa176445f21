// Two ways to put a station's round of the picture on the wire, measured side by
// side before either goes on DDS (docs/picture.md#on-the-wire quotes the numbers with the
// command that re-measures them: `skyfuse_picture_wire_bench`):
//
//  - increments: per track the station updated, (track id, detection index, dQ as its upper
//    triangle, dy), and its unassociated detections (index, value): what a station sends in a
//    one-target run, per track;
//  - detections: wire::PictureScan (idl/skyfuse_picture.idl), the station's scan (every
//    detection's value), its associations (track id, detection index) and its unassociated
//    detections' indices, with the run, step, sensor kind and digest. Every peer then computes each
//    station's increments itself: the increment is a function of the common predicted track,
//    the station's sensor and noise (which every peer knows) and the detection, so the same
//    code on the same inputs gives the same bits.
//
// The increments, which have no wire type, are encoded by hand as Fast CDR encodes a sample (the
// serializer of the generated wire types), so both byte counts are those a DDS sample would
// carry. The same two ways for the tree's cluster sample (BM_ClusterSample, below). Timed: one
// peer's round of receiving every station's sample (its own included): decoding them (for the
// detections, computing every increment) and fusing. Numbers printed, never asserted.

#include <benchmark/benchmark.h>
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <algorithm>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "picture_setup.hpp"
#include "skyfuse/transport/picture_wire.hpp"

namespace skyfuse {
namespace {

using namespace bench;  // NOLINT: the benchmarks' traffic

constexpr int kDim = Model::kDim;
constexpr int kMeasDim = TrackSensor::kMeasDim;
constexpr int kUpperTriangle = kDim * (kDim + 1) / 2;
using Report = Peer::Report;
using Cdr = eprosima::fastcdr::Cdr;

// One round at N aircraft and M stations: the picture predicted to it, every station's scan and
// the report it makes of it.
struct Round {
  Peer picture;
  std::vector<Station> stations;
  std::vector<Scan> scans;
  std::vector<Report> reports;
  transport::StationSensorKinds kinds;  // what a receiver checks each sample against
};

Round make_round(int aircraft, int station_count) {
  const auto truths = traffic(aircraft, kWarmUpSteps + 1);
  const auto stations = radars(aircraft, station_count);
  const DetectionConfig detection = detection_for(aircraft);
  Round round{warmed_picture(stations, detection, truths),
              stations,
              scans_of(stations, detection, truths, kWarmUpSteps),
              {},
              transport::StationSensorKinds(std::span<const Station>(stations))};
  round.picture.predict();
  AssociationWork work;
  for (std::size_t s = 0; s < stations.size(); ++s) {
    round.reports.push_back(round.picture.report(stations[s], round.scans[s], work));
  }
  return round;
}

// Each encoding into its own buffer, then read back by a peer into the reports it fuses.
class IncrementEncoding {
 public:
  static void encode(Cdr& cdr, const Station& /*station*/, const Report& report,
                     const Scan& /*scan*/) {
    cdr << report.station_id << static_cast<std::uint32_t>(report.updates.size());
    double upper[kUpperTriangle];
    // GNN's report: one pair per update, in the same order.
    for (std::size_t u = 0; u < report.updates.size(); ++u) {
      const auto& update = report.updates[u];
      const auto& q = update.contribution.delta_information;
      int n = 0;
      for (int r = 0; r < kDim; ++r) {
        for (int c = r; c < kDim; ++c) upper[n++] = q(r, c);
      }
      cdr << update.track << report.pairs[u].detection;
      cdr.serializeSequence(upper, kUpperTriangle);
      cdr.serializeSequence(update.contribution.delta_vector.data(), kDim);
    }
    encode_unassociated_values(cdr, report);
  }

  static void decode(Cdr& cdr, const Round& /*round*/, Report& report) {
    std::uint32_t count = 0;
    cdr >> report.station_id >> count;
    report.updates.resize(count);
    std::vector<double> upper;
    std::vector<double> vector;
    report.pairs.resize(count);
    for (std::size_t u = 0; u < count; ++u) {
      auto& update = report.updates[u];
      cdr >> update.track >> report.pairs[u].detection;
      report.pairs[u].track = update.track;
      cdr >> upper >> vector;
      auto& q = update.contribution.delta_information;
      int n = 0;
      for (int r = 0; r < kDim; ++r) {
        for (int c = r; c < kDim; ++c) q(r, c) = q(c, r) = upper[static_cast<std::size_t>(n++)];
      }
      update.contribution.delta_vector = Eigen::Map<const Vector<kDim>>(vector.data());
      update.contribution.station_id = report.station_id;
    }
    decode_unassociated_values(cdr, report);
  }

 private:
  static void encode_unassociated_values(Cdr& cdr, const Report& report) {
    cdr << static_cast<std::uint32_t>(report.unassociated.size());
    for (const auto& d : report.unassociated) {
      cdr << d.detection;
      cdr.serializeSequence(d.z.data(), kMeasDim);
    }
  }
  static void decode_unassociated_values(Cdr& cdr, Report& report) {
    std::uint32_t count = 0;
    cdr >> count;
    report.unassociated.resize(count);
    std::vector<double> z;
    for (auto& d : report.unassociated) {
      cdr >> d.detection >> z;
      d.z = Eigen::Map<const Vector<kMeasDim>>(z.data());
    }
  }
};

class DetectionEncoding {
 public:
  // The wire type itself (transport/picture_wire.hpp). Its digest's 8 bytes travel; their
  // value does not matter here.
  static void encode(Cdr& cdr, const Station& station, const Report& report, const Scan& scan) {
    transport::to_wire<kDim>(station.sensor, scan, report, 1, kWarmUpSteps, 0).serialize(cdr);
  }

  // Checked as a receiver checks it, and the station's increments computed here against the
  // common predicted tracks (PeerPicture::report_of).
  static void decode(Cdr& cdr, const Round& round, Report& report) {
    wire::PictureScan sample;
    sample.deserialize(cdr);
    // Not a structured binding: the lambda below captures the scan (clang 14 cannot capture a
    // binding).
    const auto checked = transport::picture_scan_from_wire(sample, round.kinds, 4096);
    const auto& scan = checked.first;
    const auto& station = *std::find_if(round.stations.begin(), round.stations.end(),
                                        [&](const auto& s) { return s.id == scan->station_id; });
    report = *round.picture.report_of(station, transport::published(*scan), scan->associations,
                                      scan->unassociated, scan->dropped);
  }
};

// One peer's round under `Encoding`: the M samples decoded into reports, then fused.
template <typename Encoding>
void BM_PictureRound(benchmark::State& state) {
  const Round round =
      make_round(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::size_t stations = round.stations.size();
  // Every station's sample, encoded once.
  std::vector<std::vector<char>> samples(stations);
  double bytes = 0.0;
  for (std::size_t s = 0; s < stations; ++s) {
    std::vector<char> memory(1 << 24);
    eprosima::fastcdr::FastBuffer buffer(memory.data(), memory.size());
    Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    cdr.serialize_encapsulation();
    Encoding::encode(cdr, round.stations[s], round.reports[s], round.scans[s]);
    memory.resize(cdr.getSerializedDataLength());
    bytes += static_cast<double>(memory.size());
    samples[s] = std::move(memory);
  }
  std::vector<Report> received(stations);
  std::size_t tracks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Peer picture = round.picture;  // the predicted picture, fused afresh each time
    state.ResumeTiming();
    for (std::size_t s = 0; s < stations; ++s) {
      eprosima::fastcdr::FastBuffer buffer(samples[s].data(), samples[s].size());
      Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
      cdr.read_encapsulation();
      Encoding::decode(cdr, round, received[s]);
    }
    picture.fuse(kWarmUpSteps, received);
    benchmark::DoNotOptimize(picture.tracks().data());
    tracks = picture.tracks().size();
  }
  std::size_t updates = 0;
  for (const Report& report : round.reports) updates += report.updates.size();
  state.counters["bytes_per_sample"] = bytes / static_cast<double>(stations);
  state.counters["bytes_per_peer"] = bytes;  // what each peer receives a round
  state.counters["updates_per_station"] =
      static_cast<double>(updates) / static_cast<double>(stations);
  state.counters["tracks"] = static_cast<double>(tracks);
}

// The tree's sample from a cluster's aggregator, two ways, for the first `fanout` stations of a
// round: its members' increments summed per track id in ascending station id (id, dQ's upper
// triangle, dy) with their unassociated detections forwarded (station, index, value); or its
// members' scans relayed unchanged (wire::PictureBundle, what the tree sends). Timed: the
// aggregator's forming and encoding of the sample. bytes_per_cluster is what each receiver of
// the cluster's sample gets.
struct ClusterSumEncoding {
  static void encode(Cdr& cdr, const Round& round, std::size_t fanout) {
    std::map<TrackId, std::pair<Covariance<kDim>, Vector<kDim>>> sums;
    std::uint32_t unassociated = 0;
    for (std::size_t s = 0; s < fanout; ++s) {
      for (const auto& update : round.reports[s].updates) {
        auto [it, fresh] = sums.try_emplace(update.track, update.contribution.delta_information,
                                            update.contribution.delta_vector);
        if (!fresh) {
          it->second.first += update.contribution.delta_information;
          it->second.second += update.contribution.delta_vector;
        }
      }
      unassociated += static_cast<std::uint32_t>(round.reports[s].unassociated.size());
    }
    cdr << static_cast<std::uint32_t>(sums.size());
    double upper[kUpperTriangle];
    for (const auto& [track, sum] : sums) {
      int n = 0;
      for (int r = 0; r < kDim; ++r) {
        for (int c = r; c < kDim; ++c) upper[n++] = sum.first(r, c);
      }
      cdr << track;
      cdr.serializeSequence(upper, kUpperTriangle);
      cdr.serializeSequence(sum.second.data(), kDim);
    }
    cdr << unassociated;
    for (std::size_t s = 0; s < fanout; ++s) {
      for (const auto& d : round.reports[s].unassociated) {
        cdr << round.reports[s].station_id << d.detection;
        cdr.serializeSequence(d.z.data(), kMeasDim);
      }
    }
  }
};
struct ClusterBundleEncoding {
  static void encode(Cdr& cdr, const Round& round, std::size_t fanout) {
    wire::PictureBundle bundle;
    bundle.kind(wire::CLUSTER_SCANS);
    bundle.station_id(round.reports[0].station_id);
    for (std::size_t s = 0; s < fanout; ++s) {
      bundle.scans().push_back(transport::to_wire<kDim>(round.stations[s].sensor, round.scans[s],
                                                        round.reports[s], 1, kWarmUpSteps, 0));
    }
    bundle.serialize(cdr);
  }
};

template <typename Encoding>
void BM_ClusterSample(benchmark::State& state) {
  const Round round =
      make_round(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto fanout = static_cast<std::size_t>(state.range(2));
  std::vector<char> memory(1 << 24);
  std::size_t bytes = 0;
  for (auto _ : state) {
    eprosima::fastcdr::FastBuffer buffer(memory.data(), memory.size());
    Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    cdr.serialize_encapsulation();
    Encoding::encode(cdr, round, fanout);
    bytes = cdr.getSerializedDataLength();
    benchmark::DoNotOptimize(memory.data());
  }
  state.counters["bytes_per_cluster"] = static_cast<double>(bytes);
}

void ClusterSizes(benchmark::internal::Benchmark* b) {
  for (const int aircraft : {10, 100, 1000}) b->Args({aircraft, 16, 8});
  b->ArgNames({"N", "M", "k"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_ClusterSample<ClusterSumEncoding>)->Apply(ClusterSizes);
BENCHMARK(BM_ClusterSample<ClusterBundleEncoding>)->Apply(ClusterSizes);

void Sizes(benchmark::internal::Benchmark* b) {
  for (const int stations : {8, 16}) {
    for (const int aircraft : {10, 100, 1000}) b->Args({aircraft, stations});
  }
  b->ArgNames({"N", "M"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_PictureRound<IncrementEncoding>)->Apply(Sizes);
BENCHMARK(BM_PictureRound<DetectionEncoding>)->Apply(Sizes);

}  // namespace
}  // namespace skyfuse

BENCHMARK_MAIN();
