// skyfuse-echo: the other half of the bare Fast DDS lock-step floor that `skyfuse bench`
// measures. It answers every Tick with an Echo, through the same participant setup and QoS as
// a station, and does nothing else: the round rate a skyfuse run could reach at best.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "skyfuse/transport/node_options.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/shutdown.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse;
  CLI::App app{"skyfuse-echo: answers ticks; the bare lock-step floor of skyfuse bench"};
  int id = 0;
  int domain = 0;
  std::uint64_t run_id = 1;
  std::optional<std::string> qos;
  double timeout_s = 30.0;
  app.add_option("--id", id, "Node id (>= 1)")->required()->check(CLI::PositiveNumber);
  app.add_option("--domain", domain, "DDS domain id")
      ->check(CLI::Range(0, transport::kMaxDomainId));
  app.add_option("--run-id", run_id, "Run id");
  app.add_option("--qos", qos, "Fast DDS XML profiles")->check(CLI::ExistingFile);
  app.add_option("--idle-timeout", timeout_s, "Seconds without a tick before giving up");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_pattern(fmt::format("[echo {}] %^%l%$: %v", id));
  transport::install_shutdown_handlers();

  try {
    transport::NodeConfig config;
    config.domain_id = domain;
    config.name = fmt::format("skyfuse-echo-{}", id);
    if (qos) config.qos_file = *qos;
    transport::DdsNode node(config);
    transport::NodePresence presence(node, run_id, id);
    auto ticks = node.make_reader<wire::Tick>();
    auto echoes = node.make_writer<wire::Echo>();
    transport::ReaderWaitSet wait_set;
    wait_set.attach(ticks);
    const auto joined = transport::join_run(
        presence, [&] { return ticks.matched() >= 1 && echoes.matched() >= 1; },
        [&] {
          return fmt::format("tick writer {}/1, echo reader {}/1", ticks.matched(),
                             echoes.matched());
        },
        std::chrono::milliseconds(static_cast<long>(timeout_s * 1000)));
    if (const auto code = transport::exit_code_unless_joined(
            joined, presence, fmt::format("echo {}", id), run_id, timeout_s)) {
      return *code;
    }
    auto last_tick = std::chrono::steady_clock::now();
    wire::Echo echo;
    echo.run_id(run_id);
    echo.node_id(id);
    while (!transport::shutdown_requested()) {
      wire::Tick tick;
      while (ticks.take(tick)) {
        if (tick.run_id() != run_id) continue;
        if (tick.stop()) return transport::kExitOk;
        echo.step(tick.step());
        echoes.write(echo);
        last_tick = std::chrono::steady_clock::now();
      }
      if (std::chrono::steady_clock::now() - last_tick > std::chrono::duration<double>(timeout_s)) {
        spdlog::error("no tick for {} s", timeout_s);
        return transport::kExitIdleTimeout;
      }
      wait_set.wait(std::chrono::milliseconds(50));
    }
    return 128 + transport::shutdown_signal();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return transport::kExitError;
  }
}
