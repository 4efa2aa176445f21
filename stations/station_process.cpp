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
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_plan.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "station_fusions.hpp"
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
  // The filter part and the model pick the fusion; the sensor is the sensing's business.
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    int code = options::kExitError;
    visit_group_in_shard<decltype(shard)::value>(
        plan.scenario.filter, [&]<typename Filter, typename Model>(std::type_identity<Filter>,
                                                                   std::type_identity<Model>) {
          code = run_station_rounds<StationFusion<Filter, Model>>(options, plan, me,
                                                                  std::move(sensing), *node);
        });
    return code;
  });
}

// `options` for station `id`.
StationOptions with_id(StationOptions options, int id) {
  options.id = id;
  return options;
}

// What a process of several stations cannot do, and ids given twice.
void check_several_stations(const StationOptions& options, const std::vector<int>& ids) {
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
}

// A one-aircraft station that replaces one that died rejoins a lock-step run before its end.
void check_rejoin(const StationOptions& options, const RunPlan& plan) {
  if (!options.rejoin_step) return;
  if (*options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
    throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                            *options.rejoin_step, plan.scenario.steps - 1));
  }
  if (options.node.realtime_deadline_ms > 0.0) {
    throw std::invalid_argument("--rejoin-at-step: lock-step runs only, not real time");
  }
}

}  // namespace

int run_station(const StationOptions& options) {
  return run_stations(options, {options.id});
}

int run_stations(const StationOptions& options, const std::vector<int>& ids) {
  if (ids.size() > 1) check_several_stations(options, ids);
  // The run's kind is its plan's (sim/any_plan.hpp), which every node builds alike.
  AnyPlan any_plan = transport::load_any_plan(options.node);
  if (auto* picture = std::get_if<PicturePlan>(&any_plan)) {
    return ids.size() == 1 ? run_picture_station(with_id(options, ids.front()), *picture)
                           : run_picture_stations(options, ids, *picture);
  }
  const RunPlan& plan = std::get<RunPlan>(any_plan);
  if (ids.size() == 1) {
    const StationOptions one = with_id(options, ids.front());
    const StationConfig& me = participant_of(plan, one.id);
    check_rejoin(one, plan);
    return run_one_aircraft_station(one, plan, me, nullptr);
  }
  // Every id is checked before any participant exists; the stations keep references to their
  // options and places.
  std::deque<StationOptions> each;
  std::vector<const StationConfig*> places;
  for (int id : ids) {
    places.push_back(&participant_of(plan, id));
    each.push_back(with_id(options, id));
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
