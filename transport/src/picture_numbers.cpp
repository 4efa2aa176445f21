#include "skyfuse/transport/picture_numbers.hpp"

#include <set>
#include <vector>

namespace skyfuse::transport {

void number_round(const asterix::TrackNumbers& numbers, wire::PictureRound& round) {
  for (wire::PictureTrack& track : round.tracks()) {
    track.number(numbers.number_of(track.track_id()).value_or(0));
  }
}

void track_numbers_to_wire(const asterix::TrackNumbers& numbers, wire::PictureState& sample) {
  const asterix::TrackNumbers::State state = numbers.state();
  const auto pairs = [](const auto& from, std::vector<wire::PictureTrackNumber>& to) {
    to.clear();
    to.reserve(from.size());
    for (const auto& [key, number] : from) {
      wire::PictureTrackNumber n;
      n.key(key);
      n.number(number);
      to.push_back(n);
    }
  };
  pairs(state.numbers, sample.track_numbers());
  pairs(state.held, sample.numbers_held());
  sample.numbers_free(state.free);
  sample.numbers_next(state.next_unused);
}

std::optional<asterix::TrackNumbers::State> track_numbers_from_wire(
    const wire::PictureState& sample) {
  asterix::TrackNumbers::State state;
  std::set<std::uint16_t> given;
  for (const wire::PictureTrackNumber& n : sample.track_numbers()) {
    if (n.number() == 0 || !given.insert(n.number()).second) return std::nullopt;
    if (!state.numbers.empty() && n.key() <= state.numbers.back().first) return std::nullopt;
    state.numbers.emplace_back(n.key(), n.number());
  }
  for (const wire::PictureTrackNumber& n : sample.numbers_held()) {
    if (n.number() == 0) return std::nullopt;
    if (!state.held.empty() && n.key() < state.held.back().first) return std::nullopt;
    state.held.emplace_back(n.key(), n.number());
  }
  for (const std::uint16_t number : sample.numbers_free()) {
    if (number == 0 || (!state.free.empty() && number <= state.free.back())) return std::nullopt;
    state.free.push_back(number);
  }
  // Numbers start at 1: a state whose first never given is 0 numbers nothing (or is not a
  // node's).
  if (sample.numbers_next() == 0) return std::nullopt;
  state.next_unused = sample.numbers_next();
  return state;
}

}  // namespace skyfuse::transport
