#pragma once
// What the house that runs either kind over DDS (run/run_over_dds.hpp) asks of its driver
// outside the rounds: that every node join, and a station killed and started again between
// rounds. LockstepDriver (one aircraft) and PictureDriver (many) are both one.

#include <chrono>

namespace skyfuse::harness {

class NodeDriver {
 public:
  virtual ~NodeDriver() = default;
  /// Until every node announced READY and the harness's endpoints match them.
  virtual void wait_until_joined(std::chrono::milliseconds timeout) = 0;
  /// Station `id` killed (true) or started again (false): a station down is not waited for.
  virtual void set_down(int id, bool down) = 0;
  /// Until a restarted station has announced READY again.
  virtual void wait_until_ready(int id, std::chrono::milliseconds timeout) = 0;
};

}  // namespace skyfuse::harness
