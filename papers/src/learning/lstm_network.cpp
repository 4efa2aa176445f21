#include "skyfuse/learning/lstm_network.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

// The kernels below are built twice, for x86-64-v3 (AVX2 + FMA) and the baseline, and the
// dynamic loader picks one (GCC's target_clones, an ifunc). Elsewhere: the baseline only.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SKYFUSE_LSTM_KERNEL __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define SKYFUSE_LSTM_KERNEL
#endif

namespace skyfuse::learning {
namespace {

// Eight floats, eight int32; loads and stores go through F8u, which may be unaligned and may
// alias float.
using F8 = float __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));
using F8u = float __attribute__((vector_size(32), aligned(4), may_alias));

#if defined(__clang__)
#define SKYFUSE_SHUFFLE(a, b, ...) __builtin_shufflevector(a, b, __VA_ARGS__)
#else
#define SKYFUSE_SHUFFLE(a, b, ...) __builtin_shuffle(a, b, I8{__VA_ARGS__})
#endif

constexpr int kBlock = 16;  // hidden widths are padded to multiples of this

// The helpers take and return vectors by value; they are always inlined into the kernels, so
// no vector ever crosses a call and GCC's -Wpsabi note (reported at the end of the file) does
// not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

[[gnu::always_inline]] inline F8 load(const float* p) {
  return *reinterpret_cast<const F8u*>(p);
}
[[gnu::always_inline]] inline void store(float* p, F8 v) {
  *reinterpret_cast<F8u*>(p) = v;
}
[[gnu::always_inline]] inline F8 splat(float s) {
  return F8{} + s;
}

// e^x for x in [-87, 88] (clamped there): x = n ln2 + r with |r| <= ln2 / 2 (Cody-Waite
// split of ln2, the first part exact in n ln2_hi), e^r by its degree-6 Taylor polynomial
// (relative error <= r^7 / 7! < 1.2e-7), 2^n built in the exponent bits.
[[gnu::always_inline]] inline F8 exp8(F8 x) {
  const F8 lo = splat(-87.0f);
  const F8 hi = splat(88.0f);
  x = x < lo ? lo : x;
  x = x > hi ? hi : x;
  // Adding 1.5 * 2^23 rounds to an integer, which then sits in the low mantissa bits.
  const F8 magic = splat(12582912.0f);
  const F8 shifted = x * 1.44269504f + magic;
  const I8 n = std::bit_cast<I8>(shifted) - std::bit_cast<I8>(magic);
  const F8 nf = shifted - magic;
  const F8 r = (x - nf * 0.693359375f) + nf * 2.12194440e-4f;
  F8 p = splat(1.0f / 720.0f);
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  const I8 bits = (n + 127) << 23;
  return p * std::bit_cast<F8>(bits);
}

[[gnu::always_inline]] inline F8 sigmoid8(F8 x) {
  return 1.0f / (1.0f + exp8(-x));
}
// tanh x = 2 sigma(2x) - 1: absolute error about 1e-7, also near 0.
[[gnu::always_inline]] inline F8 tanh8(F8 x) {
  return 2.0f / (1.0f + exp8(-2.0f * x)) - 1.0f;
}

// z[t][r] = bias[r] + sum_j x[t][j] W[r][j] for t < steps, r < outputs (a multiple of 32):
// every step's input projection at once. W is packed in panels of 32 outputs, each
// `inputs` x 32 contiguous (a strided block would crowd a few L1 sets: rows 2^k bytes apart),
// and a panel serves three steps per pass.
SKYFUSE_LSTM_KERNEL void project(const float* panels, int inputs, int outputs, const float* bias,
                                 const float* x, int x_stride, int steps, float* z) {
  constexpr int kTile = 3;
  for (int r = 0; r < outputs; r += 32) {
    const float* panel = panels + static_cast<std::ptrdiff_t>(r) * inputs;
    const F8 b[4] = {load(bias + r), load(bias + r + 8), load(bias + r + 16), load(bias + r + 24)};
    int t = 0;
    for (; t + kTile <= steps; t += kTile) {
      F8 a[kTile][4];
#pragma GCC unroll 3
      for (int k = 0; k < kTile; ++k) {
#pragma GCC unroll 4
        for (int v = 0; v < 4; ++v) a[k][v] = b[v];
      }
      const float* xt = x + static_cast<std::ptrdiff_t>(t) * x_stride;
      const float* w = panel;
      for (int j = 0; j < inputs; ++j, w += 32) {
        const F8 wv[4] = {load(w), load(w + 8), load(w + 16), load(w + 24)};
#pragma GCC unroll 3
        for (int k = 0; k < kTile; ++k) {
          const F8 s = splat(xt[k * x_stride + j]);
#pragma GCC unroll 4
          for (int v = 0; v < 4; ++v) a[k][v] += wv[v] * s;
        }
      }
#pragma GCC unroll 3
      for (int k = 0; k < kTile; ++k) {
        float* zt = z + static_cast<std::ptrdiff_t>(t + k) * outputs + r;
#pragma GCC unroll 4
        for (int v = 0; v < 4; ++v) store(zt + 8 * v, a[k][v]);
      }
    }
    for (; t < steps; ++t) {
      F8 a[4] = {b[0], b[1], b[2], b[3]};
      const float* xt = x + static_cast<std::ptrdiff_t>(t) * x_stride;
      const float* w = panel;
      for (int j = 0; j < inputs; ++j, w += 32) {
        const F8 s = splat(xt[j]);
#pragma GCC unroll 4
        for (int v = 0; v < 4; ++v) a[v] += load(w + 8 * v) * s;
      }
      float* zt = z + static_cast<std::ptrdiff_t>(t) * outputs + r;
#pragma GCC unroll 4
      for (int v = 0; v < 4; ++v) store(zt + 8 * v, a[v]);
    }
  }
}

