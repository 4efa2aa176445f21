#pragma once
/// \file
/// Linear assignment: rows (tracks, truths) to columns (detections, estimates) at least cost.
/// Two forms:
/// - solve_assignment: dense, each row to a distinct column (rows <= columns), by shortest
///   augmenting paths (the Jonker-Volgenant family, one Dijkstra search per row on reduced
///   costs). O(rows^2 columns) at worst.
/// - solve_gated_assignment: sparse, every row may also stay unassigned at a cost of its own;
///   only gated pairs exist. It splits the pairs into independent clusters (rows and columns
///   that share no gated pair never compete) and solves each densely, so a picture of a
///   thousand well-separated aircraft costs a thousand tiny problems, not one big one.
///
/// Both are deterministic: the same numbers give the same assignment on every machine and in
/// every process, which is what lets every peer of the network take the same decisions. Ties
/// go to the lower column index.

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace skyfuse::association {

/// The cost of a pair that may not be assigned.
inline constexpr double kForbidden = std::numeric_limits<double>::infinity();

/// A dense cost matrix, row by row.
class CostMatrix {
 public:
  CostMatrix(std::size_t rows, std::size_t cols, double fill = kForbidden)
      : rows_(rows), cols_(cols), costs_(rows * cols, fill) {}

  std::size_t rows() const { return rows_; }
  std::size_t cols() const { return cols_; }
  double& operator()(std::size_t r, std::size_t c) { return costs_[r * cols_ + c]; }
  double operator()(std::size_t r, std::size_t c) const { return costs_[r * cols_ + c]; }

 private:
  std::size_t rows_;
  std::size_t cols_;
  std::vector<double> costs_;
};

/// The column of each row, each column used at most once, minimising the sum of the costs;
/// none when rows > columns or no assignment avoids every forbidden pair. Costs may be
/// negative; they must not be NaN.
std::optional<std::vector<int>> solve_assignment(const CostMatrix& cost);

/// A pair that passed the gate: row `row` may take column `col` at `cost`.
struct GatedPair {
  int row = 0;
  int col = 0;
  double cost = 0.0;
};

/// Rows and columns that share gated pairs, directly or through others: an independent problem.
/// Its rows, columns and pairs (indices into the pairs given) ascend, so that what is solved
/// on it, and so its tie-breaks, depends on the numbers only.
struct PairCluster {
  std::vector<std::size_t> rows;
  std::vector<std::size_t> cols;
  std::vector<std::size_t> pairs;
};

/// The clusters of `pairs` over `rows` rows and `cols` columns, by their lowest row; rows and
/// columns in no pair belong to none. Pairs out of range: std::invalid_argument.
std::vector<PairCluster> cluster_pairs(std::size_t rows, std::size_t cols,
                                       std::span<const GatedPair> pairs);

/// What solve_gated_assignment decided.
struct GatedAssignment {
  std::vector<int> column_of_row;   ///< per row: its column, or -1 when it stays unassigned
  std::size_t clusters = 0;         ///< independent problems solved
  std::size_t largest_cluster = 0;  ///< rows of the largest
};

/// Each of `rows` rows takes at most one of `cols` columns, among `pairs`, or stays unassigned
/// at `unassigned_cost[row]`; each column goes to at most one row (an unused column costs
/// nothing). Minimises the total. Pairs naming a row or column out of range, or a row twice
/// with one column, are a programming error (std::invalid_argument).
GatedAssignment solve_gated_assignment(std::size_t rows, std::size_t cols,
                                       std::span<const GatedPair> pairs,
                                       std::span<const double> unassigned_cost);

}  // namespace skyfuse::association
