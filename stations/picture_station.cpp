#include "picture_station.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <deque>
#include <memory>
#include <stdexcept>
#include <vector>

#include "picture_station_node.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"

namespace skyfuse::station {

namespace {

// Refuses a station of `ids` that does not take part in `plan`, and options that do not suit a
// run of many aircraft.
void check_plan(const StationOptions& options, const PicturePlan& plan,
                const std::vector<int>& ids) {
  const std::vector<int> participants = plan.participant_ids();
  for (const int id : ids) {
    if (std::find(participants.begin(), participants.end(), id) == participants.end()) {
      throw std::invalid_argument(fmt::format(
          "--id: station {} is not one of the {} participating stations of scenario '{}' (ids {})",
          id, plan.stations, plan.scenario.name, fmt::join(participants, ", ")));
    }
  }
  if (!options.replay_path.empty()) {
    throw std::invalid_argument("--replay: not for a run of many aircraft yet");
  }
  if (options.rejoin_step &&
      *options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
    throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                            *options.rejoin_step, plan.scenario.steps - 1));
  }
}

// The aircraft, kept for the life of the process: every station of it reads them.
const std::vector<TargetTruth>& lifelong_truth(const PicturePlan& plan,
                                               const StationOptions& options) {
  return transport::make_lifelong<std::vector<TargetTruth>>(
      build_traffic_truth(plan.scenario, options.node.traffic_file).targets);
}

int run_on(const StationOptions& options, const PicturePlan& plan,
           const std::vector<TargetTruth>& truth, transport::DdsNode& node) {
  if (plan.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
    return transport::make_lifelong<PictureStation<transport::PictureTreeExchange>>(options, plan,
                                                                                    truth, node)
        .run();
  }
  return transport::make_lifelong<PictureStation<transport::PictureExchange>>(options, plan, truth,
                                                                              node)
      .run();
}

}  // namespace

std::unique_ptr<StationPicture> make_station_picture(const PicturePlan& plan) {
  auto picture = with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return make_station_picture_in_shard<decltype(shard)::value>(plan);
  });
  if (!picture) throw std::logic_error("a picture station: no picture runs this filter and model");
  return picture;
}

int run_picture_station(const StationOptions& options, const PicturePlan& plan) {
  check_plan(options, plan, {options.id});
  const std::vector<TargetTruth>& truth = lifelong_truth(plan, options);
  auto& node = transport::make_lifelong<transport::DdsNode>(
      transport::node_config(options.node, fmt::format("skyfuse-station-{}", options.id)));
  return run_on(options, plan, truth, node);
}

int run_picture_stations(const StationOptions& options, const std::vector<int>& ids,
                         const PicturePlan& plan) {
  check_plan(options, plan, ids);
  const std::vector<TargetTruth>& truth = lifelong_truth(plan, options);
  // Each station keeps a reference to its options.
  std::deque<StationOptions> each;
  for (const int id : ids) {
    each.push_back(options);
    each.back().id = id;
  }
  auto& node = transport::make_lifelong<transport::DdsNode>(transport::node_config(
      options.node, fmt::format("skyfuse-stations-{}", fmt::join(ids, "-"))));
  return run_on_threads(ids.size(),
                        [&](std::size_t i) { return run_on(each[i], plan, truth, node); });
}

}  // namespace skyfuse::station