// One LSTM cell update of 8 units from their gate pre-activations.
[[gnu::always_inline]] inline void cell8(F8 i, F8 f, F8 g, F8 o, float* c, float* h) {
  const F8 cell = sigmoid8(f) * load(c) + sigmoid8(i) * tanh8(g);
  store(c, cell);
  store(h, sigmoid8(o) * tanh8(cell));
}

// Lane k of the result is the sum of v_k's lanes: a transposing tree of 7 additions.
[[gnu::always_inline]] inline F8 lane_sums(F8 v0, F8 v1, F8 v2, F8 v3, F8 v4, F8 v5, F8 v6, F8 v7) {
  // b0 = [v0 01, v1 01, v0 23, v1 23, v0 45, v1 45, v0 67, v1 67] (pair sums), and so on.
  const F8 b0 = SKYFUSE_SHUFFLE(v0, v1, 0, 8, 2, 10, 4, 12, 6, 14) +
                SKYFUSE_SHUFFLE(v0, v1, 1, 9, 3, 11, 5, 13, 7, 15);
  const F8 b1 = SKYFUSE_SHUFFLE(v2, v3, 0, 8, 2, 10, 4, 12, 6, 14) +
                SKYFUSE_SHUFFLE(v2, v3, 1, 9, 3, 11, 5, 13, 7, 15);
  const F8 b2 = SKYFUSE_SHUFFLE(v4, v5, 0, 8, 2, 10, 4, 12, 6, 14) +
                SKYFUSE_SHUFFLE(v4, v5, 1, 9, 3, 11, 5, 13, 7, 15);
  const F8 b3 = SKYFUSE_SHUFFLE(v6, v7, 0, 8, 2, 10, 4, 12, 6, 14) +
                SKYFUSE_SHUFFLE(v6, v7, 1, 9, 3, 11, 5, 13, 7, 15);
  // c0 = [v0 0-3, v1 0-3, v2 0-3, v3 0-3, v0 4-7, v1 4-7, v2 4-7, v3 4-7], c1 likewise.
  const F8 c0 = SKYFUSE_SHUFFLE(b0, b1, 0, 1, 8, 9, 4, 5, 12, 13) +
                SKYFUSE_SHUFFLE(b0, b1, 2, 3, 10, 11, 6, 7, 14, 15);
  const F8 c1 = SKYFUSE_SHUFFLE(b2, b3, 0, 1, 8, 9, 4, 5, 12, 13) +
                SKYFUSE_SHUFFLE(b2, b3, 2, 3, 10, 11, 6, 7, 14, 15);
  return SKYFUSE_SHUFFLE(c0, c1, 0, 1, 2, 3, 8, 9, 10, 11) +
         SKYFUSE_SHUFFLE(c0, c1, 4, 5, 6, 7, 12, 13, 14, 15);
}

