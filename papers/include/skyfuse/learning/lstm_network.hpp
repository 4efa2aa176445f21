#pragma once
/// \file
/// Inference of the two-layer LSTM regressor of lstm_weights.hpp on one window, in float.
///
/// Per step t (gate rows i, f, g, o; sigma the logistic function):
///   [i f g o] = W_in x_t + W_rec h_{t-1} + b,
///   c_t = sigma(f) c_{t-1} + sigma(i) tanh(g),   h_t = sigma(o) tanh(c_t),
/// for layer 1 on the normalised inputs x_t = (window_t - input_mean) / input_std and for
/// layer 2 on layer 1's h_t; both start from h = c = 0. The output is
///   output_mean + output_scale * (W_dense h2_last + b_dense).
///
/// How it is computed: the input projections W_in x_t + b of all steps are one matrix product
/// per layer (layer 2's after layer 1 has run every step), so that only W_rec h_{t-1} is left
/// to the sequential part (none at step 0, where h = 0). For layer 1 that is a (4 H1 x H1)
/// matrix-vector product per step, which streams the recurrent weights (256 KiB at H1 = 128)
/// from the L2 cache and sets the speed; its rows are stored interleaved by blocks of 8 units
/// ([i f g o] of 8 units, 32 rows), so that each block's cell update runs while the next
/// block's weights load. The input projections' weights are packed in panels of 32 rows.
///
/// The kernels are plain C++ over GCC vector types, built for x86-64-v3 (AVX2, FMA) beside
/// the baseline and picked at load time; the two builds differ by float rounding only (FMA).
/// sigma and tanh come from one exp (range reduction, degree-6 polynomial, about 1e-7
/// relative); tanh x = 2 sigma(2x) - 1 has an absolute error of about 1e-7.
///
/// Hidden widths are padded to multiples of 16 with zero weights: a padded unit has gates 0,
/// so c stays 0 and h = sigma(0) tanh(0) = 0, and it changes nothing.

#include <Eigen/Core>
#include <cstddef>
#include <new>
#include <vector>

#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::learning {

namespace detail {
/// Allocator giving 64-byte (cache line) aligned storage.
template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}));
  }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete (p, std::align_val_t{64}); }
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};
using AlignedFloats = std::vector<float, CacheLineAllocator<float>>;
}  // namespace detail

class LstmNetwork {
 public:
  static constexpr int kSteps = 14;
  static constexpr int kFeatures = 6;
  static constexpr int kOutputs = 2;
  /// One window, a row per step, features in the order of the weights' input_mean (paper 001:
  /// CVKF [x, vx, y, vy], then the measurement [x, y]); skyfuse::Matrix<14, 6>.
  using Window = Eigen::Matrix<double, kSteps, kFeatures>;

  /// Throws std::invalid_argument when the weights are inconsistent or do not map kFeatures
  /// inputs to kOutputs outputs.
  explicit LstmNetwork(const LstmWeights& weights);

  /// The network's output for one window. Allocates nothing: every work buffer is sized in
  /// the constructor. It writes those buffers, so one object must not be used by two threads
  /// at once; give each thread its own copy.
  Eigen::Vector2d predict(const Window& window);

  const LstmTrainingRecord& record() const { return record_; }
  int hidden1() const { return hidden1_; }
  int hidden2() const { return hidden2_; }

 private:
  LstmTrainingRecord record_;
  int hidden1_ = 0;
  int hidden2_ = 0;
  int padded1_ = 0;  ///< hidden1_ rounded up to a multiple of 16
  int padded2_ = 0;  ///< hidden2_ rounded up to a multiple of 16
  Eigen::Matrix<float, kFeatures, 1> input_mean_;
  Eigen::Matrix<float, kFeatures, 1> input_inverse_std_;
  // Weights. Layer 1's 4 P1 gate rows interleaved by blocks of 8 units ([i f g o] x 8);
  // layer 2's in gate blocks [i f g o], each padded to P2 rows.
  detail::AlignedFloats input1_;      ///< W_in1 (4 P1 x kFeatures) in panels of 32 rows
  detail::AlignedFloats bias1_;       ///< 4 P1
  detail::AlignedFloats recurrent1_;  ///< 4 P1 x P1: W_rec1, row-major
  detail::AlignedFloats input2_;      ///< W_in2 (4 P2 x P1) in panels of 32 rows
  detail::AlignedFloats bias2_;       ///< 4 P2
  detail::AlignedFloats recurrent2_;  ///< P2 x 4 P2: W_rec2 transposed
  Eigen::Matrix<float, kOutputs, Eigen::Dynamic, Eigen::RowMajor> dense_;
  Eigen::Matrix<float, kOutputs, 1> dense_bias_;
  Eigen::Matrix<float, kOutputs, 1> output_mean_;
  Eigen::Matrix<float, kOutputs, 1> output_scale_;
  // Work buffers, sized once.
  detail::AlignedFloats inputs_;       ///< kSteps x kFeatures, normalised
  detail::AlignedFloats projected1_;   ///< kSteps x 4 P1: W_in1 x_t + b1
  detail::AlignedFloats projected2_;   ///< kSteps x 4 P2: W_in2 h1_t + b2
  detail::AlignedFloats hidden1_seq_;  ///< (kSteps + 1) x P1: h1 before step 0, then each step
  detail::AlignedFloats hidden2_seq_;  ///< 2 x P2: h2, alternately previous and new
  detail::AlignedFloats gates_;        ///< 4 P2: layer 2's gates
  detail::AlignedFloats cell1_;        ///< P1
  detail::AlignedFloats cell2_;        ///< P2
};

}  // namespace skyfuse::learning
