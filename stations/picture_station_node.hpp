#pragma once
// The station process of a run with many aircraft (picture_station.hpp) on one exchange (flat:
// transport/picture_exchange.hpp; tree: transport/picture_tree_exchange.hpp), compiled once:
// its picture, which knows the configuration's track type, is a StationPicture
// (station_picture.hpp), compiled by shard of the configuration groups.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "skyfuse/picture/picture_digest.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_stations.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"
#include "skyfuse/transport/fed_scans.hpp"
#include "skyfuse/transport/node_loop.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/picture_callsigns.hpp"
#include "skyfuse/transport/picture_cat062.hpp"
#include "skyfuse/transport/picture_exchange.hpp"
#include "skyfuse/transport/picture_numbers.hpp"
#include "skyfuse/transport/picture_track_writer.hpp"
#include "skyfuse/transport/picture_tree_exchange.hpp"
#include "skyfuse/transport/scan_asterix.hpp"
#include "station_picture.hpp"
#include "station_process.hpp"

namespace skyfuse::station {

using transport::RunEnd;

template <typename Exchange>
class PictureStation {
 public:
  using Sample = typename Exchange::Sample;

  // The endpoints are made in a fixed order: the loop's tick and input readers first. `node` is
  // this station's participant, or the one it shares with the other stations of its process;
  // `truth` is shared with them too. Both outlive the station.
  PictureStation(const StationOptions& options, PicturePlan plan,
                 const std::vector<TargetTruth>& truth, transport::DdsNode& node)
      : options_(options),
        plan_(std::move(plan)),
        truth_(truth),
        picture_(make_station_picture(plan_)),
        me_(index_of(plan_, options.id)),
        detection_(plan_.participants()[me_].detection.value()),
        truth_sensor_(make_picture_sensor<kKinematicsDim>(plan_.participants()[me_])),
        node_(node),
        loop_(node_, options.node, options.id, fmt::format("station {}", options.id),
              "picture scan", plan_.scenario.time_step_s,
              Exchange::input_partitions(plan_, options.id)),
        exchange_(Exchange::of_station(node_, picture_->round_stations(), plan_, options.id,
                                       options.node, loop_.inputs())),
        rounds_(node_.make_writer<wire::PictureRound>()),
        tracks_(node_),
        states_out_(node_.make_writer<wire::PictureState>()),
        states_in_(node_.make_reader<wire::PictureState>()),
        asterix_out_(transport::make_asterix_out(options.node.asterix_out, plan_.scenario)),
        fed_(fed_scans(options, plan_.participants()[me_], plan_.scenario)) {
    // What it sends to itself never crosses the simulated link: the exchange keeps it as it
    // goes out.
    loop_.skip_own(options.id, exchange_.own_writer());
  }

  int run() {
    auto& inputs = loop_.inputs();
    auto& ticks = loop_.ticks();
    if (const RunEnd end = loop_.join(
            [&] {
              const int m = plan_.stations;
              return exchange_.matched(inputs) && ticks.matched() >= 1 && rounds_.matched() >= 1 &&
                     states_out_.matched() >= m && states_in_.matched() >= m;
            },
            [&] {
              return fmt::format(
                  "{}, tick writer {}/1, picture readers {}/1 (harness), picture state readers "
                  "{}/{}, writers {}/{}",
                  exchange_.describe_matched(inputs), ticks.matched(), rounds_.matched(),
                  states_out_.matched(), plan_.stations, states_in_.matched(), plan_.stations);
            })) {
      return *end;
    }
    spdlog::info("joined run {} with {} stations; waiting for ticks", options_.node.run_id,
                 plan_.stations);
    // A station that rejoins starts with an empty picture: its first scan is made against that,
    // the lowest station sends its picture on seeing it, and the next round this one takes it.
    const std::uint64_t first = options_.rejoin_step.value_or(0);
    exchange_.start_at(first);
    return loop_.run(*this, first, static_cast<std::uint64_t>(plan_.scenario.steps), rounds_);
  }

