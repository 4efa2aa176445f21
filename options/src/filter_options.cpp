#include "skyfuse/options/filter_options.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/registry/filter_info.hpp"

namespace skyfuse::options {

void settle_exchange(Scenario& scenario, const NodeOptions& node) {
  ExchangeConfig& exchange = scenario.exchange;
  if (exchange.chosen_by_size && exchange.kind == ExchangeConfig::Kind::kTree &&
      (node.loss.enabled() || node.delay.enabled() || node.refusion_lag != 0)) {
    exchange.kind = ExchangeConfig::Kind::kFlat;
  }
  const auto filter = find_filter(scenario.filter.kind);
  if (!filter) {  // the loader refuses an unknown filter: this is a programming error
    throw std::logic_error("unregistered filter " + scenario.filter.kind);
  }
  if (const auto why =
          filter_option_refusal(*filter, node.refusion_lag, node.nis_gate().enabled())) {
    throw std::invalid_argument(fmt::format("scenario '{}': {}", scenario.name, *why));
  }
  if (scenario.exchange.kind != ExchangeConfig::Kind::kTree) return;
  if (!filter->nodes_take_tree) {
    throw std::invalid_argument(
        fmt::format("--exchange tree: the station processes of filter {} exchange flat only; the "
                    "in-process `skyfuse sweep` runs the tree for it",
                    filter->kind));
  }
  if (node.refusion_lag != 0) {
    throw std::invalid_argument(
        "--refusion-lag with --exchange tree: the tree exchange fuses each round once; leave "
        "the lag at 0");
  }
}

}  // namespace skyfuse::options
