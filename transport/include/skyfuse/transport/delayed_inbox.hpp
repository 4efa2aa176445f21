#pragma once
/// \file
/// Received samples held back by the simulated link delay (random/link_delay.hpp) until they
/// are due, then handed on earliest first, as if they had just arrived: the transport glue's
/// part of `--link-delay-ms` and `--link-jitter-ms`. No Fast DDS here.

#include <algorithm>
#include <chrono>
#include <map>
#include <utility>

#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::transport {

template <typename Sample>
class DelayedInbox {
 public:
  using Clock = std::chrono::steady_clock;

  /// Keeps `sample` from `writer` until `due`.
  void hold(Sample sample, const WriterId& writer, Clock::time_point due) {
    held_.emplace(due, Held{std::move(sample), writer});
  }

  /// deliver(sample, writer) for every held sample due by `now`, earliest first (samples due at
  /// the same time in the order they were held).
  template <typename Deliver>
  void release_due(Clock::time_point now, Deliver deliver) {
    while (!held_.empty() && held_.begin()->first <= now) {
      auto node = held_.extract(held_.begin());
      deliver(node.mapped().sample, node.mapped().writer);
    }
  }

  /// How long a wait may last so as not to sleep past the next due sample: `longest` if none
  /// is held, zero if one is due already.
  std::chrono::microseconds wait_limit(Clock::time_point now,
                                       std::chrono::microseconds longest) const {
    if (held_.empty()) return longest;
    const auto left = std::chrono::ceil<std::chrono::microseconds>(held_.begin()->first - now);
    return std::clamp(left, std::chrono::microseconds(0), longest);
  }

 private:
  struct Held {
    Sample sample;
    WriterId writer;
  };
  std::multimap<Clock::time_point, Held> held_;
};

}  // namespace skyfuse::transport