  // What the round loop asks of a station (transport::NodeProcess).

  // Predicts the picture, scans, assigns the scan to the predicted tracks and publishes it.
  RunEnd open_round(std::uint64_t k) {
    picture_->predict();
    predicted_digest_ = picture_->digest();
    const StationConfig& station = plan_.participants()[me_];
    const DetectionNoise& noise = picture_->noise(me_);
    const Scan scan =
        fed_ ? fed_->scan_at(k, noise)
             : simulate_scan(station.id, truth_sensor_, station.position_m, noise, detection_,
                             truth_, static_cast<int>(k), plan_.scenario.seed, plan_.mc_run);
    exchange_.publish(picture_->sample(me_, scan, options_.node.run_id,
                                       static_cast<std::uint32_t>(k), predicted_digest_));
    return std::nullopt;
  }

  std::optional<DropKind> receive(const Sample& sample, const transport::WriterId& writer) {
    return exchange_.receive(sample, writer);
  }

  bool round_complete() { return exchange_.round_complete(); }
  std::optional<std::chrono::system_clock::time_point> wake_at() const {
    return exchange_.wake_at();
  }

  // Fuses every station's report that arrived and was made against this picture, rebuilt
  // against it, and publishes the picture. The rule that brings parted peers together again:
  // every peer fuses onto the predicted picture of the round's lowest-id station. One whose
  // picture is another takes that station's whole picture of the round before (which the
  // station sends once it sees a scan made against another picture), predicts it as every peer
  // did, and fuses the round with the others.
  RunEnd close_round(std::uint64_t k) {
    if (!exchange_.complete()) {
      spdlog::info("step {}: fusing without station(s) {}", k,
                   fmt::join(exchange_.missing(), ", "));
    }
    take_states();
    const auto lowest = exchange_.lowest();
    const bool parted = lowest && lowest->second != predicted_digest_;
    if (parted) {
      // Parted last round too, the lowest station saw it then and sent its picture of that
      // round: wait for it (a datagram of it lost waits for its repair) rather than stay apart.
      if (parted_last_round_ && !realtime()) {
        // A restarted station waits longer for its first picture: the lowest station's writer
        // may match its new reader only after the station has joined (the picture waits for it,
        // kept for a late reader), and under load that took longer than a round's deadline.
        wait_for_state_of(
            lowest->first, k - 1,
            awaiting_first_picture_ ? kFirstPictureWait : options_.node.round_deadline());
        awaiting_first_picture_ = false;
      }
      // The lowest station's picture of this very round came instead (its writer matched this
      // reader only after sending the one before, and keeps the latest only): it is this
      // round's result, nothing left to fuse.
      if (take_finished_round_of(lowest->first, k)) {
        parted_last_round_ = false;
        publish_round(
            k, static_cast<std::uint32_t>(exchange_.station_count() - exchange_.missing().size()));
        exchange_.advance();
        return std::nullopt;
      }
      take_picture_of(*lowest, k);
    }
    parted_last_round_ = parted;
    const std::uint64_t predicted = predicted_digest_;
    // A restarted station, whose picture is still empty, fuses nothing until it has taken the
    // lowest station's: tracks it started alone would make its scans look like a picture to
    // come back to (PictureRoundScans::lowest), and as the lowest it would hand them to all.
    const bool waits_for_picture =
        parted && predicted == empty_digest_ && lowest->second != empty_digest_;
    const std::size_t fused =
        picture_->fuse(k, exchange_, predicted, waits_for_picture,
                       [&](int station_id, DropKind why) { loop_.count_drop(why, station_id, k); });
    // The callsigns the round's scans give, as every peer that fused them learns them.
    if (!waits_for_picture) transport::learn_round(callsigns_, exchange_);
    // Numbered before the picture goes to a peer: the numbers it carries are the round's.
    picture_->number(numbers_, k);
    if (lowest && lowest->first == options_.id && exchange_.any_other_picture(predicted)) {
      wire::PictureState state =
          picture_->state(options_.node.run_id, static_cast<std::uint32_t>(k), options_.id);
      transport::track_numbers_to_wire(numbers_, state);
      transport::callsigns_to_wire(callsigns_, state);
      states_out_.write(state);
    }
    publish_round(k, static_cast<std::uint32_t>(fused));
    exchange_.advance();
    return std::nullopt;
  }

