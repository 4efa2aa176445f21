#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

std::string_view to_string(ExchangeConfig::Kind kind) {
  return kind == ExchangeConfig::Kind::kTree ? "tree" : "flat";
}

std::optional<ExchangeConfig::Kind> parse_exchange_kind(std::string_view name) {
  if (name == "flat") return ExchangeConfig::Kind::kFlat;
  if (name == "tree") return ExchangeConfig::Kind::kTree;
  return std::nullopt;
}

void apply_exchange_overrides(Scenario& scenario, std::optional<ExchangeConfig::Kind> kind,
                              std::optional<int> fanout) {
  if (kind) scenario.exchange.kind = *kind;
  if (fanout) {
    if (*fanout < 2 || *fanout > ExchangeConfig::kMaxFanout) {
      throw std::invalid_argument(
          fmt::format("--fanout: must be in [2, {}], got {}", ExchangeConfig::kMaxFanout, *fanout));
    }
    scenario.exchange.fanout = *fanout;
  }
}

}  // namespace skyfuse
