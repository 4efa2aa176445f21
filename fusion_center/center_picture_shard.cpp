// One shard of the center's picture (center_picture.hpp): cmake/FilterShards.cmake compiles this
// file once per shard, with SKYFUSE_SHARD set.
#include <memory>
#include <type_traits>
#include <utility>

#include "center_picture.hpp"
#include "center_process.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/sim/picture_stations.hpp"
#include "skyfuse/transport/picture_numbers.hpp"

namespace skyfuse::center {
namespace {

template <typename Parts>
class TypedCenterPicture final : public CenterPicture {
 public:
  using Picture = CentralPicture<typename Parts::Center>;
  static constexpr int N = Picture::kDim;

  explicit TypedCenterPicture(const PicturePlan& plan)
      : known_(known_stations<N>(plan.scenario, plan.stations, plan.mc_run)),
        picture_(Parts::center(plan.scenario), known_, plan.scenario.tracker) {}

  transport::StationSensorKinds sensor_kinds() const override {
    return transport::StationSensorKinds(std::span<const KnownStation<N>>(known_));
  }

  const DetectionNoise& noise(std::size_t i) const override { return picture_.stations()[i].noise; }

  wire::PictureRound update(std::uint64_t k, const std::vector<Scan>& scans,
                            asterix::TrackNumbers& numbers, std::uint64_t run_id,
                            std::uint32_t scans_fused) override {
    picture_.predict();
    picture_.update(k, scans);
    transport::number_picture(numbers, picture_, k, numbered_ids_);
    wire::PictureRound round = transport::picture_round_to_wire(
        picture_, run_id, static_cast<std::uint32_t>(k), kCenterSourceId, scans_fused);
    transport::number_round(numbers, round);
    return round;
  }

  void publish(transport::PictureTrackWriter& tracks, const asterix::TrackNumbers& numbers,
               std::uint64_t run_id, std::uint32_t step) const override {
    tracks.publish(picture_, numbers, run_id, step, kCenterSourceId, wire::CENTRAL);
  }

 private:
  std::vector<KnownStation<N>> known_;
  Picture picture_;
  std::vector<std::uint64_t> numbered_ids_;  // number_picture's, kept between rounds
};

}  // namespace

template <std::size_t Shard>
std::unique_ptr<CenterPicture> make_center_picture_in_shard(const PicturePlan& plan) {
  std::unique_ptr<CenterPicture> picture;
  visit_picture_parts_in_shard<Shard>(plan.scenario,
                                      [&]<typename Parts>(std::type_identity<Parts>) {
                                        picture = std::make_unique<TypedCenterPicture<Parts>>(plan);
                                      });
  return picture;
}

template std::unique_ptr<CenterPicture> make_center_picture_in_shard<SKYFUSE_SHARD>(
    const PicturePlan& plan);

}  // namespace skyfuse::center
