#include "station_process.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <deque>
#include <set>
#include <stdexcept>
#include <thread>

#include "picture_station.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "station_rounds.hpp"
#include "station_sensing.hpp"

namespace skyfuse::station {

namespace {

// Station `id`'s place in the run, or why it has none.
const StationConfig& participant_of(const RunPlan& plan, int id) {
  const StationConfig* me = plan.participant(id);
  if (me == nullptr) {
    throw std::invalid_argument(fmt::format(
        "--id: station {} is not one of the {} participating stations of scenario '{}' (ids {})",
        id, plan.stations, plan.scenario.name, fmt::join(plan.participant_ids(), ", ")));
  }
  return *me;
}

// Runs station `me` of a run of one aircraft on `node`, or on a participant of its own made
// once its sensing is (a configuration the sensing refuses makes no participant).
int run_one_aircraft_station(const StationOptions& options, const RunPlan& plan,
                             const StationConfig& me, transport::DdsNode* node) {
  // The sensor's arithmetic is compiled by shard of the configuration groups, the rounds once per
  // fusion (station_sensing.hpp).
  auto sensing = with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return make_sensing_in_shard<decltype(shard)::value>(options, plan, me);
  });
  if (node == nullptr) {
    node = &transport::make_lifelong<transport::DdsNode>(
        transport::node_config(options.node, fmt::format("skyfuse-station-{}", me.id)));
  }
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_station_rounds_in_shard<decltype(shard)::value>(options, plan, me,
                                                               std::move(sensing), *node);
  });
}

}  // namespace

int run_station(const StationOptions& options) {
  if (Scenario scenario = load_scenario_or_default(options.node.scenario_path);
      scenario.has_many_targets()) {
    return run_picture_station(options, std::move(scenario));
  }
  const RunPlan plan = transport::load_plan(options.node);
  const StationConfig& me = participant_of(plan, options.id);
  if (options.rejoin_step) {
    if (*options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
      throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                              *options.rejoin_step, plan.scenario.steps - 1));
    }
    if (options.node.realtime_deadline_ms > 0.0) {
      throw std::invalid_argument("--rejoin-at-step: lock-step runs only, not real time");
    }
  }
  return run_one_aircraft_station(options, plan, me, nullptr);
}

int run_stations(const StationOptions& options, const std::vector<int>& ids) {
  if (ids.size() == 1) {
    StationOptions one = options;
    one.id = ids.front();
    return run_station(one);
  }
  if (const std::set<int> distinct(ids.begin(), ids.end()); distinct.size() != ids.size()) {
    throw std::invalid_argument(fmt::format("--id: an id given twice ({})", fmt::join(ids, ", ")));
  }
  if (options.rejoin_step) {
    throw std::invalid_argument(
        "--rejoin-at-step: one station per process (a restarted station replaces one process)");
  }
  if (options.node.secure_dir) {
    throw std::invalid_argument(
        "several --id with --secure: DDS-Security authenticates a participant, and each station "
        "needs its own identity; run one station per process");
  }
  if (Scenario scenario = load_scenario_or_default(options.node.scenario_path);
      scenario.has_many_targets()) {
    return run_picture_stations(options, ids, std::move(scenario));
  }
  const RunPlan plan = transport::load_plan(options.node);
  // Every id is checked before any participant exists; the stations keep references to their
  // options and places.
  std::deque<StationOptions> each;
  std::vector<const StationConfig*> places;
  for (int id : ids) {
    places.push_back(&participant_of(plan, id));
    each.push_back(options);
    each.back().id = id;
  }
  auto& node = transport::make_lifelong<transport::DdsNode>(transport::node_config(
      options.node, fmt::format("skyfuse-stations-{}", fmt::join(ids, "-"))));
  return run_on_threads(ids.size(), [&](std::size_t i) {
    return run_one_aircraft_station(each[i], plan, *places[i], &node);
  });
}

int run_on_threads(std::size_t count, const std::function<int(std::size_t)>& station) {
  std::vector<int> codes(count, options::kExitError);
  std::vector<std::thread> threads;
  threads.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    threads.emplace_back([&, i] { codes[i] = options::run_node([&] { return station(i); }); });
  }
  for (std::thread& thread : threads) thread.join();
  const auto failed =
      std::find_if(codes.begin(), codes.end(), [](int code) { return code != options::kExitOk; });
  return failed == codes.end() ? options::kExitOk : *failed;
}

}  // namespace skyfuse::station
