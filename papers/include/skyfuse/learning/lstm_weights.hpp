#pragma once
/// \file
/// The trained weights of a two-layer LSTM regressor (paper 001's EC and SE networks) and the
/// versioned file that carries them from the trainer to the Eigen inference (docs/lstm.md).
///
/// The network: LSTM(inputs -> H1, every step) -> LSTM(H1 -> H2, last step) -> Dense(H2 ->
/// outputs). Each LSTM layer keeps PyTorch's gate order i, f, g, o along its 4H rows:
///   gates = W_in x_t + W_rec h_{t-1} + b,   i = sigma(gates_i),  f = sigma(gates_f),
///   g = tanh(gates_g),  o = sigma(gates_o),  c_t = f c_{t-1} + i g,  h_t = o tanh(c_t),
/// with one bias b = b_ih + b_hh (Keras keeps one bias, PyTorch two: the writer sums them).
/// The network sees (x - input_mean) / input_std and reports
/// output_mean + output_scale * dense(h2_last), per component.
///
/// File format, version 2 (all of it documented in docs/lstm.md):
///   skyfuse-lstm 2              first line, exactly
///   key value                   one per line, each key exactly once, any order:
///     network ec|se, mode smoke|reduced|full, frame absolute|relative, epochs, best_epoch,
///     train_loss, val_loss,
///     seed, windows, training_seconds (the LstmTrainingRecord), and the widths
///     inputs In, hidden1 H1, hidden2 H2, outputs Out (each in [1, 4096])
///   data                        the header's last line
///   float32 little-endian arrays, back to back, in the order of LstmWeights' members:
///   input_mean[In], input_std[In], lstm1.input[4H1 x In], lstm1.recurrent[4H1 x H1],
///   lstm1.bias[4H1], lstm2.input[4H2 x H1], lstm2.recurrent[4H2 x H2], lstm2.bias[4H2],
///   dense.weight[Out x H2], dense.bias[Out], output_mean[Out], output_scale[Out];
///   matrices row-major (PyTorch's weight_ih_l0 layout), nothing after the last array.
/// Version 1 is the same without the `frame` key (read as frame absolute).

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>

namespace skyfuse::learning {

using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The first line of every weights file is kLstmMagic, a space, and the format version.
inline constexpr const char* kLstmMagic = "skyfuse-lstm";
inline constexpr int kLstmFormatVersion = 2;

/// One LSTM layer, gates stacked i, f, g, o along the rows.
struct LstmLayerWeights {
  RowMatrixXf input;      ///< 4H x In
  RowMatrixXf recurrent;  ///< 4H x H
  Eigen::VectorXf bias;   ///< 4H, b_ih + b_hh
  int hidden() const { return static_cast<int>(recurrent.cols()); }
  int inputs() const { return static_cast<int>(input.cols()); }
};

struct DenseWeights {
  RowMatrixXf weight;    ///< Out x H2
  Eigen::VectorXf bias;  ///< Out
};

/// What the trainer records about how the weights came about.
struct LstmTrainingRecord {
  std::string network = "ec";  ///< "ec" (error compensation) or "se" (state estimation)
  std::string mode = "smoke";  ///< "smoke", "reduced" or "full"
  /// The coordinates of the window's positions the network was trained on: "absolute", or
  /// "relative" to the window's last estimate (paper001::WindowFrame). Inference must build
  /// its windows the same way.
  std::string frame = "absolute";
  int epochs = 0;           ///< epochs run
  int best_epoch = 0;       ///< the epoch whose weights these are (1-based; 0: untrained)
  double train_loss = 0.0;  ///< training loss (MSE + L2 term, m^2) at best_epoch
  double val_loss = 0.0;    ///< validation loss (MSE + L2 term, m^2) at best_epoch
  std::uint64_t seed = 0;
  std::uint64_t windows = 0;  ///< training windows per epoch
  double training_seconds = 0.0;
};

struct LstmWeights {
  LstmTrainingRecord record;
  Eigen::VectorXf input_mean;    ///< In
  Eigen::VectorXf input_std;     ///< In, every entry > 0
  LstmLayerWeights lstm1;        ///< In -> H1
  LstmLayerWeights lstm2;        ///< H1 -> H2
  DenseWeights dense;            ///< H2 -> Out
  Eigen::VectorXf output_mean;   ///< Out
  Eigen::VectorXf output_scale;  ///< Out

  int inputs() const { return static_cast<int>(input_mean.size()); }
  int outputs() const { return static_cast<int>(output_mean.size()); }
  /// Parameters as Keras counts them (one bias per LSTM layer): 89 794 for 6/128/32/2.
  long parameter_count() const;
};

/// Zero-filled weights of the given widths with the identity scalings (mean 0, std 1, scale 1):
/// a starting point for tests and for the trainer's writer.
LstmWeights make_lstm_weights(int inputs, int hidden1, int hidden2, int outputs);

/// Throws std::invalid_argument naming the first inconsistent shape, non-finite value,
/// non-positive input_std, or unknown network/mode/frame name.
void validate_lstm_weights(const LstmWeights& weights);

/// Reads a version-1 or version-2 file. Throws std::runtime_error naming the file and what is
/// wrong: it cannot be opened, wrong magic, another version, unknown/missing/duplicate/malformed
/// key, widths out of [1, 4096], data truncated or followed by more bytes, a non-finite value, a
/// non-positive input_std.
LstmWeights read_lstm_weights(const std::filesystem::path& path);

/// Writes `weights` (validated first) as a version-2 file. Throws std::invalid_argument on
/// invalid weights and std::runtime_error when the file cannot be written.
void write_lstm_weights(const std::filesystem::path& path, const LstmWeights& weights);

}  // namespace skyfuse::learning
