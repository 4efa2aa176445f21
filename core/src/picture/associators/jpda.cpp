#include "skyfuse/picture/associators/jpda.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "skyfuse/picture/tracker_config.hpp"

namespace skyfuse {
namespace {

// The enumeration of one cluster's joint events, depth first over its tracks in ascending
// order, each track's options in ascending detection order, then "none": a fixed order, so
// that every peer adds the same terms in the same order.
class ClusterEvents {
 public:
  struct Option {
    std::size_t local_detection;
    double log_weight;  // log(P_D N / lambda)
    std::size_t pair;   // where its probability is summed
  };

  ClusterEvents(std::vector<std::vector<Option>> options, std::size_t detections, double log_missed)
      : options_(std::move(options)),
        used_(detections, 0),
        log_missed_(log_missed),
        chosen_(options_.size(), kNone) {
    for (const auto& track_options : options_) {
      for (const Option& o : track_options) pairs_.push_back(o.pair);
    }
  }

  // Sums every event's weight onto its pairs (their entries of `pair_sums`, which must be 0),
  // and the total, scaled by exp(-peak) against overflow, peak the largest event's log weight.
  void enumerate(std::vector<double>& pair_sums) {
    peak_ = -std::numeric_limits<double>::infinity();
    total_ = 0.0;
    visit(0, 0.0, pair_sums);
  }
  double total() const { return total_; }

 private:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  void visit(std::size_t track, double log_weight, std::vector<double>& pair_sums) {
    if (track == options_.size()) {
      add_event(log_weight, pair_sums);
      return;
    }
    for (const Option& o : options_[track]) {
      if (used_[o.local_detection]) continue;
      used_[o.local_detection] = 1;
      chosen_[track] = o.pair;
      visit(track + 1, log_weight + o.log_weight, pair_sums);
      used_[o.local_detection] = 0;
    }
    chosen_[track] = kNone;
    visit(track + 1, log_weight + log_missed_, pair_sums);
  }

  void add_event(double log_weight, std::vector<double>& pair_sums) {
    if (log_weight > peak_) {  // rescale what this cluster has summed to the new peak
      const double scale = std::isfinite(peak_) ? std::exp(peak_ - log_weight) : 0.0;
      for (const std::size_t pair : pairs_) pair_sums[pair] *= scale;
      total_ *= scale;
      peak_ = log_weight;
    }
    const double w = std::exp(log_weight - peak_);
    total_ += w;
    for (const std::size_t pair : chosen_) {
      if (pair != kNone) pair_sums[pair] += w;
    }
  }

  std::vector<std::vector<Option>> options_;
  std::vector<char> used_;
  double log_missed_;
  std::vector<std::size_t> chosen_;
  std::vector<std::size_t> pairs_;  // the cluster's pairs, where pair_sums is theirs
  double peak_ = 0.0;
  double total_ = 0.0;
};

}  // namespace

void associate_jpda(const Hypotheses& hypotheses, const DetectionPrior& prior,
                    const AssociationConfig& config, AssociationWork& work, ScanAssociation& out) {
  start_association(hypotheses, work, out);
  const std::vector<association::PairCluster> clusters =
      association::cluster_pairs(hypotheses.tracks, hypotheses.detections, work.gated);

  const double log_detected = std::log(prior.detection_probability / prior.clutter_density);
  const double log_missed = std::log1p(-prior.detection_probability * prior.gate_probability);
  std::vector<char> associated(hypotheses.detections, 0);
  work.scratch.assign(hypotheses.pairs.size(), 0.0);  // each pair's summed probability
  for (const association::PairCluster& cluster : clusters) {
    out.largest_cluster = std::max(out.largest_cluster, cluster.rows.size());
    // The bound on the events: the product of the tracks' option counts (+1 for none).
    double bound = 1.0;
    std::vector<std::vector<ClusterEvents::Option>> options(cluster.rows.size());
    for (const std::size_t p : cluster.pairs) {
      const Hypothesis& h = hypotheses.pairs[p];
      const auto row =
          static_cast<std::size_t>(std::lower_bound(cluster.rows.begin(), cluster.rows.end(),
                                                    static_cast<std::size_t>(h.track)) -
                                   cluster.rows.begin());
      const auto col =
          static_cast<std::size_t>(std::lower_bound(cluster.cols.begin(), cluster.cols.end(),
                                                    static_cast<std::size_t>(h.detection)) -
                                   cluster.cols.begin());
      options[row].push_back({col, log_detected + h.log_density, p});
    }
    for (auto& o : options) {
      std::sort(o.begin(), o.end(),
                [](const auto& a, const auto& b) { return a.local_detection < b.local_detection; });
      bound *= static_cast<double>(o.size() + 1);
    }
    if (bound > static_cast<double>(config.jpda_max_events)) {
      // Too many events to enumerate: this cluster by GNN, each pair it keeps at weight 1.
      ++out.fallback_clusters;
      std::vector<association::GatedPair> pairs;
      for (const std::size_t p : cluster.pairs) pairs.push_back(work.gated[p]);
      work.unassigned_cost.assign(hypotheses.tracks, hypotheses.gate);
      const association::GatedAssignment solved = association::solve_gated_assignment(
          hypotheses.tracks, hypotheses.detections, pairs, work.unassigned_cost);
      for (const std::size_t p : cluster.pairs) {
        const Hypothesis& h = hypotheses.pairs[p];
        if (solved.column_of_row[static_cast<std::size_t>(h.track)] == h.detection) {
          work.scratch[p] = 1.0;
          associated[static_cast<std::size_t>(h.detection)] = 1;
        }
      }
      continue;
    }
    ClusterEvents events(std::move(options), cluster.cols.size(), log_missed);
    events.enumerate(work.scratch);
    for (const std::size_t p : cluster.pairs) work.scratch[p] /= events.total();
    for (const std::size_t col : cluster.cols) associated[col] = 1;
  }

  // The pairs by track, then detection, as the report and the wire take them.
  for (std::size_t p = 0; p < hypotheses.pairs.size(); ++p) {
    if (work.scratch[p] > 0.0) {
      const Hypothesis& h = hypotheses.pairs[p];
      out.pairs.push_back({h.track, static_cast<std::uint32_t>(h.detection), work.scratch[p]});
    }
  }
  std::sort(out.pairs.begin(), out.pairs.end(), [](const WeightedPair& a, const WeightedPair& b) {
    return a.track < b.track || (a.track == b.track && a.detection < b.detection);
  });
  for (std::uint32_t j = 0; j < hypotheses.detections; ++j) {
    if (!associated[j]) out.unassociated.push_back(j);
  }
}

}  // namespace skyfuse
