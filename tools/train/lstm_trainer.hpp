#pragma once
/// \file
/// Training of paper 001's LSTM networks with libtorch (docs/lstm.md).
///
/// The model is Keras' LSTM(128, return_sequences) -> Dropout(0.1) -> LSTM(32) -> Dense(2):
///   - one bias per LSTM layer, as Keras has: PyTorch's second bias b_hh is held at zero and
///     frozen, so the trainable parameters are Keras' 89 794; the weights file stores
///     b_ih + b_hh all the same;
///   - Keras' initialisation: Glorot-uniform input kernels (bound sqrt(6 / (In + 4H)), over
///     the whole 4H x In kernel), orthogonal recurrent kernels (the 4H x H matrix has
///     orthonormal columns, Keras' H x 4H orthonormal rows transposed), zero biases but the
///     forget gate's 1 (unit_forget_bias), a Glorot-uniform dense kernel and a zero bias;
///   - loss: MSE + 0.001 * sum(W^2) over both LSTMs' input and recurrent kernels (Keras'
///     l2(0.001) as kernel and recurrent regularisers of the LSTM layers, as the paper lists
///     them; the dense layer has none); Adam with lr 1e-3,
///     betas 0.9 / 0.999 and Keras' epsilon 1e-7; the training loss of an epoch is the mean of
///     its batches' losses (dropout on), as Keras reports it; the validation loss is the same
///     loss in eval mode over the whole validation set;
///   - early stopping on the validation loss with restore_best_weights.
/// Inputs are z-scored with the training windows' per-feature mean and (population) standard
/// deviation. SE targets are scaled too: y' = (y - mean) / s with each axis' mean and one
/// scale s = sqrt(mean of the two axes' variances) (output_mean/output_scale in the file map
/// back to metres). The network then learns y' with a dense kernel W' = W / s, and the loss it
/// minimises is the paper's divided by s^2:
///   MSE' + l2 sum W_lstm^2 / s^2 = (MSE + l2 sum W_lstm^2) / s^2,
/// the same minimiser, a better-conditioned start (and a literal l2 sum W_lstm^2 on the scaled
/// problem would regularise the LSTM kernels s^2 (about 45 000) times harder than the paper). EC
/// targets are left in metres (s = 1, output mean 0). Every loss reported (log, file) is the
/// paper's loss, in m^2: the training loss times s^2.

#include <torch/torch.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "skyfuse/experiments/paper001/dataset.hpp"
#include "skyfuse/learning/lstm_weights.hpp"
#include "train_mode.hpp"

namespace skyfuse::train {

/// What one training run does. preset() gives each mode's values; the command line may
/// override paths, epochs, patience, seed and threads.
struct TrainConfig {
  paper001::Network network = paper001::Network::kErrorCompensation;
  Mode mode = Mode::kSmoke;
  /// The windows' positions: EC learns from them relative to the window's last estimate (its
  /// target, the CVKF's error, does not depend on where the path lies); SE needs them as
  /// they are.
  paper001::WindowFrame frame = paper001::WindowFrame::kAbsolute;
  int paths = 50;   ///< paths in all three splits (7:2:1)
  int stride = 14;  ///< a window starts every `stride` steps, training and validation
  int batch = 128;
  int max_epochs = 3;
  int patience = 15;  ///< epochs without a better validation loss before stopping
  std::uint64_t seed = 1;
  int hidden1 = 128;
  int hidden2 = 32;
  double dropout = 0.1;
  double l2 = 0.001;
  double learning_rate = 1e-3;
};

/// smoke: 50 paths, stride 14, batch 128, 3 epochs (seconds, for CI).
/// reduced: all 10 000 paths (7000 train), stride 14, batch 512, 10 epochs (about 30 s an
///   epoch on one thread here: both networks in about 11 minutes; docs/lstm.md).
/// full: the paper's: 10 000 paths, stride 3, batch 3072, up to 1000 epochs, patience 15.
/// Every mode: EC in the relative frame, SE in the absolute one.
TrainConfig preset(paper001::Network network, Mode mode);

/// The per-feature input statistics and the output scaling stored with the weights.
struct Scaling {
  torch::Tensor input_mean;    ///< [6]
  torch::Tensor input_std;     ///< [6]
  torch::Tensor output_mean;   ///< [2]
  torch::Tensor output_scale;  ///< [2], both target_scale
  double target_scale = 1.0;   ///< s: targets are divided by it for training
};

/// Windows as tensors: inputs [N, 14, 6], targets [N, 2], both float.
struct WindowTensors {
  torch::Tensor inputs;
  torch::Tensor targets;
};
WindowTensors to_tensors(const paper001::Windows& windows);

/// The training set's scaling for `network` (targets scaled for SE only).
Scaling fit_scaling(const WindowTensors& train, paper001::Network network);

class KerasLstmImpl : public torch::nn::Module {
 public:
  KerasLstmImpl(int inputs, int hidden1, int hidden2, int outputs, double dropout);
  /// [N, T, inputs] (already scaled) -> [N, outputs] (scaled), the last step's.
  torch::Tensor forward(const torch::Tensor& x);
  /// Keras' initialisation (see the file comment), from torch's default generator.
  void initialise();
  /// sum(W^2) / s^2 over the L2-regularised kernels (both LSTMs' input and recurrent
  /// kernels), s the target scale: the paper's penalty in the scaled problem.
  torch::Tensor kernel_penalty(double target_scale = 1.0) const;
  /// Parameters Keras would count (the trainable ones: b_hh is frozen).
  long trainable_parameters() const;

  torch::nn::LSTM lstm1{nullptr};
  torch::nn::Dropout dropout{nullptr};
  torch::nn::LSTM lstm2{nullptr};
  torch::nn::Linear dense{nullptr};
};
TORCH_MODULE(KerasLstm);

/// The weights file's content for `model` with `scaling` (b_ih + b_hh as one bias).
learning::LstmWeights to_weights(KerasLstm& model, const Scaling& scaling,
                                 const learning::LstmTrainingRecord& record);

struct EpochLog {
  int epoch = 0;
  double train_loss = 0.0;  ///< mean batch loss (MSE + L2, m^2), dropout on
  double val_loss = 0.0;    ///< MSE + L2 (m^2) on the validation set, eval mode
  double val_mse_m2 = 0.0;  ///< the validation MSE in metres^2 (mean over the two outputs)
  double seconds = 0.0;     ///< since training began, at the end of this epoch
};

struct TrainResult {
  learning::LstmWeights weights;  ///< the best epoch's
  std::vector<EpochLog> log;
  long trainable_parameters = 0;
};

/// Trains on `train`, selecting and early-stopping on `validation`; calls `on_epoch` after
/// each epoch. Seeds torch's generator with config.seed first: the run is a function of the
/// config, the data and the thread count.
TrainResult train(const TrainConfig& config, const WindowTensors& train,
                  const WindowTensors& validation,
                  const std::function<void(const EpochLog&)>& on_epoch = {});

/// The loss (MSE + l2 sum W^2, in the paper's units: m^2) of `model` in eval mode over scaled
/// windows, and the MSE alone (m^2, mean of the two outputs).
struct Evaluation {
  double loss = 0.0;
  double mse_m2 = 0.0;
};
Evaluation evaluate(KerasLstm& model, const WindowTensors& scaled, const Scaling& scaling,
                    double l2);

/// (x - mean) / std of inputs, (y - mean) / scale of targets.
WindowTensors apply_scaling(const WindowTensors& windows, const Scaling& scaling);

}  // namespace skyfuse::train