  RunEnd settle(std::uint64_t /*steps*/) { return std::nullopt; }
  transport::ProcessCounts counts() const { return {resyncs_, 0}; }

 private:
  // The latest whole picture a peer sent, kept until a newer one comes (its tracks and
  // registration kept by picture_, StationPicture::keep_peer_picture).
  struct PeerState {
    std::uint64_t step = 0;
    int station_id = 0;
    std::uint64_t digest = 0;  // of the picture after the round, as its sender computed it
    asterix::TrackNumbers::State numbers;        // the tracks' short numbers after the round
    transport::CallsignBook::Entries callsigns;  // the callsigns it had learnt
  };

  void take_states() {
    wire::PictureState sample;
    while (states_in_.take(sample)) {
      if (sample.run_id() != options_.node.run_id || sample.station_id() == options_.id) continue;
      auto numbers = transport::track_numbers_from_wire(sample);
      auto callsigns = transport::callsigns_from_wire(sample);
      if (!numbers || !callsigns || !picture_->keep_peer_picture(sample)) {
        spdlog::warn("step {}: a picture from station {} that is wrong; refused", sample.step(),
                     sample.station_id());
        continue;
      }
      latest_ = PeerState{sample.step(), static_cast<int>(sample.station_id()),
                          sample.picture_digest(), std::move(*numbers), std::move(*callsigns)};
    }
  }

  // How long a restarted station waits for its first picture at most: well below the 10 s a
  // lock-step harness lets a node stay silent.
  static constexpr std::chrono::microseconds kFirstPictureWait = std::chrono::seconds(5);

  bool realtime() const { return options_.node.realtime_deadline_ms > 0.0; }

  static std::unique_ptr<transport::FedScans> fed_scans(const StationOptions& options,
                                                        const StationConfig& station,
                                                        const Scenario& scenario) {
    auto fed = transport::make_fed_scans(options.node, station, scenario);
    if (fed) spdlog::info("{}", fed->started());
    return fed;
  }

  // The picture after round k, to the harness and to readers of its tracks.
  void publish_round(std::uint64_t k, std::uint32_t scans_fused) {
    const auto step = static_cast<std::uint32_t>(k);
    wire::PictureRound round =
        picture_->round(options_.node.run_id, step, options_.id, scans_fused);
    transport::number_round(numbers_, round);
    transport::identify_round(callsigns_, round);
    rounds_.write(round);
    if (asterix_out_) {
      asterix_out_->send(k, round);
    }
    // The loop ends the process after its last round without returning: say it now.
    if (k + 1 == static_cast<std::uint64_t>(plan_.scenario.steps)) {
      if (asterix_out_) spdlog::info("{}", transport::asterix_out_summary(*asterix_out_));
      if (fed_) spdlog::info("{}", fed_->summary());
    }
    picture_->publish(tracks_, numbers_, options_.node.run_id, step, options_.id);
  }

  // Takes the latest picture a peer sent as this station's, predicted where `predict`, if its
  // digest is then `digest`; says so where its registration is not this run's.
  StationPicture::Taken take_latest(bool predict, std::uint64_t digest) {
    const auto taken = picture_->take_peer_picture(predict, digest);
    if (taken == StationPicture::Taken::kNoRegistration) {
      spdlog::warn("step {}: station {}'s picture holds no registration of this run's stations",
                   latest_->step, latest_->station_id);
    }
    return taken;
  }

  // Takes station `station`'s picture after round k as this station's, if it came and holds
  // what its digest says.
  bool take_finished_round_of(int station, std::uint64_t k) {
    if (!latest_ || latest_->station_id != station || latest_->step != k) return false;
    if (take_latest(false, latest_->digest) != StationPicture::Taken::kTaken) return false;
    numbers_.restore(latest_->numbers);  // numbered as the sender did after the round
    callsigns_.restore(latest_->callsigns);
    ++resyncs_;
    spdlog::info("step {}: took station {}'s picture of the round", k, station);
    return true;
  }

