#pragma once
// What the kernel counts for a run, read from /proc: UDP datagrams received (every socket of a
// network namespace), and a process's CPU time and peak resident memory. A benchmark reads them
// before and after the rounds; the differences are the rounds' cost, whatever the processes
// themselves believe they did.

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace skyfuse::harness {

/// UDP datagrams delivered to sockets of the network namespace `pid` lives in (the `Udp:
/// InDatagrams` of /proc/PID/net/snmp; a multicast datagram counts once per receiving socket).
/// None when the file cannot be read (the process is gone).
std::optional<std::uint64_t> udp_datagrams_received(pid_t pid);

/// User plus system CPU time `pid` has used so far, in seconds (/proc/PID/stat).
std::optional<double> cpu_seconds(pid_t pid);

/// The most resident memory `pid` has held, in KiB (VmHWM of /proc/PID/status).
std::optional<std::uint64_t> peak_resident_kib(pid_t pid);

/// The CPU's model name as /proc/cpuinfo gives it ("unknown" if it does not): every figure of
/// speed is printed beside it, since machines of one kind differ by 2-3x.
std::string cpu_model();

/// The kernel's counts over a run's processes at one moment.
struct KernelSnapshot {
  /// Summed over one process per network namespace; none when one could not be read.
  std::optional<std::uint64_t> udp_datagrams;
  double cpu_s = 0.0;  ///< summed over the processes still alive
};

/// Reads `processes`' CPU time and the UDP counters of the namespaces that
/// `one_per_namespace` live in.
KernelSnapshot take_snapshot(const std::vector<pid_t>& processes,
                             const std::vector<pid_t>& one_per_namespace);

}  // namespace skyfuse::harness
