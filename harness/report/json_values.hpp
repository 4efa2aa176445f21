#pragma once
// Values of the harness's JSON files that a run may not have.

#include <nlohmann/json.hpp>
#include <optional>

namespace skyfuse::harness {

/// The figure, or null where the run could not measure it (a count the kernel did not give).
inline nlohmann::json number_or_null(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace skyfuse::harness
