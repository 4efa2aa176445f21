#pragma once
// The center process of a run with many aircraft (picture_center.hpp). It hears each station's
// scan (`Sample` wire::PictureScan: the flat exchange) or each cluster's scans as its aggregator
// relays them (wire::PictureBundle: the tree, transport/picture_tree_exchange.hpp). Its picture,
// the one part that knows the run's filter part and motion model, is behind an interface
// (center_picture.hpp), so that this is compiled once (picture_center.cpp).

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "center_picture.hpp"
#include "center_process.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/node_loop.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/picture_bundles.hpp"
#include "skyfuse/transport/picture_callsigns.hpp"
#include "skyfuse/transport/picture_cat062.hpp"
#include "skyfuse/transport/picture_scans.hpp"
#include "skyfuse/transport/picture_track_writer.hpp"
#include "skyfuse/transport/picture_tree_exchange.hpp"

namespace skyfuse::center {

using transport::RunEnd;

template <typename Sample>
class PictureCenter {
  static constexpr bool kTree = std::is_same_v<Sample, wire::PictureBundle>;

 public:
  // The endpoints are made in a fixed order: the loop's tick and input readers first.
  PictureCenter(const options::NodeOptions& options, PicturePlan plan)
      : options_(options),
        plan_(std::move(plan)),
        ids_(plan_.participant_ids()),
        picture_(make_center_picture(plan_)),
        node_(transport::node_config(options, "skyfuse-center")),
        loop_(node_, options, kCenterSourceId, "a fusion center", "picture scan",
              plan_.scenario.time_step_s,
              kTree ? std::vector<std::string>{transport::kPictureClustersPartition}
                    : std::vector<std::string>{}),
        scans_in_(ids_, picture_->sensor_kinds(), options.run_id,
                  plan_.scenario.tracker.association.max_detections_per_scan),
        writers_(kTree ? static_cast<int>(transport::picture_tree_layout(plan_).clusters())
                       : plan_.stations),
        rounds_(node_.make_writer<wire::PictureRound>()),
        tracks_(node_),
        asterix_out_(transport::make_asterix_out(options.asterix_out, plan_.scenario)) {}

  int run() {
    auto& inputs = loop_.inputs();
    auto& ticks = loop_.ticks();
    if (const RunEnd end = loop_.join(
            [&] {
              return inputs.matched() >= writers_ && ticks.matched() >= 1 && rounds_.matched() >= 1;
            },
            [&] {
              return fmt::format("{} writers {}/{}, tick writer {}/1, picture readers {}/1",
                                 kTree ? "cluster" : "picture scan", inputs.matched(), writers_,
                                 ticks.matched(), rounds_.matched());
            })) {
      return *end;
    }
    spdlog::info("joined run {} with {} stations", options_.run_id, plan_.stations);
    return loop_.run(*this, 0, static_cast<std::uint64_t>(plan_.scenario.steps), rounds_);
  }

  // What the round loop asks of the center (transport::NodeProcess).

  RunEnd open_round(std::uint64_t /*k*/) { return std::nullopt; }  // it scans nothing

  std::optional<DropKind> receive(const Sample& sample, const transport::WriterId& writer) {
    if constexpr (kTree) {
      return screen_->receive(sample, writer, scans_in_);
    } else {
      return scans_in_.receive(sample, writer);
    }
  }

  bool round_complete() { return scans_in_.complete(); }

  // Every scan that arrived, assigned jointly to the predicted picture; the picture published.
  RunEnd close_round(std::uint64_t k) {
    if (!scans_in_.complete()) {
      spdlog::warn("step {}: updating without station(s) {}", k,
                   fmt::join(scans_in_.missing(), ", "));
    }
    // A station whose scan did not arrive scanned nothing, as far as the center knows.
    scans_.resize(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      transport::assign_scan(scans_[i], ids_[i], picture_->noise(i), scans_in_.scan_of(ids_[i]));
    }
    wire::PictureRound round =
        picture_->update(k, scans_, numbers_, options_.run_id,
                         static_cast<std::uint32_t>(ids_.size() - scans_in_.missing().size()));
    // The callsigns of the round's scans, by ascending station id as the peers learn them.
    transport::learn_round(callsigns_, scans_in_);
    transport::identify_round(callsigns_, round);
    rounds_.write(round);
    if (asterix_out_) {
      asterix_out_->send(k, round);
      // The loop ends the process after its last round without returning: say it now.
      if (k + 1 == static_cast<std::uint64_t>(plan_.scenario.steps)) {
        spdlog::info("{}", transport::asterix_out_summary(*asterix_out_));
      }
    }
    picture_->publish(tracks_, numbers_, options_.run_id, static_cast<std::uint32_t>(k));
    scans_in_.advance();
    return std::nullopt;
  }

  RunEnd settle(std::uint64_t /*steps*/) { return std::nullopt; }
  transport::ProcessCounts counts() const { return {}; }

 private:
  const options::NodeOptions& options_;
  PicturePlan plan_;
  std::vector<int> ids_;  // the participants in scenario order, as the stations' known list
  std::unique_ptr<CenterPicture> picture_;
  transport::DdsNode node_;
  transport::NodeLoop<Sample> loop_;
  transport::PictureScans scans_in_;
  int writers_;  // of its input: every station's, or every cluster's aggregator's
  std::optional<transport::ClusterBundleScreen> screen_ =
      kTree ? std::optional(transport::ClusterBundleScreen(transport::picture_tree_layout(plan_),
                                                           options_.run_id))
            : std::nullopt;
  transport::Writer<wire::PictureRound> rounds_;
  transport::PictureTrackWriter tracks_;
  // `--asterix-out`: the picture each round as CAT062 over UDP; null without it.
  std::unique_ptr<transport::PictureAsterixOut> asterix_out_;
  // The picture's short track numbers, given each round as every node gives them.
  asterix::TrackNumbers numbers_;
  // The callsigns of the aircraft's addresses, learnt as the peers learn them.
  transport::CallsignBook callsigns_;
  std::vector<Scan> scans_;
};

}  // namespace skyfuse::center
