#pragma once
// `skyfuse run --stations-per-process K`: which process runs which stations. Process 0 is the
// center; then the stations in ascending id, K consecutive ones to a process (the last may have
// fewer), so that with K equal to the tree's fanout a cluster shares one process and its
// members' sums pass in memory. K = 1, the default, is one process per station.

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace skyfuse::harness {

class StationGroups {
 public:
  StationGroups(std::size_t stations, std::size_t per_process)
      : stations_(stations), per_process_(per_process == 0 ? 1 : per_process) {}

  /// Processes in all: the center and the station processes.
  std::size_t processes() const { return 1 + (stations_ + per_process_ - 1) / per_process_; }
  /// The process of the station at `position` among the run's ids in ascending order.
  std::size_t process_of(std::size_t position) const { return 1 + position / per_process_; }
  /// The process of station `id`, one of the run's `ascending_ids`.
  std::size_t process_of_id(int id, std::span<const int> ascending_ids) const {
    return process_of(static_cast<std::size_t>(
        std::find(ascending_ids.begin(), ascending_ids.end(), id) - ascending_ids.begin()));
  }
  /// Process `process`'s station ids (process >= 1), out of the run's `ascending_ids`.
  std::vector<int> ids_of(std::size_t process, std::span<const int> ascending_ids) const {
    const std::size_t first = (process - 1) * per_process_;
    const std::size_t last = std::min(first + per_process_, stations_);
    return {ascending_ids.begin() + static_cast<std::ptrdiff_t>(first),
            ascending_ids.begin() + static_cast<std::ptrdiff_t>(last)};
  }

 private:
  std::size_t stations_;
  std::size_t per_process_;
};

/// How a station process is told its stations: `--id A --id B ...`.
inline std::vector<std::string> id_arguments(std::span<const int> group) {
  std::vector<std::string> arguments;
  for (const int id : group) {
    arguments.push_back("--id");
    arguments.push_back(std::to_string(id));
  }
  return arguments;
}

}  // namespace skyfuse::harness
