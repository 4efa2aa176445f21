#pragma once
// What `skyfuse run` of many aircraft prints and writes of its summary.

#include <cstdint>
#include <cstdio>
#include <string>

#include "run/picture_run.hpp"
#include "skyfuse/sim/picture_run.hpp"

namespace skyfuse::harness {

/// The table on the terminal.
void print_picture_run_table(const PictureRunSummary& summary, std::FILE* out);

/// summary.json's text: the run's figures and the in-process twin's.
std::string picture_run_json(const PictureRunSummary& summary, std::uint64_t run_id,
                             const PictureRunResult& twin);

}  // namespace skyfuse::harness
