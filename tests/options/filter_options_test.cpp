// How the harness and every node settle a run's exchange: `auto` chose the tree by size, and a
// run whose links lose, delay or re-fuse samples goes back to flat; an exchange asked for is
// kept, and refused where the filter's stations cannot run it.
#include "skyfuse/options/filter_options.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::options {
namespace {

// ring64's first `stations`, with `exchange` asked for (nothing: auto).
Scenario planned(int stations, std::optional<ExchangeConfig::Kind> exchange = std::nullopt) {
  const Scenario ring = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/ring64.yaml");
  return make_run_plan(ring, {stations, 10, {}, 0, exchange, {}, {}, {}}).scenario;
}

ExchangeConfig::Kind settled(Scenario s, const NodeOptions& node) {
  settle_exchange(s, node);
  return s.exchange.kind;
}

TEST(SettleExchange, AutosTreeGoesBackToFlatForLossDelayOrALag) {
  const Scenario sixteen = planned(16);
  ASSERT_EQ(sixteen.exchange.kind, ExchangeConfig::Kind::kTree);
  ASSERT_TRUE(sixteen.exchange.chosen_by_size);
  EXPECT_EQ(settled(sixteen, {}), ExchangeConfig::Kind::kTree);

  NodeOptions loss;
  loss.loss.probability = 0.02;
  EXPECT_EQ(settled(sixteen, loss), ExchangeConfig::Kind::kFlat);
  NodeOptions delay;
  delay.delay.delay_ms = 5.0;
  EXPECT_EQ(settled(sixteen, delay), ExchangeConfig::Kind::kFlat);
  NodeOptions lag;
  lag.refusion_lag = 2;
  EXPECT_EQ(settled(sixteen, lag), ExchangeConfig::Kind::kFlat);
  EXPECT_EQ(settled(planned(8), loss), ExchangeConfig::Kind::kFlat);
}

TEST(SettleExchange, KeepsATreeAskedForAndRefusesItWithALag) {
  const Scenario tree = planned(16, ExchangeConfig::Kind::kTree);
  ASSERT_FALSE(tree.exchange.chosen_by_size);
  NodeOptions loss;
  loss.loss.probability = 0.02;
  EXPECT_EQ(settled(tree, loss), ExchangeConfig::Kind::kTree);
  NodeOptions lag;
  lag.refusion_lag = 2;
  EXPECT_THROW(settled(tree, lag), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse::options
