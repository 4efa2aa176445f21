// skyfuse-rogue: attacks a running skyfuse run from inside its DDS domain, to show that the
// network refuses what it must. At each chosen step it publishes, on the real increment and
// measurement topics, one sample of every malformed kind a receiver checks for:
//   wrong_run     another run's id
//   stale_step    the step before the current one
//   future_step   1000 steps ahead (fault_step.hpp)
//   unknown_station  station id 999
//   duplicate     a well-formed sample for a real station, from the wrong writer
//   non_finite    a NaN in dQ / in z
//   not_positive  dQ with a negative direction / R with a zero variance
//   out_of_range  a negative range (measurements only); in a TDOA run, a range difference
//                 beyond any plausible one, and an increment with information outside
//                 [dx, dy, d_t1]
//   wrong_site    the victim's id from another station position (measurements only)
// Every other measurement claims the victim's own site and sensor kind (from the scenario,
// --scenario: a radar's three components, or a TDOA receiver's one), so that it is refused for
// its one fault. Against a run of the tree exchange (--tree K: its fanout) it sends partial
// sums instead of increments, on each of the exchange's channels (forged_partial.hpp), and adds
// the partial sums' own kinds:
//   wrong_cluster a contribution from another cluster, a sum counting a station of another
//                 cluster, a total from a member that does not aggregate
//   overlap       a sum counting one station twice
// Against a run of many aircraft (--picture) it sends forged picture scans instead
// (forged_scan.hpp), of the kinds a scan can carry.
// It prints how many samples of each kind it sent, one line per topic and kind.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "fault_step.hpp"
#include "forged_increment.hpp"
#include "forged_partial.hpp"
#include "forged_scan.hpp"
#include "secure_probe.hpp"
#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/options/scenario_option.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/shutdown.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace {

using namespace skyfuse;

struct Attack {
  DropKind kind;
  std::uint64_t run_id;
  std::uint32_t step;
  int station;
};

// The malformed variants to send when the harness ticks step k of run `run`.
std::vector<Attack> attacks_at(std::uint64_t run, std::uint32_t k, int victim) {
  // The impersonation first: its kind depends on timing (fault_step.hpp).
  const auto at = [&](DropKind kind, std::uint64_t r, int station) {
    return Attack{kind, r, rogue::fault_step(kind, k), station};
  };
  return {
      at(DropKind::kDuplicate, run, victim),   at(DropKind::kWrongRun, run ^ 0x5a5a5a5aULL, victim),
      at(DropKind::kStaleStep, run, victim),   at(DropKind::kFutureStep, run, victim),
      at(DropKind::kUnknownStation, run, 999), at(DropKind::kNonFinite, run, victim),
      at(DropKind::kNotPositive, run, victim), at(DropKind::kOutOfRange, run, victim),
      at(DropKind::kWrongSite, run, victim)};
}

// The victim as the scenario has it: where it stands, whether it is a TDOA receiver, and the
// state its increments are of (the scenario's motion model's).
struct Victim {
  Vector3 site = Vector3::Zero();  // an id that is no station's stands nowhere
  bool tdoa = false;
  int state_dim = 0;
};

// Kinds that only a measurement can carry (a TDOA increment can be out of range as well).
bool measurement_only(DropKind kind, const Victim& victim) {
  return kind == DropKind::kWrongSite || (kind == DropKind::kOutOfRange && !victim.tdoa);
}

wire::InformationIncrement increment_for(const Attack& a, const Victim& victim) {
  // Well-formed but for the one fault the attack carries: a plausible range-like information
  // along x (inside a TDOA increment's [dx, dy, d_t1] block too), about a prior with P = I.
  wire::InformationIncrement s =
      rogue::plausible_increment(a.run_id, a.step, a.station, victim.state_dim);
  if (a.kind == DropKind::kNonFinite) s.delta_information()[10] = std::nan("");
  if (a.kind == DropKind::kNotPositive) s.delta_information()[0] = -1.0;
  if (a.kind == DropKind::kOutOfRange) s.delta_information().back() = 1e-4;  // dQ(n-1, n-1)
  return s;
}

