#include "skyfuse/registration/considered_biases.hpp"

#include <Eigen/Cholesky>
#include <algorithm>

namespace skyfuse {
namespace {

// The stations of the joint state: those the track holds, and those whose terms this update
// brings, ascending; each with where its u starts in [x; u₁ … u_k].
struct JointStation {
  int station_id = 0;
  Eigen::Index at = 0;
  Eigen::Index dim = 0;
  const ConsideredCross* held = nullptr;  // null: a station new to the track (C̃ = 0)
};

std::vector<JointStation> joint_stations(Eigen::Index n, const ConsideredBiases& considered,
                                         std::span<const ConsideredTerms> terms) {
  std::vector<JointStation> stations;
  for (const ConsideredBias& c : considered) {
    stations.push_back({c.station_id, 0, c.cross.cols(), &c.cross});
  }
  for (const ConsideredTerms& t : terms) {
    const bool held =
        std::any_of(considered.begin(), considered.end(),
                    [&](const ConsideredBias& c) { return c.station_id == t.station_id; });
    if (!held) stations.push_back({t.station_id, 0, t.bias.cols(), nullptr});
  }
  std::sort(stations.begin(), stations.end(), [](const JointStation& a, const JointStation& b) {
    return a.station_id < b.station_id;
  });
  Eigen::Index at = n;
  for (JointStation& s : stations) {
    s.at = at;
    at += s.dim;
  }
  return stations;
}

}  // namespace

NumericalStatus fuse_considered(Eigen::Ref<Eigen::VectorXd> mean,
                                Eigen::Ref<Eigen::MatrixXd> covariance,
                                ConsideredBiases& considered,
                                const Eigen::Ref<const Eigen::MatrixXd>& delta_information,
                                const Eigen::Ref<const Eigen::VectorXd>& delta_vector,
                                std::span<const ConsideredTerms> terms,
                                std::span<const double> weights) {
  const Eigen::Index n = mean.size();
  const std::vector<JointStation> stations = joint_stations(n, considered, terms);
  const Eigen::Index size = stations.empty() ? n : stations.back().at + stations.back().dim;

  // The joint prior [[P, C̃],[C̃ᵀ, I]], its information and information vector (u's mean 0).
  Eigen::MatrixXd prior = Eigen::MatrixXd::Identity(size, size);
  prior.topLeftCorner(n, n) = covariance;
  for (const JointStation& s : stations) {
    if (s.held == nullptr) continue;
    if (s.held->rows() != n) return NumericalStatus::kNotPositiveDefinite;
    prior.block(0, s.at, n, s.dim) = *s.held;
    prior.block(s.at, 0, s.dim, n) = s.held->transpose();
  }
  const Eigen::LLT<Eigen::MatrixXd> prior_factor(prior);
  if (prior_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  Eigen::MatrixXd information = prior_factor.solve(Eigen::MatrixXd::Identity(size, size));
  information = 0.5 * (information + information.transpose()).eval();
  Eigen::VectorXd vector = information.leftCols(n) * mean;

  information.topLeftCorner(n, n) += delta_information;
  vector.head(n) += delta_vector;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const ConsideredTerms& t = terms[i];
    const auto s = std::find_if(stations.begin(), stations.end(), [&](const JointStation& j) {
      return j.station_id == t.station_id;
    });
    if (t.cross.rows() != n || t.cross.cols() != s->dim) {
      return NumericalStatus::kNotPositiveDefinite;
    }
    information.block(0, s->at, n, s->dim) += weights[i] * t.cross;
    information.block(s->at, 0, s->dim, n) += weights[i] * t.cross.transpose();
    information.block(s->at, s->at, s->dim, s->dim) += weights[i] * t.bias;
    vector.segment(s->at, s->dim) += weights[i] * t.vector;
  }

  const Eigen::LLT<Eigen::MatrixXd> posterior_factor(information);
  if (posterior_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  Eigen::MatrixXd posterior = posterior_factor.solve(Eigen::MatrixXd::Identity(size, size));
  posterior = 0.5 * (posterior + posterior.transpose()).eval();
  const Eigen::VectorXd joint_mean = posterior * vector;

  // The track keeps its part; what the joint learnt of u is the registration's to learn.
  mean = joint_mean.head(n);
  covariance = posterior.topLeftCorner(n, n);
  ConsideredBiases next;
  next.reserve(stations.size());
  for (const JointStation& s : stations) {
    next.push_back({s.station_id, posterior.block(0, s.at, n, s.dim)});
  }
  considered = std::move(next);
  return NumericalStatus::kOk;
}

}  // namespace skyfuse
