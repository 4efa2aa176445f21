#pragma once
// `skyfuse run --hosts N`: N simulated hosts on this machine, each a network namespace with its
// own interface, joined by a bridge in the harness's namespace, so that no two hosts share a
// loopback interface (and the processes share no memory: the DDS transport is UDP only). The
// harness stays on the bridge, where it serves discovery (or, with multicast discovery, takes
// part in it as every node does). Everything is created by the
// constructor and removed by the destructor; creating namespaces needs root.

#include <cstdint>
#include <string>
#include <vector>

namespace skyfuse::harness {

class SimulatedHosts {
 public:
  /// The most hosts a run may ask for: the /24 of their bridge has room for them.
  static constexpr int kMaxHosts = 250;

  /// Throws std::invalid_argument with the reason when this process may not create `count`
  /// hosts (not root, no `ip`, a count out of range).
  static void check_allowed(int count);

  /// Creates `count` hosts, whose interfaces carry multicast only if `multicast`; throws as
  /// check_allowed() does, and std::runtime_error when a step fails (what was made is removed).
  SimulatedHosts(int count, bool multicast);
  ~SimulatedHosts();
  SimulatedHosts(const SimulatedHosts&) = delete;
  SimulatedHosts& operator=(const SimulatedHosts&) = delete;

  int count() const { return static_cast<int>(namespaces_.size()); }
  /// Host `i`'s address on the bridge.
  const std::string& address(int i) const { return addresses_[static_cast<std::size_t>(i)]; }
  /// The harness's address on the bridge.
  const std::string& bridge_address() const { return bridge_address_; }
  /// Host `i`'s namespace as a file descriptor for setns(2).
  int namespace_fd(int i) const { return fds_[static_cast<std::size_t>(i)]; }

 private:
  void remove() noexcept;

  std::string bridge_;
  std::string bridge_address_;
  std::vector<std::string> namespaces_;
  std::vector<std::string> addresses_;
  std::vector<int> fds_;
};

}  // namespace skyfuse::harness
