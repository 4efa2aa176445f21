// skyfuse-echo: the other half of the bare Fast DDS lock-step floors that `skyfuse bench`
// measures. It answers every Tick with an Echo, through the same participant setup and QoS as
// a station, and does nothing else: the round rate a skyfuse run could reach at best. With
// --all-to-all M it first sends an increment-sized sample on the increment topic and waits for
// those of the M - 1 other echoes, as a station does: the cost of the peer-to-peer exchange
// itself, without estimation, center or recorder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <optional>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/shutdown.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse;
  CLI::App app{"skyfuse-echo: answers ticks; the bare lock-step floor of skyfuse bench"};
  int id = 0;
  int domain = 0;
  std::uint64_t run_id = 1;
  std::optional<std::string> qos;
  double discovery_timeout_s = 30.0;
  double timeout_s = 30.0;
  int all_to_all = 0;
  app.add_option("--id", id, "Node id (>= 1)")
      ->required()
      ->check(options::whole_number_at_least(1));
  app.add_option("--all-to-all", all_to_all,
                 "Before each answer, send an increment-sized sample to the other M - 1 echoes "
                 "and wait for theirs")
      ->type_name("M")
      ->check(options::whole_number_at_least(1));
  app.add_option("--domain", domain, "DDS domain id")
      ->check(options::whole_number_in(0, transport::kMaxDomainId));
  app.add_option("--run-id", run_id, "Run id");
  app.add_option("--qos", qos, "Fast DDS XML profiles")->check(CLI::ExistingFile);
  app.add_option("--discovery-timeout", discovery_timeout_s,
                 "Seconds to wait until the commander (and with --all-to-all the other echoes) "
                 "matched, and then for the first tick")
      ->check(options::positive_number())
      ->capture_default_str();
  app.add_option("--idle-timeout", timeout_s, "Seconds without a tick before giving up")
      ->check(options::positive_number())
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  spdlog::set_pattern(fmt::format("[echo {}] %^%l%$: %v", id));
  transport::install_shutdown_handlers();

  return options::run_node([&]() -> int {
    transport::NodeConfig config;
    config.domain_id = domain;
    config.name = fmt::format("skyfuse-echo-{}", id);
    if (qos) config.qos_file = *qos;
    transport::DdsNode node(config);
    transport::NodePresence presence(node, run_id, id);
    auto ticks = node.make_reader<wire::Tick>();
    auto echoes = node.make_writer<wire::Echo>();
    // Only with --all-to-all: a reader or writer nobody matches would still cost discovery.
    std::optional<transport::Reader<wire::InformationIncrement>> peers_in;
    std::optional<transport::Writer<wire::InformationIncrement>> peers_out;
    transport::ReaderWaitSet wait_set;
    wait_set.attach(ticks);
    if (all_to_all > 0) {
      peers_in.emplace(node.make_reader<wire::InformationIncrement>());
      peers_out.emplace(node.make_writer<wire::InformationIncrement>());
      wait_set.attach(*peers_in);
    }
    const auto peers_matched = [&] {
      return all_to_all == 0 ||
             (peers_in->matched() >= all_to_all && peers_out->matched() >= all_to_all);
    };
    const auto joined = transport::join_run(
        presence, [&] { return ticks.matched() >= 1 && echoes.matched() >= 1 && peers_matched(); },
        [&] {
          return fmt::format("tick writer {}/1, echo reader {}/1, peers {}/{} and {}/{}",
                             ticks.matched(), echoes.matched(), peers_in ? peers_in->matched() : 0,
                             all_to_all, peers_out ? peers_out->matched() : 0, all_to_all);
        },
        std::chrono::milliseconds(static_cast<long>(discovery_timeout_s * 1000)));
    if (const auto code = transport::exit_code_unless_joined(
            joined, presence, fmt::format("echo {}", id), run_id, discovery_timeout_s)) {
      return *code;
    }
    // The commander ticks once every echo has joined; those that joined first wait for the
    // others' discovery, so the first tick may take as long as discovery does.
    auto last_tick = std::chrono::steady_clock::now();
    double tick_wait_s = std::max(discovery_timeout_s, timeout_s);
    wire::Echo echo;
    echo.run_id(run_id);
    echo.node_id(id);
    wire::InformationIncrement sample;  // zeros: only its size and its path matter
    sample.run_id(run_id);
    sample.station_id(id);
    // Lock-step: every peer sample in flight is of the current round, though it may come
    // before this echo's tick; one step and its count suffice.
    std::uint32_t heard_step = 0;
    int heard = 0;
    // Ticked and sample sent, the peers' samples not all in yet. (Not a std::optional: g++ 12
    // then warns of a maybe-uninitialised payload.)
    bool waiting = false;
    std::uint32_t waiting_step = 0;
    while (!transport::shutdown_requested()) {
      wire::Tick tick;
      while (ticks.take(tick)) {
        if (tick.run_id() != run_id) continue;
        if (tick.stop()) return options::kExitOk;
        last_tick = std::chrono::steady_clock::now();
        tick_wait_s = timeout_s;
        if (all_to_all == 0) {
          echo.step(tick.step());
          echoes.write(echo);
          continue;
        }
        sample.step(tick.step());
        peers_out->write(sample);
        waiting = true;
        waiting_step = tick.step();
      }
      if (all_to_all > 0) {
        wire::InformationIncrement received;
        while (peers_in->take(received)) {
          if (received.run_id() != run_id || received.station_id() == id) continue;
          if (received.step() != heard_step) {
            heard_step = received.step();
            heard = 0;
          }
          ++heard;
        }
        const int peers = all_to_all - 1;
        if (waiting && (peers == 0 || (heard_step == waiting_step && heard >= peers))) {
          echo.step(waiting_step);
          echoes.write(echo);
          waiting = false;
        }
      }
      if (std::chrono::steady_clock::now() - last_tick >
          std::chrono::duration<double>(tick_wait_s)) {
        spdlog::error("no tick for {} s", tick_wait_s);
        return options::kExitIdleTimeout;
      }
      wait_set.wait(std::chrono::milliseconds(50));
    }
    return 128 + transport::shutdown_signal();
  });
}
