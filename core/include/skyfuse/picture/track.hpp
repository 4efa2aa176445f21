#pragma once
/// \file
/// One track of the fused picture: its id, its status, its filter state and its history of
/// hits and misses. Every peer holds the same table bit for bit.

#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/registration/considered_biases.hpp"

namespace skyfuse {

/// A track's id: a function of the round and of the detection that started it, so that every
/// peer, and the center, names a new track the same without asking anyone. Step in the high 32
/// bits, then the station id and the detection's index in its scan, 16 bits each.
using TrackId = std::uint64_t;

/// The id of a track started at `step` by detection `detection` of station `station_id`.
/// Throws std::out_of_range for a station id or index beyond 16 bits.
TrackId make_track_id(std::uint64_t step, int station_id, std::uint32_t detection);
/// "step.station.detection", as people and recordings name it.
std::string track_label(TrackId id);

enum class TrackStatus : std::uint8_t {
  kTentative,  ///< started, not yet confirmed: not in the picture users see as tracks
  kConfirmed,
};
const char* to_string(TrackStatus status);

/// Hits and misses, most recent first.
class TrackHistory {
 public:
  void record(bool hit) {
    hits_ = (hits_ << 1U) | (hit ? 1U : 0U);
    if (rounds_ < 32) ++rounds_;
    consecutive_misses_ = hit ? 0 : consecutive_misses_ + 1;
  }
  /// Hits among the last `window` rounds (at most 32).
  int hits_in_last(int window) const {
    const std::uint32_t mask = window >= 32 ? ~0U : ((1U << window) - 1U);
    return std::popcount(hits_ & mask);
  }
  int rounds() const { return static_cast<int>(rounds_); }
  int consecutive_misses() const { return static_cast<int>(consecutive_misses_); }
  bool operator==(const TrackHistory&) const = default;

  /// The history as three words, and back: what a peer sends of it to another that must hold
  /// the same picture (transport/picture_state_wire.hpp). nullopt for words no history has.
  struct Words {
    std::uint32_t hits = 0;  ///< bit i: a hit i rounds ago
    std::uint32_t rounds = 0;
    std::uint32_t consecutive_misses = 0;
  };
  Words words() const { return {hits_, rounds_, consecutive_misses_}; }
  static std::optional<TrackHistory> from_words(const Words& w) {
    if (w.rounds > 32) return std::nullopt;  // it counts rounds up to 32
    TrackHistory history;
    history.hits_ = w.hits;
    history.rounds_ = w.rounds;
    history.consecutive_misses_ = w.consecutive_misses;
    return history;
  }

 private:
  std::uint32_t hits_ = 0;  // bit i: a hit i rounds ago
  std::uint32_t rounds_ = 0;
  std::uint32_t consecutive_misses_ = 0;
};

/// A track whose filter is a `State` (picture/track_filters.hpp: a Gaussian, an IMM).
template <typename State>
struct Track {
  TrackId id = 0;
  TrackStatus status = TrackStatus::kTentative;
  TrackHistory history;
  State filter;
  /// The stations whose detections updated it in the last round, ascending.
  std::vector<int> updated_by;
  /// The aircraft's address, once an addressed detection was assigned to the track
  /// (picture/identity.hpp); kNoAddress until then.
  Address address = kNoAddress;
  /// Its error's cross-covariance with each registered station's bias error, for a filter part
  /// that keeps them (registration/considered_biases.hpp); empty otherwise.
  ConsideredBiases considered{};
};

}  // namespace skyfuse
