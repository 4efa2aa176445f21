#include "skyfuse/asterix/track_numbers.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace skyfuse::asterix {

TrackNumbers::TrackNumbers(std::uint16_t first, std::uint16_t last, std::uint32_t hold_off_rounds)
    : last_(last), hold_off_rounds_(hold_off_rounds), next_unused_(first) {
  if (first == 0 || first > last) {
    throw std::invalid_argument("TrackNumbers: numbers from first >= 1 to last >= first");
  }
}

std::optional<std::uint16_t> TrackNumbers::take_lowest_free() {
  // A number given back was given before next_unused_, so it is the lower.
  if (!free_.empty()) {
    const std::uint16_t number = *free_.begin();
    free_.erase(free_.begin());
    return number;
  }
  if (next_unused_ <= last_) return static_cast<std::uint16_t>(next_unused_++);
  return std::nullopt;
}

void TrackNumbers::update(std::span<const std::uint64_t> ids, std::uint64_t round) {
  // The tracks gone give their numbers back, held off from now.
  std::vector<std::uint64_t> gone;
  for (const auto& [id, number] : numbers_) {
    if (!std::binary_search(ids.begin(), ids.end(), id)) gone.push_back(id);
  }
  for (const std::uint64_t id : gone) {
    held_.emplace_back(round + hold_off_rounds_, numbers_.at(id));
    numbers_.erase(id);
  }
  while (!held_.empty() && held_.front().first <= round) {
    free_.insert(held_.front().second);
    held_.pop_front();
  }
  // The new tracks, in ascending id, take the lowest numbers free.
  unnumbered_ = 0;
  for (const std::uint64_t id : ids) {
    if (numbers_.contains(id)) continue;
    if (const auto number = take_lowest_free()) {
      numbers_.emplace(id, *number);
    } else {
      ++unnumbered_;
    }
  }
}

TrackNumbers::State TrackNumbers::state() const {
  State s;
  s.numbers.assign(numbers_.begin(), numbers_.end());
  s.held.assign(held_.begin(), held_.end());
  s.free.assign(free_.begin(), free_.end());
  s.next_unused = next_unused_;
  return s;
}

void TrackNumbers::restore(const State& state) {
  numbers_ = {state.numbers.begin(), state.numbers.end()};
  held_ = {state.held.begin(), state.held.end()};
  free_ = {state.free.begin(), state.free.end()};
  next_unused_ = state.next_unused;
  unnumbered_ = 0;
}

std::optional<std::uint16_t> TrackNumbers::number_of(std::uint64_t id) const {
  const auto at = numbers_.find(id);
  if (at == numbers_.end()) return std::nullopt;
  return at->second;
}

}  // namespace skyfuse::asterix
