// One shard of the station's picture (station_picture.hpp): cmake/FilterShards.cmake compiles
// this file once per shard, with SKYFUSE_SHARD set.
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/sim/picture_stations.hpp"
#include "skyfuse/transport/picture_numbers.hpp"
#include "skyfuse/transport/picture_round_reports.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "station_picture.hpp"

namespace skyfuse::station {
namespace {

template <typename Parts>
class TypedStationPicture final : public StationPicture {
 public:
  using Tracks = typename Parts::Peer;
  using Picture = PeerPicture<Tracks>;
  static constexpr int N = Tracks::kDim;

  explicit TypedStationPicture(const PicturePlan& plan)
      : known_(known_stations<N>(plan.scenario, plan.stations, plan.mc_run)),
        picture_(Parts::peer(plan.scenario), known_, plan.scenario.tracker),
        reports_(std::span<const KnownStation<N>>(known_)) {}

  transport::RoundStations round_stations() const override { return reports_.round_stations(); }
  const DetectionNoise& noise(std::size_t i) const override { return known_[i].noise; }
  std::uint64_t digest() const override { return picture_.digest(); }

  void predict() override { picture_.predict(); }

  wire::PictureScan sample(std::size_t i, const Scan& scan, std::uint64_t run_id,
                           std::uint32_t step, std::uint64_t digest) override {
    const auto report = picture_.report(known_[i], scan, work_);
    return transport::to_wire<N>(known_[i].sensor, scan, report, run_id, step, digest);
  }

  std::size_t fuse(std::uint64_t k, const transport::PictureRoundScans& scans,
                   std::uint64_t predicted, bool nothing,
                   const std::function<void(int, DropKind)>& on_refused) override {
    const auto reports = nothing ? std::vector<typename Picture::Report>{}
                                 : reports_.reports(scans, picture_, predicted, on_refused);
    picture_.fuse(k, reports);
    return reports.size();
  }

  void number(asterix::TrackNumbers& numbers, std::uint64_t k) override {
    transport::number_picture(numbers, picture_, k, numbered_ids_);
  }

  wire::PictureState state(std::uint64_t run_id, std::uint32_t step,
                           int station_id) const override {
    return transport::picture_state_to_wire(picture_, run_id, step, station_id);
  }

  wire::PictureRound round(std::uint64_t run_id, std::uint32_t step, int station_id,
                           std::uint32_t scans_fused) const override {
    return transport::picture_round_to_wire(picture_, run_id, step, station_id, scans_fused);
  }

  void publish(transport::PictureTrackWriter& tracks, const asterix::TrackNumbers& numbers,
               std::uint64_t run_id, std::uint32_t step, int station_id) const override {
    tracks.publish(picture_, numbers, run_id, step, station_id, wire::PEER);
  }

  bool keep_peer_picture(const wire::PictureState& sample) override {
    auto tracks = transport::picture_state_from_wire(sample, picture_.filters());
    auto biases = transport::picture_biases_from_wire(sample);
    if (!tracks || !biases) return false;
    kept_ = Kept{std::move(*tracks), std::move(*biases)};
    return true;
  }

  Taken take_peer_picture(bool predict, std::uint64_t digest) override {
    Picture candidate = picture_;
    candidate.restore(kept_->tracks);
    // A picture without the registration would correct the next scans otherwise than its
    // sender.
    if (picture_.registers() && !candidate.restore_biases(kept_->biases)) {
      return Taken::kNoRegistration;
    }
    if (predict) candidate.predict();
    if (candidate.digest() != digest) return Taken::kOtherDigest;
    picture_ = std::move(candidate);
    return Taken::kTaken;
  }

 private:
  // The latest whole picture a peer sent.
  struct Kept {
    std::vector<typename Picture::TrackType> tracks;
    std::vector<BiasSums> biases;  // every station's registration, where the tracker registers
  };

  std::vector<KnownStation<N>> known_;
  Picture picture_;
  transport::PictureRoundReports<Tracks> reports_;
  AssociationWork work_;
  std::vector<std::uint64_t> numbered_ids_;  // number_picture's, kept between rounds
  std::optional<Kept> kept_;
};

}  // namespace

template <std::size_t Shard>
std::unique_ptr<StationPicture> make_station_picture_in_shard(const PicturePlan& plan) {
  std::unique_ptr<StationPicture> picture;
  visit_picture_parts_in_shard<Shard>(
      plan.scenario, [&]<typename Parts>(std::type_identity<Parts>) {
        picture = std::make_unique<TypedStationPicture<Parts>>(plan);
      });
  return picture;
}

template std::unique_ptr<StationPicture> make_station_picture_in_shard<SKYFUSE_SHARD>(
    const PicturePlan& plan);

}  // namespace skyfuse::station