  // Lock-step: takes pictures that come until station `station`'s of round `step` is in, or
  // `limit` passes.
  void wait_for_state_of(int station, std::uint64_t step, std::chrono::microseconds limit) {
    const auto give_up = std::chrono::steady_clock::now() + limit;
    // Its picture of the round after `step` does as well (take_finished_round_of).
    const auto have = [&] {
      return latest_ && latest_->station_id == station &&
             (latest_->step == step || latest_->step == step + 1);
    };
    while (!have() && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::microseconds(500));
      take_states();
    }
  }

  // Takes the picture `lowest` (station, digest of its predicted picture) made its scan of
  // round k against: its picture of round k - 1, predicted. Nothing if that has not come (the
  // next round tries again) or does not predict to the digest.
  void take_picture_of(const std::pair<int, std::uint64_t>& lowest, std::uint64_t k) {
    if (!latest_ || latest_->station_id != lowest.first || latest_->step + 1 != k) return;
    const auto taken = take_latest(true, lowest.second);
    if (taken == StationPicture::Taken::kOtherDigest) {
      spdlog::warn("step {}: station {}'s picture does not predict to its scan's", k, lowest.first);
    }
    if (taken != StationPicture::Taken::kTaken) return;
    numbers_.restore(latest_->numbers);      // as after round k - 1: round k numbers on from them
    callsigns_.restore(latest_->callsigns);  // and learns this round's on top
    predicted_digest_ = lowest.second;
    ++resyncs_;
    spdlog::info("step {}: took station {}'s picture", k, lowest.first);
  }

  static std::size_t index_of(const PicturePlan& plan, int id) {
    const auto participants = plan.participants();
    for (std::size_t i = 0; i < participants.size(); ++i) {
      if (participants[i].id == id) return i;
    }
    throw std::logic_error("picture station: not a participant");
  }

  const StationOptions& options_;
  PicturePlan plan_;
  const std::vector<TargetTruth>& truth_;
  // The picture first: the exchange is made of its stations.
  std::unique_ptr<StationPicture> picture_;
  std::size_t me_;
  DetectionConfig detection_;
  PictureSensor<kKinematicsDim> truth_sensor_;  // this station's sensor, on the truth
  transport::DdsNode& node_;
  transport::NodeLoop<Sample> loop_;
  Exchange exchange_;
  transport::Writer<wire::PictureRound> rounds_;
  transport::PictureTrackWriter tracks_;
  transport::Writer<wire::PictureState> states_out_;
  transport::Reader<wire::PictureState> states_in_;
  // The picture's short track numbers, given each round as every peer gives them.
  asterix::TrackNumbers numbers_;
  // The callsigns of the aircraft's addresses, learnt as every peer learns them.
  transport::CallsignBook callsigns_;
  // `--asterix-out`: the picture each round as CAT062 over UDP; null without it.
  std::unique_ptr<transport::PictureAsterixOut> asterix_out_;
  // `--asterix-replay` or `--asterix-in`: this station's scans from a recorded or a live feed,
  // where its sensor is one ASTERIX carries; it simulates them otherwise (null).
  std::unique_ptr<transport::FedScans> fed_;
  // picture_'s digest as predicted for the round (or taken): it is published with the scan and
  // compared with the others', and computed once a round rather than at each use.
  std::uint64_t predicted_digest_ = 0;
  const std::uint64_t empty_digest_ = empty_picture_digest();
  std::optional<PeerState> latest_;
  bool parted_last_round_ = false;  // this picture was not the lowest station's last round
  // A restarted station that has not yet waited for the lowest station's picture.
  bool awaiting_first_picture_ = options_.rejoin_step.has_value();
  std::uint32_t resyncs_ = 0;  // rounds in which this station took another's picture
};

}  // namespace skyfuse::station
