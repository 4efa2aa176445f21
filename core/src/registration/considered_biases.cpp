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

// The joint information is never formed whole: with u's prior block the identity, its inverse
// and the posterior's x-part follow from blocks of the track's size and of the biases', by
// Schur complements (an n + k inverse was four times the cost of the round).
NumericalStatus fuse_considered(Eigen::Ref<Eigen::VectorXd> mean,
                                Eigen::Ref<Eigen::MatrixXd> covariance,
                                ConsideredBiases& considered,
                                const Eigen::Ref<const Eigen::MatrixXd>& delta_information,
                                const Eigen::Ref<const Eigen::VectorXd>& delta_vector,
                                std::span<const ConsideredTerms> terms,
                                std::span<const double> weights) {
  using Eigen::MatrixXd;
  using Eigen::VectorXd;
  const Eigen::Index n = mean.size();
  const std::vector<JointStation> stations = joint_stations(n, considered, terms);
  const Eigen::Index k = stations.empty() ? 0 : stations.back().at + stations.back().dim - n;

  // The prior's cross-covariance C̃ (n × k; zero for a station new to the track).
  MatrixXd cross = MatrixXd::Zero(n, k);
  for (const JointStation& s : stations) {
    if (s.held == nullptr) continue;
    if (s.held->rows() != n) return NumericalStatus::kNotPositiveDefinite;
    cross.middleCols(s.at - n, s.dim) = *s.held;
  }

  // The joint prior's information [[A, B],[Bᵀ, D]] of [[P, C̃],[C̃ᵀ, I]]: with W = P⁻¹ C̃ and
  // S = I − C̃ᵀ W, A = P⁻¹ + W S⁻¹ Wᵀ, B = −W S⁻¹, D = S⁻¹; its vector [A x̂; Bᵀ x̂] (u's mean 0).
  const Eigen::LLT<MatrixXd> prior_factor(covariance);
  if (prior_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  MatrixXd a = prior_factor.solve(MatrixXd::Identity(n, n));
  const MatrixXd w = a.lazyProduct(cross);
  MatrixXd s = MatrixXd::Identity(k, k);
  s.noalias() -= cross.transpose().lazyProduct(w);
  const Eigen::LLT<MatrixXd> s_factor(s);
  if (s_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  MatrixXd b = -s_factor.solve(w.transpose()).transpose();  // −W S⁻¹
  a.noalias() -= b.lazyProduct(w.transpose());
  MatrixXd d = s_factor.solve(MatrixXd::Identity(k, k));
  VectorXd eta_x = a.lazyProduct(mean);
  VectorXd eta_u = b.transpose().lazyProduct(mean);

  // The stations' increments and terms.
  a += delta_information;
  eta_x += delta_vector;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const ConsideredTerms& t = terms[i];
    const auto s_at = std::find_if(stations.begin(), stations.end(), [&](const JointStation& j) {
      return j.station_id == t.station_id;
    });
    if (t.cross.rows() != n || t.cross.cols() != s_at->dim) {
      return NumericalStatus::kNotPositiveDefinite;
    }
    const Eigen::Index at = s_at->at - n;
    b.middleCols(at, s_at->dim) += weights[i] * t.cross;
    d.block(at, at, s_at->dim, s_at->dim) += weights[i] * t.bias;
    eta_u.segment(at, s_at->dim) += weights[i] * t.vector;
  }

  // The posterior's x-part: X = (A − B D⁻¹ Bᵀ)⁻¹, x = X (η_x − B D⁻¹ η_u), C̃ = −X B D⁻¹.
  const Eigen::LLT<MatrixXd> d_factor(d);
  if (d_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  const MatrixXd d_inv_bt = d_factor.solve(b.transpose());  // D⁻¹ Bᵀ
  MatrixXd schur = a;
  schur.noalias() -= b.lazyProduct(d_inv_bt);
  schur = 0.5 * (schur + schur.transpose()).eval();
  const Eigen::LLT<MatrixXd> x_factor(schur);
  if (x_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  MatrixXd posterior = x_factor.solve(MatrixXd::Identity(n, n));
  posterior = 0.5 * (posterior + posterior.transpose()).eval();
  const VectorXd reduced = eta_x - d_inv_bt.transpose().lazyProduct(eta_u);
  const MatrixXd posterior_cross = -posterior.lazyProduct(d_inv_bt.transpose());

  // The track keeps its part; what the joint learnt of u is the registration's to learn.
  mean = posterior.lazyProduct(reduced);
  covariance = posterior;
  ConsideredBiases next;
  next.reserve(stations.size());
  for (const JointStation& st : stations) {
    next.push_back({st.station_id, posterior_cross.middleCols(st.at - n, st.dim)});
  }
  considered = std::move(next);
  return NumericalStatus::kOk;
}

void settle_considered(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::MatrixXd> covariance,
                       ConsideredBias& c, const Eigen::Ref<const Eigen::VectorXd>& move,
                       const Eigen::Ref<const Eigen::MatrixXd>& narrowing) {
  const auto d = c.cross.cols();
  if (move.size() != d || narrowing.rows() != d || narrowing.cols() != d) return;
  mean.noalias() += c.cross * move;
  // C̃ (I − A Aᵀ) C̃ᵀ as C̃ C̃ᵀ − (C̃ A)(C̃ A)ᵀ: no D × D temporary, and C̃ A is the new C̃.
  const ConsideredCross narrowed = c.cross * narrowing;
  covariance.noalias() -= c.cross * c.cross.transpose();
  covariance.noalias() += narrowed * narrowed.transpose();
  symmetrize(covariance);
  c.cross = narrowed;
}

}  // namespace skyfuse
