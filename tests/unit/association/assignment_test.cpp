#include "skyfuse/association/assignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

namespace skyfuse::association {
namespace {

// The cheapest assignment by trying every one: each row takes a distinct column, or (when
// `unassigned` is given) stays unassigned at its cost. Infinity when none is allowed.
double brute_force(const CostMatrix& cost, const std::vector<double>* unassigned = nullptr) {
  std::vector<char> used(cost.cols(), 0);
  std::function<double(std::size_t)> best_from = [&](std::size_t row) -> double {
    if (row == cost.rows()) return 0.0;
    double best = kForbidden;
    if (unassigned != nullptr) best = (*unassigned)[row] + best_from(row + 1);
    for (std::size_t c = 0; c < cost.cols(); ++c) {
      if (used[c] || cost(row, c) == kForbidden) continue;
      used[c] = 1;
      best = std::min(best, cost(row, c) + best_from(row + 1));
      used[c] = 0;
    }
    return best;
  };
  return best_from(0);
}

double total(const CostMatrix& cost, const std::vector<int>& column_of_row,
             const std::vector<double>* unassigned = nullptr) {
  double sum = 0.0;
  for (std::size_t r = 0; r < column_of_row.size(); ++r) {
    sum += column_of_row[r] < 0 ? (*unassigned)[r]
                                : cost(r, static_cast<std::size_t>(column_of_row[r]));
  }
  return sum;
}

bool columns_distinct(const std::vector<int>& column_of_row) {
  std::vector<int> used;
  for (const int c : column_of_row) {
    if (c >= 0) used.push_back(c);
  }
  std::sort(used.begin(), used.end());
  return std::adjacent_find(used.begin(), used.end()) == used.end();
}

CostMatrix random_costs(std::mt19937& rng, std::size_t rows, std::size_t cols,
                        double forbidden_share, double low) {
  std::uniform_real_distribution<double> value(low, 10.0);
  std::bernoulli_distribution forbidden(forbidden_share);
  CostMatrix cost(rows, cols);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < cols; ++c) {
      if (!forbidden(rng)) cost(r, c) = value(rng);
    }
  }
  return cost;
}

TEST(Assignment, AHandWorkedSquareProblem) {
  // The diagonal is cheapest row by row, but rows 0 and 1 both want column 0 first.
  CostMatrix cost(3, 3);
  const double values[3][3] = {{1, 2, 9}, {1, 5, 9}, {9, 9, 3}};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) cost(r, c) = values[r][c];
  }
  const auto solved = solve_assignment(cost);
  ASSERT_TRUE(solved);
  EXPECT_EQ(*solved, (std::vector<int>{1, 0, 2}));
}

TEST(Assignment, MatchesBruteForceOnRandomRectangularProblems) {
  std::mt19937 rng(7);
  int feasible = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const auto rows = static_cast<std::size_t>(1 + trial % 5);
    const auto cols = rows + static_cast<std::size_t>(trial % 3);
    // Some problems have negative costs, some forbidden pairs, some no full assignment.
    const CostMatrix cost = random_costs(rng, rows, cols, 0.3, trial % 2 == 0 ? -5.0 : 0.0);
    const double best = brute_force(cost);
    const auto solved = solve_assignment(cost);
    if (best == kForbidden) {
      EXPECT_FALSE(solved) << "trial " << trial;
      continue;
    }
    ++feasible;
    ASSERT_TRUE(solved) << "trial " << trial;
    EXPECT_TRUE(columns_distinct(*solved));
    EXPECT_NEAR(total(cost, *solved), best, 1e-9) << "trial " << trial;
  }
  EXPECT_GT(feasible, 1000);  // the comparison ran on real problems, not only infeasible ones
}

TEST(Assignment, MoreRowsThanColumnsHasNoFullAssignment) {
  EXPECT_FALSE(solve_assignment(CostMatrix(3, 2, 1.0)));
}

TEST(Assignment, TiesGoToTheLowerColumnTheSameWayEveryTime) {
  const CostMatrix cost(2, 4, 1.0);
  const auto solved = solve_assignment(cost);
  ASSERT_TRUE(solved);
  EXPECT_EQ(*solved, (std::vector<int>{0, 1}));
}

TEST(GatedAssignment, MatchesBruteForceWithUnassignedCosts) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unassigned_value(0.0, 8.0);
  for (int trial = 0; trial < 1500; ++trial) {
    const auto rows = static_cast<std::size_t>(1 + trial % 6);
    const auto cols = static_cast<std::size_t>(1 + (trial / 6) % 6);
    const CostMatrix cost = random_costs(rng, rows, cols, 0.6, 0.0);
    std::vector<double> unassigned(rows);
    for (double& u : unassigned) u = unassigned_value(rng);
    std::vector<GatedPair> pairs;
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < cols; ++c) {
        if (cost(r, c) != kForbidden) {
          pairs.push_back({static_cast<int>(r), static_cast<int>(c), cost(r, c)});
        }
      }
    }
    const GatedAssignment solved = solve_gated_assignment(rows, cols, pairs, unassigned);
    ASSERT_EQ(solved.column_of_row.size(), rows);
    EXPECT_TRUE(columns_distinct(solved.column_of_row));
    for (std::size_t r = 0; r < rows; ++r) {  // only gated pairs are ever taken
      const int c = solved.column_of_row[r];
      if (c >= 0) {
        EXPECT_NE(cost(r, static_cast<std::size_t>(c)), kForbidden);
      }
    }
    EXPECT_NEAR(total(cost, solved.column_of_row, &unassigned), brute_force(cost, &unassigned),
                1e-9)
        << "trial " << trial;
  }
}

TEST(GatedAssignment, SeparateGroupsAreSolvedApart) {
  // Rows 0-1 compete for columns 0-1; row 2 gates only column 3; row 3 gates nothing.
  const std::vector<GatedPair> pairs = {{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 1.5}, {2, 3, 0.5}};
  const std::vector<double> unassigned = {10.0, 10.0, 10.0, 10.0};
  const GatedAssignment solved = solve_gated_assignment(4, 4, pairs, unassigned);
  EXPECT_EQ(solved.column_of_row, (std::vector<int>{1, 0, 3, -1}));
  EXPECT_EQ(solved.clusters, 2U);
  EXPECT_EQ(solved.largest_cluster, 2U);
}

TEST(GatedAssignment, APairDearerThanLeavingTheRowUnassignedIsNotTaken) {
  const std::vector<GatedPair> pairs = {{0, 0, 5.0}};
  const std::vector<double> unassigned = {4.0};
  EXPECT_EQ(solve_gated_assignment(1, 1, pairs, unassigned).column_of_row, (std::vector<int>{-1}));
}

TEST(GatedAssignment, RefusesPairsOutOfRangeOrTwice) {
  const std::vector<double> unassigned = {1.0};
  const std::vector<GatedPair> out_of_range = {{0, 2, 1.0}};
  EXPECT_THROW(solve_gated_assignment(1, 2, out_of_range, unassigned), std::invalid_argument);
  const std::vector<GatedPair> twice = {{0, 1, 1.0}, {0, 1, 2.0}};
  EXPECT_THROW(solve_gated_assignment(1, 2, twice, unassigned), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse::association
