#pragma once
// Real processes for integration tests: start one with its output captured to a file, wait for
// it with a timeout, signal it, find processes by their command line. A test never hangs: the
// destructor kills what is still running.

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace skyfuse::test {

struct ExitStatus {
  bool exited = false;  ///< false: killed by a signal
  int code = -1;        ///< exit code, or the signal number
};

class Process {
 public:
  Process(const std::vector<std::string>& argv, const std::filesystem::path& log);
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  pid_t pid() const { return pid_; }
  /// The exit status, or nullopt if still running after `timeout`.
  std::optional<ExitStatus> wait(std::chrono::milliseconds timeout);
  void signal(int signal) const;
  /// Everything the process wrote to stdout and stderr so far.
  std::string output() const;

 private:
  pid_t pid_ = -1;
  std::filesystem::path log_;
  std::optional<ExitStatus> status_;
};

/// Runs to completion (killed after `timeout`) and returns the status and the output.
struct Completed {
  ExitStatus status;
  std::string output;
};
Completed run_to_completion(const std::vector<std::string>& argv, const std::filesystem::path& log,
                            std::chrono::milliseconds timeout);

/// Pids of live processes whose command line holds every pair of `flag_values` (flag, value,
/// flag, value, ...) as adjacent arguments: {"--id", "17"} is station 17, not a station whose
/// peer list names participant 17.
std::vector<pid_t> find_processes(const std::vector<std::string>& flag_values);

/// Names in /dev/shm that Fast DDS creates (segments, port files, semaphores).
std::vector<std::string> fastdds_shm_entries();

/// Polls `condition` every 20 ms until it holds or `timeout` passes.
bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout);

std::string read_file(const std::filesystem::path& path);

}  // namespace skyfuse::test
