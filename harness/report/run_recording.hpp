#pragma once
// `skyfuse run --record FILE.mcap`: the run as an MCAP recording (record/mcap_writer.hpp) of
// every round's messages on the channels of report/run_channels.hpp, then the run's summary —
// nothing thinned: one scene per round, one error entry per track in tracks.csv.

#include <cstdint>
#include <filesystem>
#include <string>

#include "run/run_report.hpp"

namespace skyfuse::harness {

/// Writes the rounds `recorder` holds to `path`, step 0 at `epoch_ns` (ns since the Unix
/// epoch), and `summary_json` (summary.json's text) after the last step. Throws
/// std::runtime_error naming the file if it cannot be written.
void write_recording(const RunRecorder& recorder, std::string summary_json,
                     const std::filesystem::path& path, std::uint64_t epoch_ns);

/// Whether skyfuse's page can show `path`: an MCAP file with its summary whose channels include
/// every round's (/skyfuse/round, with at least one message). Throws std::invalid_argument
/// naming the file and what is wrong with it.
void check_viewable_recording(const std::filesystem::path& path);

}  // namespace skyfuse::harness
