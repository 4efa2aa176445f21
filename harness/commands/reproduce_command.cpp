#include "commands/reproduce_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <stdexcept>

#include "reproduce/papers.hpp"
#include "skyfuse/options/number_checks.hpp"

namespace skyfuse::harness {
namespace {

struct Paper {
  const char* name;
  Reproduction (*run)(const ReproduceSettings&);
};
constexpr Paper kPapers[] = {{"paper000", reproduce_paper000},
                             {"paper000-imm", reproduce_paper000_imm},
                             {"paper001", reproduce_paper001},
                             {"paper002", reproduce_paper002},
                             {"paper003", reproduce_paper003}};

}  // namespace

void add_reproduce_command(CLI::App& app, ReproduceOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "reproduce",
      "A paper's headline results next to this run's; writes OUT/reproduce.json, CSV and PNG");
  std::string names;
  for (const Paper& p : kPapers) names += (names.empty() ? "" : ", ") + std::string(p.name);
  cmd->add_option("paper", options.paper, "Which paper: " + names)->required();
  cmd->add_option("--runs", options.runs,
                  "Monte-Carlo runs, test paths for paper001 (default: the paper's)")
      ->check(options::whole_number_in(1, 1000000));
  cmd->add_option("--seed", options.seed, "Override the seed");
  cmd->add_option("--out", options.out_dir, "Output folder (default: results/reproduce/PAPER)");
  cmd->add_option("--threads", options.threads, "Worker threads (default: one per core)")
      ->check(options::whole_number_in(0, 1024));
  cmd->add_flag("!--no-plot", options.plot, "Skip the PNG plots");
  cmd->add_option("--data", options.data_dir,
                  "Shipped data, e.g. paper001/ec.lstm (default: the source tree's data/)")
      ->check(CLI::ExistingDirectory);
}

int run_reproduce(const ReproduceOptions& options) {
  for (const Paper& p : kPapers) {
    if (options.paper != p.name) continue;
    ReproduceSettings settings;
    settings.runs = options.runs;
    settings.seed = options.seed;
    settings.out_dir = options.out_dir.empty()
                           ? std::filesystem::path("results/reproduce") / options.paper
                           : std::filesystem::path(options.out_dir);
    settings.threads = options.threads;
    settings.plot = options.plot;
    settings.data_dir = options.data_dir.empty() ? std::filesystem::path(SKYFUSE_DATA_DIR)
                                                 : std::filesystem::path(options.data_dir);
    std::filesystem::create_directories(settings.out_dir);
    const Reproduction reproduction = p.run(settings);
    print_claims(reproduction, stdout);
    const auto json = settings.out_dir / "reproduce.json";
    write_reproduce_json(reproduction, json);
    fmt::print("wrote {}\n", json.string());
    return reproduction.all_hold() ? 0 : 1;
  }
  std::string names;
  for (const Paper& p : kPapers) names += (names.empty() ? "" : ", ") + std::string(p.name);
  throw std::invalid_argument(
      fmt::format("reproduce: unknown paper '{}' (known: {})", options.paper, names));
}

}  // namespace skyfuse::harness
