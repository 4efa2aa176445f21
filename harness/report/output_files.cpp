#include "report/output_files.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace skyfuse::harness {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
    out << content;
    if (!out.flush()) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
  }
  std::filesystem::rename(tmp, path);
}

std::filesystem::path executable_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::current_path() : exe.parent_path();
}

std::filesystem::path helper_program(const std::string& name) {
  auto path = executable_dir() / name;
  if (access(path.c_str(), X_OK) != 0) {
    throw std::runtime_error(fmt::format(
        "{} is not built beside this program (./quickstart demo builds only what the demo runs): "
        "build it with `cmake --build build --target {}` after configuring with "
        "-DSKYFUSE_BUILD_BENCHMARKS=ON, or run ./quickstart test",
        path.string(), name));
  }
  return path;
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  // Debian's interpreter carries python3-matplotlib; a python3 earlier on PATH may not.
  const char* python = std::getenv("SKYFUSE_PYTHON");
  std::string command =
      python ? python : (access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3");
  command = fmt::format("'{}' '{}'", command, (executable_dir() / script).string());
  for (const std::string& a : args) command += fmt::format(" '{}'", a);
  return std::system(command.c_str()) == 0;
}

}  // namespace skyfuse::harness
