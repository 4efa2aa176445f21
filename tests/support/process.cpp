#include "support/process.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace skyfuse::test {

Process::Process(const std::vector<std::string>& argv, const std::filesystem::path& log)
    : log_(log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot open " + log.string());
  pid_ = fork();
  if (pid_ == 0) {
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    execv(args[0], args.data());
    _exit(127);
  }
  ::close(fd);
  if (pid_ < 0) throw std::runtime_error("fork failed");
}

Process::~Process() {
  if (!status_) {
    ::kill(pid_, SIGKILL);
    wait(std::chrono::seconds(10));
  }
}

std::optional<ExitStatus> Process::wait(std::chrono::milliseconds timeout) {
  if (status_) return status_;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    int raw = 0;
    if (waitpid(pid_, &raw, WNOHANG) == pid_) {
      status_ =
          WIFEXITED(raw) ? ExitStatus{true, WEXITSTATUS(raw)} : ExitStatus{false, WTERMSIG(raw)};
      return status_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void Process::signal(int signal) const {
  ::kill(pid_, signal);
}

std::string Process::output() const {
  return read_file(log_);
}

Completed run_to_completion(const std::vector<std::string>& argv, const std::filesystem::path& log,
                            std::chrono::milliseconds timeout) {
  Process p(argv, log);
  const auto status = p.wait(timeout);
  if (!status) {
    p.signal(SIGKILL);
    p.wait(std::chrono::seconds(10));
    return {{false, SIGKILL}, p.output() + "\n[test: killed after timeout]"};
  }
  return {*status, p.output()};
}

std::vector<pid_t> find_processes(const std::vector<std::string>& flag_values) {
  if (flag_values.size() % 2 != 0) {
    throw std::invalid_argument("find_processes: flags and values in pairs");
  }
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (!std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::vector<std::string> args;
    for (std::string arg; std::getline(in, arg, '\0');) args.push_back(arg);
    bool all = true;
    for (std::size_t i = 0; all && i < flag_values.size(); i += 2) {
      bool adjacent = false;
      for (std::size_t a = 0; !adjacent && a + 1 < args.size(); ++a) {
        adjacent = args[a] == flag_values[i] && args[a + 1] == flag_values[i + 1];
      }
      all = adjacent;
    }
    if (all && !args.empty()) found.push_back(static_cast<pid_t>(std::stoi(name)));
  }
  return found;
}

std::vector<std::string> fastdds_shm_entries() {
  std::vector<std::string> entries;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm")) {
    const std::string name = entry.path().filename().string();
    if (name.find("fastrtps") != std::string::npos || name.find("fastdds") != std::string::npos) {
      entries.push_back(name);
    }
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace skyfuse::test
