#pragma once
// What `skyfuse sweep` reports of a registered scenario's bias estimates (docs/registration.md):
// per station, over the runs, how many ended within 2σ of their truth and from which round on
// they stayed so; registration.csv holds every round of every run.

#include <cstdio>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "report/picture_report.hpp"

namespace skyfuse::harness {

/// The table of each station's estimates over the runs; nothing where nothing registers.
void print_registration_table(const PictureReport& report, std::FILE* out);
/// registration.csv: run, step, station, entry, estimate, sigma, truth.
void write_registration_csv(const PictureReport& report, const std::filesystem::path& path);
/// Run `run`'s registration for picture.json: per station, each entry's last estimate, σ and
/// truth, whether all end within 2σ, and the round from which they stay so.
nlohmann::json registration_json(const PictureRunResult& run, double time_step_s);

}  // namespace skyfuse::harness
