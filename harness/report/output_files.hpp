#pragma once
// Results are written through a temporary file and a rename, so a run that fails half-way
// never leaves half a file where a whole one stood.

#include <filesystem>
#include <string>
#include <vector>

namespace skyfuse::harness {

void write_file_atomically(const std::filesystem::path& path, const std::string& content);

/// The folder of the running executable (where the station, center and scripts live).
std::filesystem::path executable_dir();

/// A helper program beside the executable that only the full build makes (the benchmark's and
/// the floor's); throws, naming the build command, when it is not there.
std::filesystem::path helper_program(const std::string& name);

/// Runs one of the plot scripts beside the executable with Debian's python3; false on failure.
bool run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace skyfuse::harness
