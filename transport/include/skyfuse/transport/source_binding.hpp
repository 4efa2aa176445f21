#pragma once
/// \file
/// Which writer speaks for which station. The first writer a receiver hears for a station id
/// owns that id; a sample for the id from any other writer is a duplicate, whoever sent it.
/// A process that reuses a running station's id therefore cannot get its samples fused, even
/// if they arrive first in a later step. The one exception is how a restarted station gets its
/// id back: a station that delivered nothing in the step closed last may be claimed by a new
/// writer (admit() rebinds it).
///
/// This is trust on first use, not authentication: a process that speaks for an id before its
/// real owner does takes it. Authentication is DDS-Security's job (`skyfuse run --secure`).

#include <cstdint>
#include <map>
#include <optional>

#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::transport {

class SourceBinding {
 public:
  /// Binds `station_id` to `writer` in advance (a node's own writer).
  void bind(int station_id, const WriterId& writer) { owners_[station_id] = writer; }
  /// What accept() would say, binding nothing.
  bool would_accept(int station_id, const WriterId& writer) const {
    const auto it = owners_.find(station_id);
    return it == owners_.end() || it->second == writer;
  }
  /// True if `writer` owns `station_id`, binding it on first use.
  bool accept(int station_id, const WriterId& writer) {
    const auto [it, inserted] = owners_.try_emplace(station_id, writer);
    return inserted || it->second == writer;
  }

 private:
  std::map<int, WriterId> owners_;
};

/// The last stage of every receiver's screening, after the run id and the content passed: who
/// the sample claims to be and when (the collector's window), then whether its writer speaks
/// for that station; then the collector keeps it. Nothing if kept, else why not.
template <typename Payload>
std::optional<DropKind> admit(StepCollector<Payload>& collector, SourceBinding& sources,
                              std::uint64_t step, int station_id, const WriterId& writer,
                              const Payload& payload) {
  if (const auto why = collector.check(step, station_id)) return why;
  if (!sources.accept(station_id, writer)) {
    if (!collector.absent_last_step(station_id)) return DropKind::kDuplicate;
    sources.bind(station_id, writer);  // its old writer fell silent: a restarted process
  }
  return collector.offer(step, station_id, payload);
}

}  // namespace skyfuse::transport
