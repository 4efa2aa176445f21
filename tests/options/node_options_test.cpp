// The options every node process shares, as the command line sets them.
#include "skyfuse/options/node_options.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <string>
#include <vector>

namespace skyfuse::options {
namespace {

using namespace std::chrono_literals;

NodeOptions parsed(std::vector<std::string> args) {
  CLI::App app;
  NodeOptions options;
  add_node_options(app, options);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return options;
}

TEST(NodeOptions, TheWaitForTheFirstTickIsDiscoverysWhenThatIsLonger) {
  // Nodes that joined first wait while the others still discover each other: at M = 64 that
  // took longer than the idle timeout.
  const NodeOptions big = parsed({"--idle-timeout", "30", "--discovery-timeout", "128"});
  EXPECT_EQ(big.idle_timeout(), 30s);
  EXPECT_EQ(big.first_tick_timeout(), 128s);
  // A short discovery does not shorten the first wait below the idle timeout.
  const NodeOptions small = parsed({"--idle-timeout", "30", "--discovery-timeout", "5"});
  EXPECT_EQ(small.first_tick_timeout(), 30s);
}

// What the harness hands a child is what the child reads: every field, bit for bit.
TEST(NodeOptions, ArgumentsParseBackToTheSameOptions) {
  NodeOptions o;
  o.scenario_path = "";  // the embedded scenario: --scenario checks that a file exists
  o.domain = 171;
  o.run_id = 0x0123456789abcdefULL;
  o.overrides.stations = 5;
  o.overrides.steps = 321;
  o.overrides.speed_kmh = 100.0 / 3.6 * 3.6 + 1e-13;  // not a short decimal
  o.overrides.mc_run = 7;
  o.discovery_timeout_s = 12.345;
  o.idle_timeout_s = 0.1 + 0.2;
  o.realtime_deadline_ms = 15.5;
  o.round_deadline_ms = 250.0;
  o.loss.probability = 0.1;
  o.loss.seed = 99;
  o.loss.first_step = 10;
  o.loss.end_step = 20;
  o.best_effort = true;
  o.delay.delay_ms = 10.0;
  o.delay.jitter_ms = 0.1 + 0.7;
  o.refusion_lag = 3;
  o.gate = NisGate::at_probability(0.9999);
  o.network.interface_address = "10.77.0.3";
  o.network.discovery_server = Ipv4Endpoint{"10.77.0.254", 11811};
  o.log_level = "warn";
  o.asterix_out = "239.255.86.0:8600";
  o.asterix_in = "239.255.86.1:8601";
  o.asterix_in_wait_ms = 2500.5;

  const NodeOptions back = parsed(to_arguments(o));
  EXPECT_EQ(back.scenario_path, o.scenario_path);
  EXPECT_EQ(back.domain, o.domain);
  EXPECT_EQ(back.run_id, o.run_id);
  EXPECT_EQ(back.overrides.stations, o.overrides.stations);
  EXPECT_EQ(back.overrides.steps, o.overrides.steps);
  EXPECT_EQ(back.overrides.speed_kmh, o.overrides.speed_kmh);  // exactly: the same bits
  EXPECT_EQ(back.overrides.mc_run, o.overrides.mc_run);
  EXPECT_EQ(back.discovery_timeout_s, o.discovery_timeout_s);
  EXPECT_EQ(back.idle_timeout_s, o.idle_timeout_s);
  EXPECT_EQ(back.realtime_deadline_ms, o.realtime_deadline_ms);
  EXPECT_EQ(back.round_deadline_ms, o.round_deadline_ms);
  EXPECT_EQ(back.loss.probability, o.loss.probability);
  EXPECT_EQ(back.loss.seed, o.loss.seed);
  EXPECT_EQ(back.loss.first_step, o.loss.first_step);
  EXPECT_EQ(back.loss.end_step, o.loss.end_step);
  EXPECT_EQ(back.best_effort, o.best_effort);
  EXPECT_EQ(back.delay.delay_ms, o.delay.delay_ms);
  EXPECT_EQ(back.delay.jitter_ms, o.delay.jitter_ms);
  EXPECT_EQ(back.refusion_lag, o.refusion_lag);
  EXPECT_EQ(back.gate.probability(), o.gate.probability());
  EXPECT_EQ(back.network, o.network);
  EXPECT_EQ(back.log_level, o.log_level);
  EXPECT_EQ(back.asterix_out, o.asterix_out);
  EXPECT_EQ(back.asterix_in, o.asterix_in);
  EXPECT_EQ(back.asterix_in_wait_ms, o.asterix_in_wait_ms);

  // Defaults travel as defaults: nothing set, nothing invented.
  const NodeOptions plain = parsed(to_arguments(NodeOptions{}));
  EXPECT_FALSE(plain.overrides.stations.has_value());
  EXPECT_FALSE(plain.qos_file.has_value());
  EXPECT_FALSE(plain.gate.enabled());
  EXPECT_EQ(plain.loss.probability, 0.0);
  EXPECT_FALSE(plain.delay.enabled());
  EXPECT_EQ(plain.network, NetworkOptions{});
  EXPECT_EQ(plain.network.interface_address, "127.0.0.1");
  EXPECT_TRUE(plain.asterix_in.empty());
}

// The delay draws with the loss's seed: a delay without loss still passes the seed on.
TEST(NodeOptions, ADelayWithoutLossKeepsItsSeed) {
  NodeOptions o;
  o.loss.seed = 42;
  o.delay.jitter_ms = 3.0;
  const NodeOptions back = parsed(to_arguments(o));
  EXPECT_EQ(back.loss.seed, 42U);
  EXPECT_FALSE(back.loss.enabled());
  EXPECT_EQ(back.delay.jitter_ms, 3.0);
}

TEST(NetworkOptions, TakeAnIpv4AddressAndPortAndRefuseAnythingElse) {
  EXPECT_EQ(parse_ipv4_endpoint("127.0.0.1:11811"), (Ipv4Endpoint{"127.0.0.1", 11811}));
  EXPECT_EQ(parse_ipv4_endpoint("10.0.0.254:1"), (Ipv4Endpoint{"10.0.0.254", 1}));
  for (const char* bad : {"127.0.0.1", "127.0.0.1:", ":11811", "127.0.0.1:0", "127.0.0.1:65536",
                          "127.0.0.1:-1", "127.0.0.1:+80", "127.0.0.1: 80", "localhost:11811",
                          "256.0.0.1:80", "10.0.0:80", "::1:80"}) {
    EXPECT_EQ(parse_ipv4_endpoint(bad), std::nullopt) << bad;
  }
  EXPECT_TRUE(is_ipv4_address("192.168.1.20"));
  EXPECT_FALSE(is_ipv4_address("192.168.1.20 "));
  EXPECT_FALSE(is_ipv4_address("eth0"));
  EXPECT_THROW(parsed({"--interface", "eth0"}), CLI::ValidationError);
  EXPECT_THROW(parsed({"--discovery-server", "10.0.0.1"}), CLI::ValidationError);
}

}  // namespace
}  // namespace skyfuse::options
