#include "run/secure_start.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

bool is_stalled_start(const RunAborted& aborted) {
  const std::string_view what = aborted.what();
  // The harness's timeout and a node's FAILED status both say so; a node that timed out first
  // may also be seen only by its exit code.
  const std::string node_exit =
      fmt::format("exited with status {}", static_cast<int>(options::kExitDiscoveryTimeout));
  return what.find("discovery timed out") != std::string_view::npos ||
         what.find(node_exit) != std::string_view::npos || what.starts_with("round 0 incomplete");
}

}  // namespace skyfuse::harness
