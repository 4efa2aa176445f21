// The configuration groups that split the build's per-configuration code into shards
// (registry/configuration_groups.hpp): every filter part on every model it runs on has a number
// of its own, the numbers are 0 .. kConfigurationGroups - 1, and a model a part does not run on
// has none.
#include "skyfuse/registry/configuration_groups.hpp"

#include <gtest/gtest.h>

#include <set>
#include <type_traits>

namespace skyfuse {
namespace {

template <typename... Filters, typename... Models>
void collect_groups(FilterList<Filters...> /*parts*/, ModelList<Models...> /*models*/,
                    std::multiset<std::size_t>& numbers, int& pairs_run_on) {
  const auto per_part = [&]<typename Filter>(std::type_identity<Filter>) {
    const auto per_model = [&]<typename Model>(std::type_identity<Model>) {
      constexpr auto group = kConfigurationGroup<Filter, Model>;
      if constexpr (filter_runs_on_model<Filter, Model>()) {
        ++pairs_run_on;
        ASSERT_TRUE(group.has_value()) << Filter::kKind << " on " << Model::kKind;
        numbers.insert(*group);
      } else {
        EXPECT_FALSE(group.has_value()) << Filter::kKind << " on " << Model::kKind;
      }
    };
    (per_model(std::type_identity<Models>{}), ...);
  };
  (per_part(std::type_identity<Filters>{}), ...);
}

TEST(ConfigurationGroups, NumberEachPartOnEachModelItRunsOnOnce) {
  std::multiset<std::size_t> numbers;
  int pairs = 0;
  collect_groups(FilterParts{}, MotionModels{}, numbers, pairs);
  EXPECT_EQ(static_cast<std::size_t>(pairs), kConfigurationGroups);
  std::set<std::size_t> expected;
  for (std::size_t g = 0; g < kConfigurationGroups; ++g) expected.insert(g);
  EXPECT_EQ(std::set<std::size_t>(numbers.begin(), numbers.end()), expected);
  EXPECT_EQ(numbers.size(), expected.size()) << "a number given twice";
}

TEST(ConfigurationGroups, FollowTheRegistrysOrder) {
  // The first part (the EKF runs on every model) on the first model, then its second.
  EXPECT_EQ((kConfigurationGroup<EkfFilterPart, ConstantAcceleration3D>), 0U);
  EXPECT_EQ((kConfigurationGroup<EkfFilterPart, ConstantVelocity3D>), 1U);
  // The NCRKF runs on paper 002's relative motion only.
  EXPECT_EQ((kConfigurationGroup<NcrkfFilterPart, ConstantVelocity3D>), std::nullopt);
  EXPECT_TRUE((kConfigurationGroup<NcrkfFilterPart, TdoaRelativeMotion>).has_value());
}

}  // namespace
}  // namespace skyfuse
