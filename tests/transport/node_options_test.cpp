// The options every node process shares, as the command line sets them.
#include "skyfuse/transport/node_options.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <string>
#include <vector>

namespace skyfuse::transport {
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

}  // namespace
}  // namespace skyfuse::transport
