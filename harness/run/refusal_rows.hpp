#pragma once
// refusals.csv, either kind's: each refusal a node reported, as reported in round `reported`
// (the nodes' last statuses: the run's `steps`), by node (0 the center, -1 the harness), the
// node's round and the kind; its rows add up to summary.json's counts by node.

#include <fmt/format.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "run/round_record.hpp"

namespace skyfuse::harness {

inline constexpr std::string_view kRefusalsHeader = "reported,node,step,kind,count\n";

inline void append_refusal_rows(std::string& csv, std::uint64_t reported,
                                std::span<const Refusal> refused) {
  for (const Refusal& x : refused) {
    csv += fmt::format("{},{},{},{},{}\n", reported, x.node, x.step, to_string(x.kind), x.count);
  }
}

}  // namespace skyfuse::harness
