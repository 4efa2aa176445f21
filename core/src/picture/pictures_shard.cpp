// The pictures' tables, the peers' and the center's (picture/peer_picture.hpp,
// central_picture.hpp and the table under both, track_table.hpp), compiled here once for every
// group of this shard that a picture runs (picture/picture_parts.hpp) and nowhere else: the
// in-process picture, the station and center processes, the benchmarks and the tests see only
// their declarations and link these. The peers and the center share most of what they compile
// (the filter part's arithmetic for every sensor), so they are compiled in one file: apart, the
// unscented filter's shard took 64 s each instead of 65 s together.
// cmake/FilterShards.cmake compiles this file once per shard, with SKYFUSE_SHARD set.
#include <tuple>
#include <type_traits>
#include <utility>

#include "skyfuse/picture/central_picture_impl.hpp"
#include "skyfuse/picture/peer_picture_impl.hpp"
#include "skyfuse/picture/picture_parts.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#if SKYFUSE_STATE_SIZE_SLOTS == 0
#include "skyfuse/picture/state_size_code.hpp"
#endif

namespace skyfuse {
namespace {

// The headers declare the rounds and the *_impl.hpp define them; naming each public round by
// its address makes the compiler compile it here, and `used` keeps the addresses, though nothing
// reads them, so this object file holds every round for the linker.
template <typename Tracks>
void keep_table_rounds() {
  using Table = TrackTable<Tracks>;
  [[gnu::used]] static constexpr auto kRounds = std::tuple{
      &Table::associate, &Table::add_known_track, &Table::predict, &Table::restore, &Table::digest};
}

template <typename Parts>
void keep_picture_rounds() {
  using Peer = PeerPicture<typename Parts::Peer>;
  using Center = CentralPicture<typename Parts::Center>;
  keep_table_rounds<typename Parts::Peer>();
  keep_table_rounds<typename Parts::Center>();
  [[gnu::used]] static constexpr auto kRounds =
      std::tuple{&Peer::report, &Peer::report_of, &Peer::fuse, &Center::update};
}

}  // namespace

template <std::size_t Shard>
void keep_pictures_in_shard() {
  for_each_picture_parts_in_shard<Shard>(
      []<typename Parts>(std::type_identity<Parts>) { keep_picture_rounds<Parts>(); });
#if SKYFUSE_STATE_SIZE_SLOTS == 0
  // No file of its own compiles the code of each state size (picture/state_size_code.hpp):
  // the first shard does.
  if constexpr (Shard == 0) {
    keep_state_size_slots(std::make_index_sequence<picture_state_sizes().count>{});
  }
#endif
}

template void keep_pictures_in_shard<SKYFUSE_SHARD>();

}  // namespace skyfuse
