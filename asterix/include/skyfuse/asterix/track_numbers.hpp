#pragma once
// Short track numbers for a picture's tracks: I062/040 holds 16 bits, and every air-traffic
// display expects a number a controller can read, while a picture's track ids are 64-bit and
// never reused. Numbers are given by one rule that depends only on the pictures: each round,
// the tracks that are new take the lowest numbers free, in ascending id; a track gone gives
// its number back, free again only `hold_off_rounds` rounds later, so that a display does not
// join one aircraft's history to another's. Nodes fed the same pictures number them alike,
// round for round.

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <utility>
#include <vector>

namespace skyfuse::asterix {

class TrackNumbers {
 public:
  /// Numbers `first` to `last`, each free again `hold_off_rounds` rounds after its track went.
  /// first ≥ 1 (0 is no number), first ≤ last.
  explicit TrackNumbers(std::uint16_t first = 1, std::uint16_t last = 65535,
                        std::uint32_t hold_off_rounds = 10);

  /// Round `round`'s track ids, ascending (rounds ascending too): the tracks that went give
  /// their numbers back, the new ones take numbers. A track for which no number is free
  /// (more tracks than numbers) has none, and takes one in a later round when one frees.
  void update(std::span<const std::uint64_t> ids, std::uint64_t round);

  /// The number of track `id`, if it has one.
  std::optional<std::uint16_t> number_of(std::uint64_t id) const;

  /// Tracks of the last round without a number: the numbers ran out.
  std::size_t unnumbered() const { return unnumbered_; }

  /// Everything the numbering of the rounds to come depends on: what a node that restarts takes
  /// from a peer, so that it numbers the next rounds as the peer does.
  struct State {
    std::vector<std::pair<std::uint64_t, std::uint16_t>> numbers;  ///< (track id, number)
    std::vector<std::pair<std::uint64_t, std::uint16_t>> held;     ///< (free from round, number)
    std::vector<std::uint16_t> free;                               ///< given back, ascending
    std::uint32_t next_unused = 1;  ///< numbers from here on were never given
    bool operator==(const State&) const = default;
  };
  State state() const;
  /// Numbers as `state` says from now on (the range and hold-off stay this instance's).
  void restore(const State& state);

 private:
  std::optional<std::uint16_t> take_lowest_free();

  std::uint16_t last_;
  std::uint32_t hold_off_rounds_;
  std::uint32_t next_unused_;     // numbers from here to last_ were never given
  std::set<std::uint16_t> free_;  // given back and past their hold-off
  std::deque<std::pair<std::uint64_t, std::uint16_t>> held_;  // (free from round, number)
  std::map<std::uint64_t, std::uint16_t> numbers_;            // track id -> number
  std::size_t unnumbered_ = 0;
};

}  // namespace skyfuse::asterix
