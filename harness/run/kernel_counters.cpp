#include "run/kernel_counters.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace skyfuse::harness {
namespace {

std::string proc_path(pid_t pid, const char* file) {
  return "/proc/" + std::to_string(pid) + "/" + file;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string f; in >> f;) fields.push_back(f);
  return fields;
}

}  // namespace

std::optional<std::uint64_t> udp_datagrams_received(pid_t pid) {
  // Two "Udp:" lines: the first names the columns, the second holds the values.
  std::ifstream in(proc_path(pid, "net/snmp"));
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Udp: ", 0) != 0) continue;
    if (names.empty()) {
      names = fields_of(line);
      continue;
    }
    const std::vector<std::string> values = fields_of(line);
    for (std::size_t i = 1; i < names.size() && i < values.size(); ++i) {
      if (names[i] == "InDatagrams") return std::stoull(values[i]);
    }
    return std::nullopt;
  }
  return std::nullopt;
}

std::optional<double> cpu_seconds(pid_t pid) {
  std::ifstream in(proc_path(pid, "stat"));
  std::string stat;
  if (!std::getline(in, stat)) return std::nullopt;
  // The command name (field 2) may hold spaces; the fields after its closing parenthesis
  // start at field 3, so utime and stime (fields 14 and 15) are the 12th and 13th there.
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  const std::vector<std::string> rest = fields_of(stat.substr(close + 1));
  if (rest.size() < 13) return std::nullopt;
  const double ticks = static_cast<double>(std::stoull(rest[11]) + std::stoull(rest[12]));
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::optional<std::uint64_t> peak_resident_kib(pid_t pid) {
  std::ifstream in(proc_path(pid, "status"));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6));
  }
  return std::nullopt;
}

KernelSnapshot take_snapshot(const std::vector<pid_t>& processes,
                             const std::vector<pid_t>& one_per_namespace) {
  KernelSnapshot snapshot;
  for (pid_t pid : processes) snapshot.cpu_s += cpu_seconds(pid).value_or(0.0);
  std::uint64_t datagrams = 0;
  for (pid_t pid : one_per_namespace) {
    const auto n = udp_datagrams_received(pid);
    if (!n) return snapshot;
    datagrams += *n;
  }
  snapshot.udp_datagrams = datagrams;
  return snapshot;
}

std::string cpu_model() {
  // The name alone can hide generations ("AMD EPYC" names machines 3x apart): family and model
  // go with it. The first processor's block, which ends at the first empty line, says.
  std::ifstream in("/proc/cpuinfo");
  std::string name;
  std::string family;
  std::string model;
  for (std::string line; std::getline(in, line) && !line.empty();) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, line.find_last_not_of(" \t", colon - 1) + 1);
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : "";
    if (key == "model name") name = value;
    if (key == "cpu family") family = value;
    if (key == "model") model = value;
  }
  if (name.empty()) return "unknown";
  if (family.empty() || model.empty()) return name;
  return name + " (family " + family + ", model " + model + ")";
}

}  // namespace skyfuse::harness