// One step of a layer `width` (a multiple of 8) units wide whose gate rows are interleaved by
// blocks of 8 units: block b holds rows [i f g o] of units 8b..8b+7, 32 rows, each `width`
// long. For each block and gate: the 8 values z + W_rec h_prev (eight rows at once, each read
// once front to back), then the block's cell update, arithmetic only, which overlaps the next
// block's loads: this step is bound by reading W_rec from L2. `first`: h_prev is zero, so the
// gates are z.
SKYFUSE_LSTM_KERNEL void interleaved_step(const float* w, int width, const float* z,
                                          const float* h_prev, bool first, float* c, float* h) {
  for (int u = 0; u < width; u += 8) {
    const float* block = w + static_cast<std::ptrdiff_t>(u) * 4 * width;
    F8 gates[4];
    for (int g = 0; g < 4; ++g) {
      gates[g] = load(z + 4 * u + 8 * g);
      if (first) continue;
      const float* r0 = block + static_cast<std::ptrdiff_t>(8 * g) * width;
      const float* r1 = r0 + width;
      const float* r2 = r1 + width;
      const float* r3 = r2 + width;
      const float* r4 = r3 + width;
      const float* r5 = r4 + width;
      const float* r6 = r5 + width;
      const float* r7 = r6 + width;
      F8 a0{}, a1{}, a2{}, a3{}, a4{}, a5{}, a6{}, a7{};
      for (int j = 0; j < width; j += 8) {
        const F8 x = load(h_prev + j);
        a0 += load(r0 + j) * x, a1 += load(r1 + j) * x, a2 += load(r2 + j) * x;
        a3 += load(r3 + j) * x, a4 += load(r4 + j) * x, a5 += load(r5 + j) * x;
        a6 += load(r6 + j) * x, a7 += load(r7 + j) * x;
      }
      gates[g] += lane_sums(a0, a1, a2, a3, a4, a5, a6, a7);
    }
    cell8(gates[0], gates[1], gates[2], gates[3], c + u, h + u);
  }
}

// gates[r] = z[r] + sum_j h[j] wt[j][r] for r < outputs (a multiple of 64), wt row-major
// `inputs` x `outputs`: for a small recurrent matrix that stays in L1.
SKYFUSE_LSTM_KERNEL void recur_columns(const float* wt, int inputs, int outputs, const float* z,
                                       const float* h, float* gates) {
  for (int r = 0; r < outputs; r += 64) {
    F8 a0 = load(z + r), a1 = load(z + r + 8), a2 = load(z + r + 16), a3 = load(z + r + 24);
    F8 a4 = load(z + r + 32), a5 = load(z + r + 40), a6 = load(z + r + 48);
    F8 a7 = load(z + r + 56);
    const float* w = wt + r;
    for (int j = 0; j < inputs; ++j, w += outputs) {
      const F8 s = splat(h[j]);
      a0 += load(w) * s, a1 += load(w + 8) * s, a2 += load(w + 16) * s, a3 += load(w + 24) * s;
      a4 += load(w + 32) * s, a5 += load(w + 40) * s, a6 += load(w + 48) * s;
      a7 += load(w + 56) * s;
    }
    store(gates + r, a0), store(gates + r + 8, a1), store(gates + r + 16, a2);
    store(gates + r + 24, a3), store(gates + r + 32, a4), store(gates + r + 40, a5);
    store(gates + r + 48, a6), store(gates + r + 56, a7);
  }
}

// The cell update for `width` (a multiple of 8) units from gates [i f g o], each `width` long.
SKYFUSE_LSTM_KERNEL void lstm_cell(const float* gates, int width, float* c, float* h) {
  for (int u = 0; u < width; u += 8) {
    cell8(load(gates + u), load(gates + width + u), load(gates + 2 * width + u),
          load(gates + 3 * width + u), c + u, h + u);
  }
}

int padded(int width) {
  return (width + kBlock - 1) / kBlock * kBlock;
}

// Where row `gate * width + unit` of a PyTorch-ordered 4H-row matrix goes: in gate blocks
// padded to `padded_width` rows (layer 2), or interleaved by blocks of 8 units (layer 1).
Eigen::Index blocked_row(Eigen::Index row, Eigen::Index width, Eigen::Index padded_width) {
  return row / width * padded_width + row % width;
}
Eigen::Index interleaved_row(Eigen::Index row, Eigen::Index width) {
  const Eigen::Index gate = row / width;
  const Eigen::Index unit = row % width;
  return unit / 8 * 32 + gate * 8 + unit % 8;
}

// Where W[r][j] of a matrix with `inputs` columns goes in project()'s panels of 32 rows.
std::size_t panel_index(std::size_t r, std::size_t j, std::size_t inputs) {
  return r / 32 * 32 * inputs + j * 32 + r % 32;
}

}  // namespace