wire::Measurement measurement_for(const Attack& a, const Victim& victim) {
  wire::Measurement s;
  s.run_id(a.run_id);
  s.step(a.step);
  s.station_id(a.station);
  s.station_position() = {victim.site.x(), victim.site.y(), victim.site.z()};
  if (a.kind == DropKind::kWrongSite) s.station_position()[0] += 10.0;
  if (victim.tdoa) {
    s.sensor(std::string(RangeDifferenceSensor<kKinematicsDim>::kKind));
    s.z() = {150.0};
    s.noise() = {0.16};
    if (a.kind == DropKind::kNonFinite) s.z()[0] = std::numeric_limits<double>::infinity();
    if (a.kind == DropKind::kNotPositive) s.noise()[0] = 0.0;
    if (a.kind == DropKind::kOutOfRange) s.z()[0] = 2.0 * kMaxRangeM;
    return s;
  }
  s.sensor(std::string(RangeAzimuthElevation<kKinematicsDim>::kKind));
  s.z() = {1500.0, 0.5, 0.3};
  s.noise() = {1.0, 0.0, 0.0, 1e-4, 0.0, 1e-4};  // upper triangle of diag(1, 1e-4, 1e-4)
  if (a.kind == DropKind::kNonFinite) s.z()[1] = std::numeric_limits<double>::infinity();
  if (a.kind == DropKind::kNotPositive) s.noise()[5] = 0.0;
  if (a.kind == DropKind::kOutOfRange) s.z()[0] = -5.0;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skyfuse-rogue: publishes malformed samples into a running run (a test tool)"};
  int domain = 0;
  std::uint64_t run_id = 0;
  std::set<std::uint32_t> steps = {5, 10, 15};
  int victim = 2;
  int stations = 1;
  double timeout_s = 60.0;
  app.add_option("--domain", domain, "DDS domain id of the run")
      ->check(skyfuse::options::whole_number_in(0, transport::kMaxDomainId));
  app.add_option("--run-id", run_id, "Id of the run to attack")->required();
  app.add_option("--stations", stations, "Station readers to reach before attacking")
      ->check(skyfuse::options::whole_number_at_least(1));
  app.add_option("--victim", victim, "A real station id to impersonate");
  app.add_option("--at-steps", steps,
                 "Steps (>= 1) at which to attack; an attack waits for the first tick after its "
                 "step if not every reader has matched by then")
      ->capture_default_str();
  app.add_option("--timeout", timeout_s, "Seconds to wait for the run's ticks");
  int tree_fanout = 0;
  app.add_option("--tree", tree_fanout,
                 "The run exchanges in a tree of this fanout: attack its partial sums instead of "
                 "increments")
      ->check(skyfuse::options::whole_number_at_least(2));
  bool picture = false;
  app.add_flag("--picture", picture,
               "The run is of many aircraft: attack its picture scans instead (the victim a "
               "radar)");
  std::string scenario_path;
  options::add_scenario_option(app, scenario_path);
  rogue::ProbeOptions probe;
  rogue::add_probe_options(app, probe);
  options::NetworkOptions network;
  options::add_network_options(app, network);
  CLI11_PARSE(app, argc, argv);
  spdlog::set_pattern("[rogue] %^%l%$: %v");
  transport::install_shutdown_handlers();
  if (steps.count(0) != 0) {
    spdlog::error("--at-steps: step 0 has no stale step before it");
    return options::kExitUsage;
  }

  try {
    const Scenario scenario = load_scenario_or_default(scenario_path);
    const int state_dim = find_motion_model(scenario.filter.motion_model.kind)->state_dim;
    if (probe.probe) {
      return rogue::run_probe(probe, {domain, run_id, victim, state_dim, timeout_s, network});
    }
    Victim victim_config;
    victim_config.state_dim = state_dim;
    for (const StationConfig& s : scenario.stations) {
      if (s.id != victim) continue;
      victim_config.site = s.position_m;
      victim_config.tdoa = s.sensor.kind == RangeDifferenceSensor<kKinematicsDim>::kKind;
    }
    transport::NodeConfig config;
    config.domain_id = domain;
    config.name = "skyfuse-rogue";
    config.security = probe.security();
    config.network = network;
    transport::DdsNode node(config);
    auto ticks = node.make_reader<wire::Tick>();
    auto increments = node.make_writer<wire::InformationIncrement>();
    auto measurements = node.make_writer<wire::Measurement>();
    // Against a tree: cluster 0's and cluster 1's channels, as the run's stations derive them.
    std::optional<ClusterLayout> layout;
    std::map<std::string, transport::Writer<wire::PartialSum>> partials;
    if (tree_fanout != 0) {
      RunOverrides overrides;
      overrides.stations = stations;
      layout.emplace(sorted_ascending(make_run_plan(scenario, overrides).participant_ids()),
                     static_cast<std::size_t>(tree_fanout));
      if (layout->clusters() < 2) {
        spdlog::error("--tree {}: {} stations make one cluster; the attacks need two", tree_fanout,
                      stations);
        return options::kExitUsage;
      }
      for (const std::string& partition : rogue::partial_attack_partitions()) {
        partials.emplace(partition, node.make_writer<wire::PartialSum>({partition}));
      }
    }
    std::optional<transport::Writer<wire::PictureScan>> scans;
    if (picture) scans.emplace(node.make_writer<wire::PictureScan>());
    auto all_matched = [&] {
      // A run of many aircraft: every station and the center read the scans.
      if (scans) return scans->matched() >= stations + 1;
      if (measurements.matched() < 1) return false;
      if (!layout) return increments.matched() >= stations;
      for (const auto& [partition, writer] : partials) {
        if (writer.matched() < rogue::receivers_of(partition, *layout)) return false;
      }
      return true;
    };
    // What all_matched() counts, for the log, and the participants known: they tell a reader
    // never discovered (its process unseen) from one whose process was seen but did not match.
    auto matched_readers = [&] {
      const std::string readers =
          scans ? fmt::format("{} of {} scan readers", scans->matched(), stations + 1)
                : fmt::format("{} measurement readers, {} increment readers",
                              measurements.matched(), increments.matched());
      return fmt::format("{}; {} participants known", readers, node.participants_known());
    };
    transport::ReaderWaitSet wait_set;
    wait_set.attach(ticks);
    DropCounts sent_increments{};
    DropCounts sent_partials{};
    DropCounts sent_measurements{};
    DropCounts sent_scans{};
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    std::set<std::uint32_t> left = steps;
    while (!left.empty()) {
      if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
      if (std::chrono::steady_clock::now() > give_up) {
        spdlog::error("no tick of run {} for steps {} within {} s", run_id, fmt::join(left, ", "),
                      timeout_s);
        return options::kExitIdleTimeout;
      }
      // Attack at the newest tick: on a loaded machine this process may wake several rounds
      // late, and samples timed against an old tick would land outside the receivers' window.
      std::optional<std::uint32_t> newest;
      wire::Tick tick;
      while (ticks.take(tick)) {
        if (tick.run_id() == run_id && !tick.stop())
          newest = std::max(newest.value_or(0), tick.step());
      }
      if (newest && !left.empty() && *left.begin() <= *newest) {
        // Every reader must be matched, or a sample could miss one and the counts not add up.
        // On a loaded machine the run may reach the step before discovery has matched them all:
        // the attack waits for the first tick after that (a later step, one attack a tick), so
        // that every attack asked for is sent; the run must last long enough for it.
        if (!all_matched()) {
          spdlog::warn(
              "step {}: not every reader matched yet ({}); the attack planned for step "
              "{} waits",
              *newest, matched_readers(), *left.begin());
          wait_set.wait(std::chrono::milliseconds(20));
          continue;
        }
        left.erase(left.begin());
        if (scans) {
          for (const rogue::ScanAttack& a : rogue::scan_attacks_at(run_id, *newest, victim)) {
            scans->write(a.sample);
            ++sent_scans[static_cast<std::size_t>(a.kind)];
          }
          wait_set.wait(std::chrono::milliseconds(20));
          continue;
        }
        if (layout) {
          for (rogue::PartialAttack& a :
               rogue::partial_attacks_at(run_id, *newest, *layout, state_dim)) {
            partials.at(a.partition).write(a.sample);
            ++sent_partials[static_cast<std::size_t>(a.kind)];
          }
        }
        for (const Attack& a : attacks_at(run_id, *newest, victim)) {
          const auto kind = static_cast<std::size_t>(a.kind);
          if (!layout && !measurement_only(a.kind, victim_config)) {
            increments.write(increment_for(a, victim_config));
            ++sent_increments[kind];
          }
          measurements.write(measurement_for(a, victim_config));
          ++sent_measurements[kind];
        }
      }
      wait_set.wait(std::chrono::milliseconds(20));
    }
    increments.wait_acknowledged(std::chrono::seconds(5));
    for (auto& [partition, writer] : partials) writer.wait_acknowledged(std::chrono::seconds(5));
    measurements.wait_acknowledged(std::chrono::seconds(5));
    if (scans) scans->wait_acknowledged(std::chrono::seconds(5));
    for (std::size_t i = 0; i < kDropKinds; ++i) {
      const auto kind = to_string(static_cast<DropKind>(i));
      if (sent_increments[i] != 0) fmt::print("sent increment {} {}\n", kind, sent_increments[i]);
      if (sent_partials[i] != 0) fmt::print("sent partial sum {} {}\n", kind, sent_partials[i]);
      if (sent_scans[i] != 0) fmt::print("sent picture scan {} {}\n", kind, sent_scans[i]);
      if (sent_measurements[i] != 0) {
        fmt::print("sent measurement {} {}\n", kind, sent_measurements[i]);
      }
    }
    return options::kExitOk;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return options::kExitError;
  }
}
