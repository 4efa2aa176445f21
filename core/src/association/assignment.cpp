#include "skyfuse/association/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace skyfuse::association {
namespace {

// The cheapest full assignment of the rows of `cost` (every entry >= 0 or forbidden), one
// shortest augmenting path per row: a Dijkstra search over reduced costs c(i, j) - u(i) - v(j),
// which the dual updates keep non-negative, from the new row to the nearest free column.
std::optional<std::vector<int>> shortest_augmenting_paths(const CostMatrix& cost) {
  const std::size_t rows = cost.rows();
  const std::size_t cols = cost.cols();
  std::vector<double> u(rows, 0.0);
  std::vector<double> v(cols, 0.0);
  std::vector<int> col_of_row(rows, -1);
  std::vector<int> row_of_col(cols, -1);
  std::vector<double> path_cost(cols);
  std::vector<int> previous_row(cols);
  std::vector<char> row_seen(rows);
  std::vector<char> col_seen(cols);
  std::vector<std::size_t> rows_seen;

  for (std::size_t start = 0; start < rows; ++start) {
    std::fill(path_cost.begin(), path_cost.end(), kForbidden);
    std::fill(row_seen.begin(), row_seen.end(), 0);
    std::fill(col_seen.begin(), col_seen.end(), 0);
    rows_seen.clear();
    double reached = 0.0;  // the length of the shortest path found so far
    std::size_t row = start;
    int sink = -1;
    while (sink < 0) {
      row_seen[row] = 1;
      rows_seen.push_back(row);
      double lowest = kForbidden;
      int next = -1;
      for (std::size_t c = 0; c < cols; ++c) {
        if (col_seen[c]) continue;
        const double through_row = reached + cost(row, c) - u[row] - v[c];
        if (through_row < path_cost[c]) {
          path_cost[c] = through_row;
          previous_row[c] = static_cast<int>(row);
        }
        // Ties: the lower column, unless a later one is free (the search ends there).
        if (path_cost[c] < lowest ||
            (path_cost[c] == lowest && next >= 0 &&
             row_of_col[static_cast<std::size_t>(next)] >= 0 && row_of_col[c] < 0)) {
          lowest = path_cost[c];
          next = static_cast<int>(c);
        }
      }
      if (next < 0 || lowest == kForbidden) return std::nullopt;  // no free column reachable
      reached = lowest;
      const auto column = static_cast<std::size_t>(next);
      col_seen[column] = 1;
      if (row_of_col[column] < 0) {
        sink = next;
      } else {
        row = static_cast<std::size_t>(row_of_col[column]);
      }
    }
    // Duals: what keeps every reduced cost non-negative and the new path's tight.
    u[start] += reached;
    for (const std::size_t r : rows_seen) {
      if (r != start) u[r] += reached - path_cost[static_cast<std::size_t>(col_of_row[r])];
    }
    for (std::size_t c = 0; c < cols; ++c) {
      if (col_seen[c]) v[c] -= reached - path_cost[c];
    }
    // Augment along the path back to the start row.
    auto column = static_cast<std::size_t>(sink);
    while (true) {
      const auto r = static_cast<std::size_t>(previous_row[column]);
      row_of_col[column] = static_cast<int>(r);
      const int freed = col_of_row[r];
      col_of_row[r] = static_cast<int>(column);
      if (r == start) break;
      column = static_cast<std::size_t>(freed);
    }
  }
  return col_of_row;
}

// Disjoint sets over the rows and columns of a gated problem (columns after the rows).
class Clusters {
 public:
  explicit Clusters(std::size_t size) : parent_(size) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t root(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void join(std::size_t a, std::size_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the lowest member is the root
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace

std::optional<std::vector<int>> solve_assignment(const CostMatrix& cost) {
  if (cost.rows() > cost.cols()) return std::nullopt;
  if (cost.rows() == 0) return std::vector<int>{};
  // Shifted so that every cost is >= 0, which the search needs; a full assignment of the rows
  // pays the shift once per row, so the cheapest one is the same.
  double lowest = kForbidden;
  for (std::size_t r = 0; r < cost.rows(); ++r) {
    for (std::size_t c = 0; c < cost.cols(); ++c) lowest = std::min(lowest, cost(r, c));
  }
  if (lowest == kForbidden) return std::nullopt;
  if (lowest >= 0.0) return shortest_augmenting_paths(cost);
  CostMatrix shifted = cost;
  for (std::size_t r = 0; r < cost.rows(); ++r) {
    for (std::size_t c = 0; c < cost.cols(); ++c) shifted(r, c) -= lowest;
  }
  return shortest_augmenting_paths(shifted);
}

std::vector<PairCluster> cluster_pairs(std::size_t rows, std::size_t cols,
                                       std::span<const GatedPair> pairs) {
  Clusters clusters(rows + cols);
  for (const GatedPair& pair : pairs) {
    if (pair.row < 0 || static_cast<std::size_t>(pair.row) >= rows || pair.col < 0 ||
        static_cast<std::size_t>(pair.col) >= cols) {
      throw std::invalid_argument("solve_gated_assignment: pair (" + std::to_string(pair.row) +
                                  ", " + std::to_string(pair.col) + ") out of range");
    }
    clusters.join(static_cast<std::size_t>(pair.row), rows + static_cast<std::size_t>(pair.col));
  }
  std::vector<std::size_t> cluster_of(rows + cols, rows + cols);  // by root
  std::vector<PairCluster> found;
  auto cluster_at = [&](std::size_t node) -> PairCluster& {
    const std::size_t r = clusters.root(node);
    if (cluster_of[r] == rows + cols) {
      cluster_of[r] = found.size();
      found.emplace_back();
    }
    return found[cluster_of[r]];
  };
  std::vector<char> in_pair(rows + cols, 0);
  for (const GatedPair& pair : pairs) {
    in_pair[static_cast<std::size_t>(pair.row)] = 1;
    in_pair[rows + static_cast<std::size_t>(pair.col)] = 1;
  }
  for (std::size_t node = 0; node < rows + cols; ++node) {
    if (!in_pair[node]) continue;
    PairCluster& cluster = cluster_at(node);
    (node < rows ? cluster.rows : cluster.cols).push_back(node < rows ? node : node - rows);
  }
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    cluster_at(static_cast<std::size_t>(pairs[p].row)).pairs.push_back(p);
  }
  return found;
}

GatedAssignment solve_gated_assignment(std::size_t rows, std::size_t cols,
                                       std::span<const GatedPair> pairs,
                                       std::span<const double> unassigned_cost) {
  if (unassigned_cost.size() != rows) {
    throw std::invalid_argument("solve_gated_assignment: one unassigned cost per row");
  }
  const std::vector<PairCluster> found = cluster_pairs(rows, cols, pairs);

  GatedAssignment result;
  result.column_of_row.assign(rows, -1);
  result.clusters = found.size();
  std::vector<std::size_t> local(std::max(rows, cols), 0);
  for (const PairCluster& cluster : found) {
    result.largest_cluster = std::max(result.largest_cluster, cluster.rows.size());
    const std::size_t n = cluster.rows.size();
    const std::size_t m = cluster.cols.size();
    // Columns: the cluster's own, then one "stays unassigned" column per row.
    CostMatrix cost(n, m + n);
    for (std::size_t i = 0; i < n; ++i) {
      local[cluster.rows[i]] = i;
      cost(i, m + i) = unassigned_cost[cluster.rows[i]];
    }
    std::vector<std::size_t> col_local(m);
    for (std::size_t j = 0; j < m; ++j) col_local[j] = cluster.cols[j];
    for (const std::size_t p : cluster.pairs) {
      const GatedPair* pair = &pairs[p];
      const std::size_t i = local[static_cast<std::size_t>(pair->row)];
      const auto j =
          static_cast<std::size_t>(std::lower_bound(col_local.begin(), col_local.end(),
                                                    static_cast<std::size_t>(pair->col)) -
                                   col_local.begin());
      if (cost(i, j) != kForbidden) {
        throw std::invalid_argument("solve_gated_assignment: pair (" + std::to_string(pair->row) +
                                    ", " + std::to_string(pair->col) + ") given twice");
      }
      cost(i, j) = pair->cost;
    }
    const auto solved = solve_assignment(cost);
    if (!solved) {
      throw std::invalid_argument("solve_gated_assignment: an unassigned cost is not finite");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>((*solved)[i]);
      if (j < m) result.column_of_row[cluster.rows[i]] = static_cast<int>(cluster.cols[j]);
    }
  }
  return result;
}

}  // namespace skyfuse::association
