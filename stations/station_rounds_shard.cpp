// One shard of the station's rounds: cmake/FilterShards.cmake compiles this file once per shard,
// with SKYFUSE_SHARD set. It compiles the rounds of each fusion whose first configuration group
// is in this shard (station_fusions.hpp): a fusion two groups share is compiled once.
#include <type_traits>

#include "skyfuse/registry/filter_shards.hpp"
#include "station.hpp"
#include "station_fusions.hpp"

namespace skyfuse::station {

template <std::size_t Shard>
void keep_station_rounds_in_shard() {
  for_each_group_in_shard<Shard>(
      []<typename Filter, typename Model>(std::type_identity<Filter>, std::type_identity<Model>) {
        if constexpr (compiles_its_fusion<Filter, Model>()) {
          // Naming the rounds by their address compiles them here; `used` keeps them for the
          // linker, though nothing reads the address.
          [[gnu::used]] static constexpr auto kRounds =
              &run_station_rounds<StationFusion<Filter, Model>>;
        }
      });
}

template void keep_station_rounds_in_shard<SKYFUSE_SHARD>();

}  // namespace skyfuse::station
