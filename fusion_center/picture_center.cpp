#include "picture_center.hpp"

#include <memory>
#include <stdexcept>
#include <utility>

#include "center_picture.hpp"
#include "picture_center_node.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/sim/picture_plan.hpp"

namespace skyfuse::center {

std::unique_ptr<CenterPicture> make_center_picture(const PicturePlan& plan) {
  auto picture = with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return make_center_picture_in_shard<decltype(shard)::value>(plan);
  });
  if (!picture) throw std::logic_error("a picture center: no picture runs this filter and model");
  return picture;
}

int run_picture_center(const options::NodeOptions& options, PicturePlan plan) {
  if (plan.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
    return transport::make_lifelong<PictureCenter<wire::PictureBundle>>(options, std::move(plan))
        .run();
  }
  return transport::make_lifelong<PictureCenter<wire::PictureScan>>(options, std::move(plan)).run();
}

}  // namespace skyfuse::center
