#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

std::string_view to_string(ExchangeConfig::Kind kind) {
  switch (kind) {
    case ExchangeConfig::Kind::kFlat:
      return "flat";
    case ExchangeConfig::Kind::kTree:
      return "tree";
    case ExchangeConfig::Kind::kAuto:
      break;
  }
  return "auto";
}

std::optional<ExchangeConfig::Kind> parse_exchange_kind(std::string_view name) {
  if (name == "flat") return ExchangeConfig::Kind::kFlat;
  if (name == "tree") return ExchangeConfig::Kind::kTree;
  if (name == "auto") return ExchangeConfig::Kind::kAuto;
  return std::nullopt;
}

ExchangeConfig::Kind chosen_exchange(const Scenario& scenario, std::size_t stations) {
  if (scenario.exchange.kind != ExchangeConfig::Kind::kAuto) return scenario.exchange.kind;
  const auto filter = find_filter(scenario.filter);
  const bool nodes_take_tree = filter && filter->nodes_take_tree;
  return nodes_take_tree && stations >= ExchangeConfig::kTreeFromStations
             ? ExchangeConfig::Kind::kTree
             : ExchangeConfig::Kind::kFlat;
}

std::size_t round_fanout_for(const Scenario& scenario, std::size_t stations) {
  ExchangeConfig exchange = scenario.exchange;
  exchange.kind = chosen_exchange(scenario, stations);
  return exchange.round_fanout();
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