LstmNetwork::LstmNetwork(const LstmWeights& weights) {
  validate_lstm_weights(weights);
  if (weights.inputs() != kFeatures || weights.outputs() != kOutputs) {
    throw std::invalid_argument(
        fmt::format("LstmNetwork: weights map {} inputs to {} outputs, expected {} to {}",
                    weights.inputs(), weights.outputs(), kFeatures, kOutputs));
  }
  record_ = weights.record;
  hidden1_ = weights.lstm1.hidden();
  hidden2_ = weights.lstm2.hidden();
  padded1_ = padded(hidden1_);
  padded2_ = padded(hidden2_);
  const auto p1 = static_cast<std::size_t>(padded1_);
  const auto p2 = static_cast<std::size_t>(padded2_);
  const auto steps = static_cast<std::size_t>(kSteps);
  input_mean_ = weights.input_mean;
  input_inverse_std_ = weights.input_std.cwiseInverse();

  input1_.assign(kFeatures * 4 * p1, 0.0f);
  bias1_.assign(4 * p1, 0.0f);
  recurrent1_.assign(4 * p1 * p1, 0.0f);
  for (Eigen::Index row = 0; row < 4 * hidden1_; ++row) {
    const auto r = static_cast<std::size_t>(interleaved_row(row, hidden1_));
    bias1_[r] = weights.lstm1.bias[row];
    for (Eigen::Index j = 0; j < kFeatures; ++j) {
      input1_[panel_index(r, static_cast<std::size_t>(j), kFeatures)] = weights.lstm1.input(row, j);
    }
    for (Eigen::Index j = 0; j < hidden1_; ++j) {
      recurrent1_[r * p1 + static_cast<std::size_t>(j)] = weights.lstm1.recurrent(row, j);
    }
  }
  input2_.assign(p1 * 4 * p2, 0.0f);
  bias2_.assign(4 * p2, 0.0f);
  recurrent2_.assign(p2 * 4 * p2, 0.0f);
  for (Eigen::Index row = 0; row < 4 * hidden2_; ++row) {
    const auto r = static_cast<std::size_t>(blocked_row(row, hidden2_, padded2_));
    bias2_[r] = weights.lstm2.bias[row];
    for (Eigen::Index j = 0; j < hidden1_; ++j) {
      input2_[panel_index(r, static_cast<std::size_t>(j), p1)] = weights.lstm2.input(row, j);
    }
    for (Eigen::Index j = 0; j < hidden2_; ++j) {
      recurrent2_[static_cast<std::size_t>(j) * 4 * p2 + r] = weights.lstm2.recurrent(row, j);
    }
  }
  dense_ = weights.dense.weight;
  dense_bias_ = weights.dense.bias;
  output_mean_ = weights.output_mean;
  output_scale_ = weights.output_scale;

  inputs_.assign(steps * kFeatures, 0.0f);
  projected1_.assign(steps * 4 * p1, 0.0f);
  projected2_.assign(steps * 4 * p2, 0.0f);
  hidden1_seq_.assign((steps + 1) * p1, 0.0f);
  hidden2_seq_.assign(2 * p2, 0.0f);
  gates_.assign(4 * p2, 0.0f);
  cell1_.assign(p1, 0.0f);
  cell2_.assign(p2, 0.0f);
}

Eigen::Vector2d LstmNetwork::predict(const Window& window) {
  const int p1 = padded1_;
  const int p2 = padded2_;
  for (int t = 0; t < kSteps; ++t) {
    for (int f = 0; f < kFeatures; ++f) {
      inputs_[static_cast<std::size_t>(t * kFeatures + f)] =
          (static_cast<float>(window(t, f)) - input_mean_[f]) * input_inverse_std_[f];
    }
  }
  // Layer 1, every step; h1 before step t is row t of hidden1_seq_ (row 0: zeros, so step 0
  // skips the recurrent product).
  project(input1_.data(), kFeatures, 4 * p1, bias1_.data(), inputs_.data(), kFeatures, kSteps,
          projected1_.data());
  std::fill(cell1_.begin(), cell1_.end(), 0.0f);
  for (int t = 0; t < kSteps; ++t) {
    const float* h = hidden1_seq_.data() + static_cast<std::ptrdiff_t>(t) * p1;
    interleaved_step(recurrent1_.data(), p1,
                     projected1_.data() + static_cast<std::ptrdiff_t>(t) * 4 * p1, h, t == 0,
                     cell1_.data(), hidden1_seq_.data() + static_cast<std::ptrdiff_t>(t + 1) * p1);
  }
  // Layer 2 on layer 1's outputs (rows 1..kSteps), keeping the last step.
  project(input2_.data(), p1, 4 * p2, bias2_.data(), hidden1_seq_.data() + p1, p1, kSteps,
          projected2_.data());
  std::fill(cell2_.begin(), cell2_.end(), 0.0f);
  float* previous = hidden2_seq_.data();
  float* next = previous + p2;
  for (int t = 0; t < kSteps; ++t) {
    const float* z = projected2_.data() + static_cast<std::ptrdiff_t>(t) * 4 * p2;
    if (t > 0) recur_columns(recurrent2_.data(), p2, 4 * p2, z, previous, gates_.data());
    lstm_cell(t > 0 ? gates_.data() : z, p2, cell2_.data(), next);
    std::swap(previous, next);
  }
  const Eigen::Map<const Eigen::VectorXf> h2(previous, hidden2_);
  const Eigen::Matrix<float, kOutputs, 1> dense = dense_.lazyProduct(h2) + dense_bias_;
  return (output_mean_ + output_scale_.cwiseProduct(dense)).cast<double>();
}

}  // namespace skyfuse::learning
