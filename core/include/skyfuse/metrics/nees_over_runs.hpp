#pragma once
/// \file
/// Whether a filter is consistent, judged from the ANEES of independent Monte-Carlo runs: the
/// pooled χ² band, the interval of the runs' mean, and how far apart the two tests are.
///
/// A track's successive errors are correlated — a filter with little process noise carries one
/// error for hundreds of rounds — so the χ² band of all the samples pooled, which takes them as
/// independent, is far narrower than the pooled mean's real spread. The runs are independent:
/// the interval of their mean, from their own spread (run_mean_interval), assumes nothing about
/// the samples within a run. The ratio of the runs' variance to the one independent samples
/// would give says how much narrower the pooled band is than it should be.

#include <cstddef>
#include <optional>
#include <span>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/metrics/run_mean_interval.hpp"

namespace skyfuse {

/// One run's NEES: the mean of its `samples` NEES values of `dof` degrees of freedom.
struct RunNees {
  double anees = 0.0;
  int dof = 0;
  std::size_t samples = 0;
};

struct NeesOverRuns {
  int dof = 0;
  std::size_t runs = 0;       ///< those with samples, the ones judged
  std::size_t samples = 0;    ///< over every run
  ChiSquareBand pooled_band;  ///< per dof, at 95 %, the pooled samples taken as independent
  RunMeanInterval over_runs;  ///< of the runs' ANEES per dof, at 95 %
  /// The runs' variance of ANEES per dof over the mean of 2 a_r² / (dof n_r), the variance of
  /// run r's a_r were its n_r samples independent draws of a_r χ²(dof) / dof: 1 for
  /// independent samples, the larger the longer a track carries one error.
  double variance_over_independent = 0.0;
};

/// The summary of `runs`, leaving out runs of no samples; nullopt where none has any. Throws
/// std::invalid_argument where the runs' degrees of freedom differ.
std::optional<NeesOverRuns> nees_over_runs(std::span<const RunNees> runs);

}  // namespace skyfuse
