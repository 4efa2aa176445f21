#include "secure_probe.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>

#include "forged_increment.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/shutdown.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::rogue {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kSendPeriod = std::chrono::milliseconds(10);
constexpr std::uint32_t kStepAhead = 2;

// Samples that pass every content check, so that only who sent them can keep them out (the
// increment: forged_increment.hpp).
wire::Measurement plausible_measurement(std::uint64_t run, std::uint32_t step, int station) {
  wire::Measurement s;
  s.run_id(run);
  s.step(step);
  s.station_id(station);
  s.sensor(std::string(RangeAzimuthElevation<kKinematicsDim>::kKind));
  s.z() = {1200.0, 0.4, 0.2};
  s.noise() = {0.01, 0.0, 0.0, 1e-4, 0.0, 1e-4};
  s.station_position() = {0.0, 0.0, 0.0};
  return s;
}

// The access control refused a writer: the answer to "may this identity publish here?".
class PublishRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename T>
transport::Writer<T> writer_or_refusal(transport::DdsNode& node, const ProbeOptions& options) {
  try {
    return node.make_writer<T>();
  } catch (const transport::DdsError&) {
    if (!options.security()) throw;
    throw PublishRefused(fmt::format(
        "identity '{}' may not publish on {}: DDS-Security access control refused the writer "
        "(create_datawriter failed)",
        options.identity, transport::TopicTraits<T>::kName));
  }
}

// One topic as the probe uses it: it writes in the victim's name, and listens where its own
// grant lets it subscribe.
template <typename T>
struct ProbeChannel {
  ProbeChannel(transport::DdsNode& node, const ProbeOptions& options)
      : writer(writer_or_refusal<T>(node, options)) {
    try {
      reader = std::make_unique<transport::Reader<T>>(node.make_reader<T>());
    } catch (const transport::DdsError&) {
      if (!options.security()) throw;  // only access control may refuse a reader
    }
  }

  // Remote readers matched now: the count includes this participant's own reader.
  int remote_readers() const { return writer.matched() - (reader ? 1 : 0); }

  void listen() {
    most_matched = std::max(most_matched, remote_readers());
    if (!reader) return;
    T sample;
    transport::WriterId from;
    while (reader->take(sample, &from)) {
      if (from != writer.id()) ++heard;
    }
  }

  void report(const char* topic) const {
    fmt::print("probe sent {} {}\n", topic, sent);
    if (reader) {
      fmt::print("probe heard {} {}\n", topic, heard);
    } else {
      fmt::print("probe heard {} none: its identity may not subscribe\n", topic);
    }
    fmt::print("probe matched {} readers {}\n", topic, most_matched);
  }

  transport::Writer<T> writer;
  std::unique_ptr<transport::Reader<T>> reader;  ///< none: the identity may not subscribe
  int sent = 0;
  int heard = 0;
  int most_matched = 0;  ///< remote readers, at most, at any one time
};

void probe(transport::DdsNode& node, const ProbeOptions& options, const ProbeTarget& target) {
  // Writers first: for an identity without a publish grant, their refusal is the answer.
  ProbeChannel<wire::InformationIncrement> increments(node, options);
  ProbeChannel<wire::Measurement> measurements(node, options);
  auto ticks = node.make_reader<wire::Tick>();
  transport::ReaderWaitSet wait_set;
  wait_set.attach(ticks);
  if (increments.reader) wait_set.attach(*increments.reader);
  if (measurements.reader) wait_set.attach(*measurements.reader);

  std::optional<std::uint32_t> latest_tick;
  const auto end = Clock::now() + std::chrono::duration<double>(target.duration_s);
  auto next_send = Clock::now();
  while (!transport::shutdown_requested() && Clock::now() < end) {
    wire::Tick tick;
    while (ticks.take(tick)) {
      if (tick.run_id() == target.run_id) {
        latest_tick = std::max(latest_tick.value_or(0), tick.step());
      }
    }
    increments.listen();
    measurements.listen();

    // It speaks for the step it last heard ticked, or - before any tick, or never hearing one -
    // for step 2, a step just ahead that every receiver accepts once it gets there. Either way
    // every receiver has by then bound the victim's id to the real station (at step 0), so a
    // sample that arrives is refused and counted, never fused, whatever the timing.
    if (Clock::now() >= next_send) {
      const std::uint32_t step = std::max(latest_tick.value_or(0), kStepAhead);
      increments.writer.write(
          plausible_increment(target.run_id, step, target.victim, target.state_dim));
      measurements.writer.write(plausible_measurement(target.run_id, step, target.victim));
      ++increments.sent;
      ++measurements.sent;
      next_send = Clock::now() + kSendPeriod;
    }
    wait_set.wait(kSendPeriod);
  }

  fmt::print("probe identity {}\n",
             options.secure_dir ? fmt::format("{} from {}", options.identity, *options.secure_dir)
                                : std::string("none (no DDS-Security)"));
  fmt::print("probe heard ticks up to step {}\n",
             latest_tick ? std::to_string(*latest_tick) : std::string("none"));
  increments.report("increment");
  measurements.report("measurement");
}

}  // namespace

std::optional<transport::SecurityConfig> ProbeOptions::security() const {
  if (!secure_dir) return std::nullopt;
  return transport::SecurityConfig{*secure_dir, identity};
}

void add_probe_options(CLI::App& app, ProbeOptions& o) {
  app.add_option("--secure", o.secure_dir,
                 "Join with DDS-Security, with an identity from this `skyfuse certs` folder (the "
                 "run's, or another CA's)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--identity", o.identity, "Identity in the --secure folder: station-N, observer")
      ->capture_default_str();
  app.add_flag("--probe", o.probe,
               "Speak for the victim with well-formed samples every 10 ms and count what is heard "
               "on the increment and measurement topics, until interrupted or --timeout");
}

int run_probe(const ProbeOptions& options, const ProbeTarget& target) {
  transport::NodeConfig config;
  config.domain_id = target.domain;
  config.name = "skyfuse-rogue";
  config.security = options.security();
  config.network = target.network;
  transport::DdsNode node(config);
  try {
    probe(node, options, target);
    return options::kExitOk;
  } catch (const PublishRefused& e) {
    spdlog::error("{}", e.what());
    return kExitPublishRefused;
  }
}

}  // namespace skyfuse::rogue
