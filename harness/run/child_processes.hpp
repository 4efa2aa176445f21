#pragma once
// The station and center processes a run starts. Children die with the harness even if it is
// killed with SIGKILL (PR_SET_PDEATHSIG), exits are noticed while the harness waits for
// anything, and on the way out every child still alive is terminated, then killed.

#include <sys/resource.h>
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace skyfuse::harness {

struct ChildExit {
  std::string name;
  pid_t pid = 0;
  int status = 0;                ///< raw waitpid status
  std::string describe() const;  ///< "station 3 (pid 123) exited with status 2"
  std::string outcome() const;   ///< "exit 2", "signal 6 (Aborted)"
  bool success() const;
};

class ChildProcesses {
 public:
  ChildProcesses() = default;
  ~ChildProcesses();
  ChildProcesses(const ChildProcesses&) = delete;
  ChildProcesses& operator=(const ChildProcesses&) = delete;

  /// Starts `argv[0]` with `argv`; `name` identifies it in messages. Throws on failure.
  /// `network_namespace`: a namespace's file descriptor (a simulated host) to run it in; -1:
  /// the harness's own.
  pid_t spawn(const std::string& name, const std::vector<std::string>& argv,
              int network_namespace = -1);

  /// Kills the child called `name` with SIGKILL and reaps it: a crash the caller asked for, so
  /// it is not reported by poll() or exited(). Throws if there is no such live child.
  void kill_now(const std::string& name);

  /// Reaps children that have exited since the last call.
  std::vector<ChildExit> poll();
  /// Waits up to `timeout` for every child to exit by itself; true if all did.
  bool wait_all(std::chrono::milliseconds timeout);
  /// SIGTERM to every live child, SIGKILL to any still alive after `grace`.
  void terminate_all(std::chrono::milliseconds grace);

  std::size_t alive() const { return children_.size(); }
  /// The live children's process ids.
  std::vector<pid_t> pids() const;
  const std::vector<ChildExit>& exited() const { return exited_; }
  /// The CPU time (user and system) of every child reaped so far, s: with the live children's,
  /// a count that does not drop when a child exits between two readings.
  double reaped_cpu_s() const { return reaped_cpu_s_; }

 private:
  struct Child {
    std::string name;
    pid_t pid;
  };
  void add_cpu(const rusage& usage);

  std::vector<Child> children_;
  std::vector<ChildExit> exited_;
  double reaped_cpu_s_ = 0.0;
};

}  // namespace skyfuse::harness
