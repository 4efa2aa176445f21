#pragma once
/// \file
/// A station's side of the picture's flat exchange over DDS. Each round it
/// publishes its scan with its associations against the common predicted picture
/// (wire::PictureScan, transport/picture_wire.hpp), sent once to a multicast group, and collects
/// every station's sample of the round that its reader of the topic hears, its own included
/// (picture_round_scans.hpp says what a peer makes of them).
///
/// Threading: the node's thread, as every endpoint (dds_node.hpp).

#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/picture_round_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

class PictureExchange : public PictureRoundScans {
 public:
  using Sample = wire::PictureScan;

  /// Where the station's reader of samples listens: the topic's default partition.
  static std::vector<std::string> input_partitions(const PicturePlan& /*plan*/, int /*id*/) {
    return {};
  }

  /// The exchange of `node` among `stations` (every participant of the run), for run `run_id`;
  /// a sample of more than `max_detections` is refused.
  PictureExchange(DdsNode& node, const RoundStations& stations, std::uint64_t run_id,
                  std::size_t max_detections)
      : PictureRoundScans(stations, run_id, max_detections),
        out_(node.make_writer<wire::PictureScan>()) {}
  /// The exchange of a station of `plan` (any id: every station does the same).
  static PictureExchange of_station(DdsNode& node, const RoundStations& stations,
                                    const PicturePlan& plan, int /*id*/,
                                    const options::NodeOptions& options,
                                    Reader<wire::PictureScan>& /*inputs*/) {
    return PictureExchange(node, stations, options.run_id,
                           plan.scenario.tracker.association.max_detections_per_scan);
  }

  /// Every station's writer and reader matched, this one's own included (`in`: the node's
  /// reader of the topic).
  bool matched(const Reader<wire::PictureScan>& in) const {
    return in.matched() >= stations() && out_.matched() >= stations();
  }
  std::string describe_matched(const Reader<wire::PictureScan>& in) const {
    return fmt::format("picture scan writers {}/{}, readers {}/{}", in.matched(), stations(),
                       out_.matched(), stations());
  }
  /// This station's writer, whose samples its own reader hears too: the loop skips them, since
  /// publish() keeps them as they go out (a simulated link must not lose them).
  WriterId own_writer() const { return out_.id(); }

  /// Publishes this station's sample of a round: its scan and its report against the predicted
  /// picture (picture_wire.hpp's to_wire).
  void publish(const wire::PictureScan& sample) {
    out_.write(sample);
    this->scans().receive(sample, out_.id());
  }

  /// Keeps a sample of the current step or the next, or says why not (picture_scans.hpp).
  std::optional<DropKind> receive(const wire::PictureScan& sample, const WriterId& writer) {
    return this->scans().receive(sample, writer);
  }

  /// Every station's sample of the current step is in.
  bool round_complete() { return this->complete(); }
  /// Nothing to do but wait for the samples.
  std::optional<std::chrono::system_clock::time_point> wake_at() const { return std::nullopt; }

 private:
  int stations() const { return static_cast<int>(station_count()); }

  Writer<wire::PictureScan> out_;
};

}  // namespace skyfuse::transport
