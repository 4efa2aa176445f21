// skyfuse: the harness. Parses the command line and hands over to one command.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "commands/bench_command.hpp"
#include "commands/certs_command.hpp"
#include "commands/demo_command.hpp"
#include "commands/feed_command.hpp"
#include "commands/reproduce_command.hpp"
#include "commands/run_command.hpp"
#include "commands/soak_command.hpp"
#include "commands/sweep_command.hpp"
#include "commands/view_command.hpp"
#include "run/execute_run.hpp"
#include "run/lockstep_driver.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/shutdown.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse::harness;
  CLI::App app{"skyfuse: ground-station aircraft tracking, central vs peer-to-peer fusion"};
  app.require_subcommand(1);
  SweepOptions sweep;
  RunOptions run;
  DemoOptions demo;
  BenchOptions bench;
  SoakOptions soak;
  CertsOptions certs;
  ReproduceOptions reproduce;
  ViewOptions view;
  FeedOptions feed;
  add_sweep_command(app, sweep);
  add_run_command(app, run);
  add_feed_command(app, feed);
  add_demo_command(app, demo);
  add_bench_command(app, bench);
  add_soak_command(app, soak);
  add_certs_command(app, certs);
  add_reproduce_command(app, reproduce);
  add_view_command(app, view);
  // CLI11 takes a word that names no command for a stray argument and answers "A subcommand is
  // required": say which word, and what the commands are.
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const CLI::App* command : app.get_subcommands({})) {
      known = known || command->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "skyfuse: unknown command '%s' (commands: %s); see skyfuse --help\n",
                   argv[1], names.c_str());
      return 2;
    }
  }
  CLI11_PARSE(app, argc, argv);

  // Line-buffered even into a file or pipe, so that tables and child messages keep their order.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  skyfuse::transport::install_shutdown_handlers();
  try {
    if (app.got_subcommand("sweep")) return run_sweep(sweep);
    if (app.got_subcommand("run")) return run_run(run);
    if (app.got_subcommand("demo")) return run_demo(demo);
    if (app.got_subcommand("bench")) return run_bench(bench);
    if (app.got_subcommand("soak")) return run_soak(soak);
    if (app.got_subcommand("certs")) return run_certs(certs);
    if (app.got_subcommand("reproduce")) return run_reproduce(reproduce);
    if (app.got_subcommand("view")) return run_view(view);
    if (app.got_subcommand("feed")) return run_feed(feed);
  } catch (const RunStoppedEarly& e) {
    std::fprintf(stderr, "skyfuse: run stopped early (%s): %s\n",
                 std::string(to_string(e.cause())).c_str(), e.what());
    if (!e.host_verdict().empty()) {
      std::fprintf(stderr, "skyfuse: %s\n", e.host_verdict().c_str());
    }
    return exit_status_of(e);
  } catch (const RunAborted& e) {
    std::fprintf(stderr, "skyfuse: run aborted: %s\n", e.what());
    return exit_status_of(e);
  } catch (const skyfuse::ConfigError& e) {
    std::fprintf(stderr, "skyfuse: error: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "skyfuse: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skyfuse: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
