#include "run/child_processes.hpp"

#include <fmt/format.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace skyfuse::harness {

std::string ChildExit::describe() const {
  if (WIFEXITED(status)) {
    return fmt::format("{} (pid {}) exited with status {}", name, pid, WEXITSTATUS(status));
  }
  if (WIFSIGNALED(status)) {
    return fmt::format("{} (pid {}) was killed by signal {} ({})", name, pid, WTERMSIG(status),
                       strsignal(WTERMSIG(status)));
  }
  return fmt::format("{} (pid {}) ended with wait status {}", name, pid, status);
}

std::string ChildExit::outcome() const {
  if (WIFEXITED(status)) return fmt::format("exit {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    return fmt::format("signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  }
  return fmt::format("wait status {}", status);
}

bool ChildExit::success() const {
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

ChildProcesses::~ChildProcesses() {
  terminate_all(std::chrono::milliseconds(2000));
}

pid_t ChildProcesses::spawn(const std::string& name, const std::vector<std::string>& argv,
                            int network_namespace) {
  // Everything exec needs is prepared before fork: the child of a multi-threaded process may
  // only call async-signal-safe functions.
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t parent = getpid();

  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(fmt::format("fork for {}: {}", name, strerror(errno)));
  if (pid == 0) {
    // Die with the harness, however it dies; and if it died before this line, go now.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    if (network_namespace >= 0 && setns(network_namespace, CLONE_NEWNET) != 0) _exit(126);
    // Keep only stdin, stdout and stderr: the harness's DDS sockets (Fast DDS does not open
    // them close-on-exec) would otherwise stay bound in every node, and stay open after the
    // harness has gone.
    close_range(3, ~0U, 0);
    execv(args[0], args.data());
    _exit(127);
  }
  children_.push_back({name, pid});
  return pid;
}

void ChildProcesses::kill_now(const std::string& name) {
  const auto it = std::find_if(children_.begin(), children_.end(),
                               [&](const Child& c) { return c.name == name; });
  if (it == children_.end()) throw std::runtime_error(fmt::format("no live child called {}", name));
  kill(it->pid, SIGKILL);
  int status = 0;
  rusage usage{};
  while (wait4(it->pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  add_cpu(usage);
  children_.erase(it);
}

std::vector<ChildExit> ChildProcesses::poll() {
  std::vector<ChildExit> now_exited;
  for (auto it = children_.begin(); it != children_.end();) {
    int status = 0;
    rusage usage{};
    const pid_t r = wait4(it->pid, &status, WNOHANG, &usage);
    if (r == it->pid) {
      add_cpu(usage);
      now_exited.push_back({it->name, it->pid, status});
      exited_.push_back(now_exited.back());
      it = children_.erase(it);
    } else {
      ++it;
    }
  }
  return now_exited;
}

bool ChildProcesses::wait_all(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    poll();
    if (children_.empty()) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void ChildProcesses::terminate_all(std::chrono::milliseconds grace) {
  poll();
  if (children_.empty()) return;
  for (const Child& c : children_) kill(c.pid, SIGTERM);
  if (wait_all(grace)) return;
  for (const Child& c : children_) kill(c.pid, SIGKILL);
  wait_all(std::chrono::milliseconds(5000));
}

void ChildProcesses::add_cpu(const rusage& usage) {
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  reaped_cpu_s_ += seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

std::vector<pid_t> ChildProcesses::pids() const {
  std::vector<pid_t> pids;
  for (const Child& c : children_) pids.push_back(c.pid);
  return pids;
}

}  // namespace skyfuse::harness
