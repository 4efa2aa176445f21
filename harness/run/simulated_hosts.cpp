#include "run/simulated_hosts.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

extern char** environ;

namespace skyfuse::harness {
namespace {

// RFC 2544's benchmarking range, 198.18.0.0/15: meant for test networks, routed nowhere, so a
// /24 of it is unlikely to collide with a real network of the machine.
constexpr const char* kSubnetPrefix = "198.18";

// Runs `ip` with `args`; its exit status (127 if it could not start).
int ip(const std::vector<std::string>& args, bool quiet = false) {
  std::vector<std::string> argv = {"ip"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> raw;
  for (std::string& a : argv) raw.push_back(a.data());
  raw.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "ip", &actions, nullptr, raw.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return 127;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return 127;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

void ip_or_throw(const std::vector<std::string>& args) {
  if (const int status = ip(args); status != 0) {
    throw std::runtime_error(
        fmt::format("--hosts: `ip {}` failed (status {})", fmt::join(args, " "), status));
  }
}

// Whether a link of this name exists, or an address of this machine lies in `subnet`.0/24.
bool taken(const std::string& link, const std::string& subnet) {
  if (ip({"link", "show", link}, true) == 0) return true;
  const std::string command = fmt::format("ip -4 -o addr show to {}.0/24 2>/dev/null", subnet);
  FILE* out = popen(command.c_str(), "r");
  if (out == nullptr) return true;
  const bool any = std::fgetc(out) != EOF;
  pclose(out);
  return any;
}

}  // namespace

void SimulatedHosts::check_allowed(int count) {
  if (count < 1 || count > kMaxHosts) {
    throw std::invalid_argument(fmt::format("--hosts: expected 1 to {}, got {}", kMaxHosts, count));
  }
  if (geteuid() != 0) {
    throw std::invalid_argument(
        "--hosts: creating network namespaces needs root; run as root, or leave out --hosts "
        "to run every process on this host's loopback");
  }
  if (ip({"-V"}, true) != 0) {
    throw std::invalid_argument("--hosts: needs the `ip` command (Debian package iproute2)");
  }
}

SimulatedHosts::SimulatedHosts(int count, bool multicast) {
  check_allowed(count);
  // A tag of our own, so that runs side by side do not meet: the pid's low bits pick the
  // names and the /24, the next free one if taken.
  const int pid = static_cast<int>(getpid());
  int tag = -1;
  for (int i = 0; i < 256 && tag < 0; ++i) {
    const int candidate = (pid + i) % 256;
    if (!taken(fmt::format("sfbr{}", candidate), fmt::format("{}.{}", kSubnetPrefix, candidate))) {
      tag = candidate;
    }
  }
  if (tag < 0) throw std::runtime_error("--hosts: no free bridge name and subnet");
  const std::string subnet = fmt::format("{}.{}", kSubnetPrefix, tag);
  bridge_ = fmt::format("sfbr{}", tag);
  bridge_address_ = subnet + ".254";
  try {
    ip_or_throw({"link", "add", bridge_, "type", "bridge"});
    ip_or_throw({"addr", "add", bridge_address_ + "/24", "dev", bridge_});
    ip_or_throw({"link", "set", bridge_, "up"});
    for (int i = 0; i < count; ++i) {
      const std::string name = fmt::format("skyfuse-{}-h{}", tag, i);
      const std::string veth = fmt::format("sfv{}-{}", tag, i);
      ip_or_throw({"netns", "add", name});
      namespaces_.push_back(name);
      const std::string address = fmt::format("{}.{}", subnet, i + 1);
      ip_or_throw({"link", "add", veth, "type", "veth", "peer", "name", "eth0", "netns", name});
      ip_or_throw({"link", "set", veth, "master", bridge_, "up"});
      ip_or_throw({"-n", name, "addr", "add", address + "/24", "dev", "eth0"});
      // Without multicast discovery, no multicast on the host's interface: discovery and data
      // must go through the server and unicast, as across real networks that do not carry
      // multicast. With it, the bridge carries every participant's announcements to every host.
      ip_or_throw({"-n", name, "link", "set", "eth0", "multicast", multicast ? "on" : "off", "up"});
      ip_or_throw({"-n", name, "link", "set", "lo", "up"});
      addresses_.push_back(address);
      const int fd = open(("/run/netns/" + name).c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) throw std::runtime_error("--hosts: cannot open /run/netns/" + name);
      fds_.push_back(fd);
    }
  } catch (...) {
    remove();
    throw;
  }
  spdlog::info("--hosts: {} hosts {}.1-{} on bridge {} ({})", count, subnet, count, bridge_,
               bridge_address_);
}

SimulatedHosts::~SimulatedHosts() {
  remove();
}

void SimulatedHosts::remove() noexcept {
  for (int fd : fds_) close(fd);
  fds_.clear();
  // Deleting a namespace deletes its end of the veth pair, and with it the other end.
  for (const std::string& name : namespaces_) {
    if (ip({"netns", "delete", name}, true) != 0) {
      spdlog::warn("--hosts: could not delete network namespace {}", name);
    }
  }
  namespaces_.clear();
  if (!bridge_.empty() && ip({"link", "delete", bridge_}, true) != 0) {
    spdlog::warn("--hosts: could not delete bridge {}", bridge_);
  }
  bridge_.clear();
}

}  // namespace skyfuse::harness
