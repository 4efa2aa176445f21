#include "lstm_trainer.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace skyfuse::train {
namespace {

using paper001::Network;

constexpr int kInputs = paper001::kWindowFeatures;
constexpr int kOutputs = 2;
constexpr std::int64_t kEvalChunk = 8192;

torch::Tensor parameter(const torch::nn::Module& module, const std::string& name) {
  const auto params = module.named_parameters(/*recurse=*/false);
  const torch::Tensor* found = params.find(name);
  if (found == nullptr) throw std::logic_error("skyfuse-train: no parameter " + name);
  return *found;
}

void initialise_lstm(torch::nn::LSTM& lstm) {
  const std::int64_t hidden = lstm->options.hidden_size();
  const std::int64_t inputs = lstm->options.input_size();
  const double bound = std::sqrt(6.0 / static_cast<double>(inputs + 4 * hidden));
  parameter(*lstm, "weight_ih_l0").uniform_(-bound, bound);
  torch::nn::init::orthogonal_(parameter(*lstm, "weight_hh_l0"));
  torch::Tensor bias = parameter(*lstm, "bias_ih_l0");
  bias.zero_();
  bias.slice(0, hidden, 2 * hidden).fill_(1.0);  // forget gate
  torch::Tensor second = parameter(*lstm, "bias_hh_l0");
  second.zero_();
  second.set_requires_grad(false);
}

learning::RowMatrixXf to_matrix(const torch::Tensor& t) {
  const torch::Tensor c = t.detach().to(torch::kFloat).contiguous();
  return Eigen::Map<const learning::RowMatrixXf>(c.data_ptr<float>(), c.size(0), c.size(1));
}

Eigen::VectorXf to_vector(const torch::Tensor& t) {
  const torch::Tensor c = t.detach().to(torch::kFloat).contiguous();
  return Eigen::Map<const Eigen::VectorXf>(c.data_ptr<float>(), c.numel());
}

learning::LstmLayerWeights layer_weights(const torch::nn::LSTM& lstm) {
  learning::LstmLayerWeights w;
  w.input = to_matrix(parameter(*lstm, "weight_ih_l0"));
  w.recurrent = to_matrix(parameter(*lstm, "weight_hh_l0"));
  w.bias = to_vector(parameter(*lstm, "bias_ih_l0") + parameter(*lstm, "bias_hh_l0"));
  return w;
}

std::vector<torch::Tensor> copy_parameters(const torch::nn::Module& module) {
  std::vector<torch::Tensor> copy;
  for (const torch::Tensor& p : module.parameters()) copy.push_back(p.detach().clone());
  return copy;
}

void restore_parameters(torch::nn::Module& module, const std::vector<torch::Tensor>& copy) {
  torch::NoGradGuard no_grad;
  const std::vector<torch::Tensor> params = module.parameters();
  for (std::size_t i = 0; i < params.size(); ++i) params[i].copy_(copy[i]);
}

}  // namespace

TrainConfig preset(Network network, Mode mode) {
  TrainConfig c;
  c.network = network;
  c.mode = mode;
  c.frame = network == Network::kErrorCompensation ? paper001::WindowFrame::kRelative
                                                   : paper001::WindowFrame::kAbsolute;
  switch (mode) {
    case Mode::kSmoke:
      c.paths = 50, c.stride = 14, c.batch = 128, c.max_epochs = 3;
      break;
    case Mode::kReduced:
      c.paths = 10000, c.stride = 14, c.batch = 512, c.max_epochs = 10;
      break;
    case Mode::kFull:
      c.paths = 10000, c.stride = 3, c.batch = 3072, c.max_epochs = 1000;
      break;
  }
  return c;
}

WindowTensors to_tensors(const paper001::Windows& windows) {
  const auto n = static_cast<std::int64_t>(windows.count());
  if (windows.inputs.size() != static_cast<std::size_t>(n) * paper001::kWindowSteps * kInputs) {
    throw std::invalid_argument("skyfuse-train: window inputs and targets disagree in count");
  }
  auto* inputs = const_cast<float*>(windows.inputs.data());
  auto* targets = const_cast<float*>(windows.targets.data());
  return {torch::from_blob(inputs, {n, paper001::kWindowSteps, kInputs}, torch::kFloat).clone(),
          torch::from_blob(targets, {n, kOutputs}, torch::kFloat).clone()};
}

Scaling fit_scaling(const WindowTensors& train, Network network) {
  if (train.inputs.size(0) < 2) throw std::invalid_argument("skyfuse-train: too few windows");
  const torch::Tensor x = train.inputs.reshape({-1, kInputs}).to(torch::kDouble);
  Scaling s;
  s.input_mean = x.mean(0).to(torch::kFloat);
  s.input_std = x.std(0, /*unbiased=*/false).clamp_min(1e-6).to(torch::kFloat);
  if (network == Network::kStateEstimation) {
    const torch::Tensor y = train.targets.to(torch::kDouble);
    s.output_mean = y.mean(0).to(torch::kFloat);
    // One scale for both axes, sqrt of the mean of their (population) variances: then the
    // scaled MSE is the MSE in metres^2 divided by its square.
    s.target_scale = std::max(1e-6, std::sqrt(y.var(0, /*unbiased=*/false).mean().item<double>()));
    s.output_scale = torch::full({kOutputs}, s.target_scale, torch::kFloat);
  } else {
    s.output_mean = torch::zeros({kOutputs});
    s.output_scale = torch::ones({kOutputs});
  }
  return s;
}

WindowTensors apply_scaling(const WindowTensors& windows, const Scaling& scaling) {
  return {(windows.inputs - scaling.input_mean) / scaling.input_std,
          (windows.targets - scaling.output_mean) / scaling.output_scale};
}

KerasLstmImpl::KerasLstmImpl(int inputs, int hidden1, int hidden2, int outputs, double rate) {
  lstm1 = register_module(
      "lstm1", torch::nn::LSTM(torch::nn::LSTMOptions(inputs, hidden1).batch_first(true)));
  dropout = register_module("dropout", torch::nn::Dropout(rate));
  lstm2 = register_module(
      "lstm2", torch::nn::LSTM(torch::nn::LSTMOptions(hidden1, hidden2).batch_first(true)));
  dense = register_module("dense", torch::nn::Linear(hidden2, outputs));
  initialise();
}

torch::Tensor KerasLstmImpl::forward(const torch::Tensor& x) {
  torch::Tensor y = std::get<0>(lstm1->forward(x));
  y = dropout->forward(y);
  y = std::get<0>(lstm2->forward(y));
  return dense->forward(y.select(1, -1));
}

void KerasLstmImpl::initialise() {
  torch::NoGradGuard no_grad;
  initialise_lstm(lstm1);
  initialise_lstm(lstm2);
  const auto fan =
      static_cast<double>(dense->options.in_features() + dense->options.out_features());
  dense->weight.uniform_(-std::sqrt(6.0 / fan), std::sqrt(6.0 / fan));
  dense->bias.zero_();
}

torch::Tensor KerasLstmImpl::kernel_penalty(double target_scale) const {
  torch::Tensor lstm_sum = torch::zeros({});
  for (const torch::nn::LSTM* lstm : {&lstm1, &lstm2}) {
    lstm_sum = lstm_sum + parameter(**lstm, "weight_ih_l0").pow(2).sum() +
               parameter(**lstm, "weight_hh_l0").pow(2).sum();
  }
  return lstm_sum / (target_scale * target_scale);
}

long KerasLstmImpl::trainable_parameters() const {
  long count = 0;
  for (const torch::Tensor& p : parameters()) {
    if (p.requires_grad()) count += static_cast<long>(p.numel());
  }
  return count;
}

learning::LstmWeights to_weights(KerasLstm& model, const Scaling& scaling,
                                 const learning::LstmTrainingRecord& record) {
  learning::LstmWeights w;
  w.record = record;
  w.input_mean = to_vector(scaling.input_mean);
  w.input_std = to_vector(scaling.input_std);
  w.lstm1 = layer_weights(model->lstm1);
  w.lstm2 = layer_weights(model->lstm2);
  w.dense.weight = to_matrix(model->dense->weight);
  w.dense.bias = to_vector(model->dense->bias);
  w.output_mean = to_vector(scaling.output_mean);
  w.output_scale = to_vector(scaling.output_scale);
  learning::validate_lstm_weights(w);
  return w;
}

Evaluation evaluate(KerasLstm& model, const WindowTensors& scaled, const Scaling& scaling,
                    double l2) {
  torch::NoGradGuard no_grad;
  const bool was_training = model->is_training();
  model->eval();
  const std::int64_t n = scaled.inputs.size(0);
  torch::Tensor squared = torch::zeros({kOutputs}, torch::kDouble);
  for (std::int64_t start = 0; start < n; start += kEvalChunk) {
    const std::int64_t end = std::min(n, start + kEvalChunk);
    const torch::Tensor diff =
        model->forward(scaled.inputs.slice(0, start, end)) - scaled.targets.slice(0, start, end);
    squared += diff.to(torch::kDouble).pow(2).sum(0);
  }
  model->train(was_training);
  const torch::Tensor per_output = squared / static_cast<double>(n);
  const double s2 = scaling.target_scale * scaling.target_scale;
  Evaluation e;
  e.loss = s2 * (per_output.mean().item<double>() +
                 l2 * model->kernel_penalty(scaling.target_scale).item<double>());
  e.mse_m2 = (per_output * scaling.output_scale.to(torch::kDouble).pow(2)).mean().item<double>();
  return e;
}

TrainResult train(const TrainConfig& config, const WindowTensors& train,
                  const WindowTensors& validation,
                  const std::function<void(const EpochLog&)>& on_epoch) {
  using Clock = std::chrono::steady_clock;
  torch::manual_seed(config.seed);
  const Scaling scaling = fit_scaling(train, config.network);
  const WindowTensors tr = apply_scaling(train, scaling);
  const WindowTensors va = apply_scaling(validation, scaling);
  KerasLstm model(kInputs, config.hidden1, config.hidden2, kOutputs, config.dropout);
  std::vector<torch::Tensor> trainable;
  for (const torch::Tensor& p : model->parameters()) {
    if (p.requires_grad()) trainable.push_back(p);
  }
  torch::optim::Adam adam(
      trainable,
      torch::optim::AdamOptions(config.learning_rate).betas(std::make_tuple(0.9, 0.999)).eps(1e-7));

  TrainResult result;
  result.trainable_parameters = model->trainable_parameters();
  learning::LstmTrainingRecord record;
  record.network = network_name(config.network);
  record.mode = mode_name(config.mode);
  record.frame = paper001::name_of(config.frame);
  record.seed = config.seed;
  record.windows = static_cast<std::uint64_t>(tr.inputs.size(0));
  std::vector<torch::Tensor> best = copy_parameters(*model);
  double best_val = std::numeric_limits<double>::infinity();
  int wait = 0;
  const auto begin = Clock::now();
  const std::int64_t n = tr.inputs.size(0);
  for (int epoch = 1; epoch <= config.max_epochs; ++epoch) {
    model->train();
    const torch::Tensor order = torch::randperm(n, torch::kLong);
    double loss_sum = 0.0;
    for (std::int64_t start = 0; start < n; start += config.batch) {
      const torch::Tensor index = order.slice(0, start, std::min(n, start + config.batch));
      const torch::Tensor x = tr.inputs.index_select(0, index);
      const torch::Tensor y = tr.targets.index_select(0, index);
      adam.zero_grad();
      const torch::Tensor loss = torch::mse_loss(model->forward(x), y) +
                                 config.l2 * model->kernel_penalty(scaling.target_scale);
      loss.backward();
      adam.step();
      loss_sum += loss.item<double>() * static_cast<double>(index.size(0));
    }
    const Evaluation val = evaluate(model, va, scaling, config.l2);
    EpochLog log;
    log.epoch = epoch;
    log.train_loss =
        scaling.target_scale * scaling.target_scale * loss_sum / static_cast<double>(n);
    log.val_loss = val.loss;
    log.val_mse_m2 = val.mse_m2;
    log.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    result.log.push_back(log);
    if (on_epoch) on_epoch(log);
    record.epochs = epoch;
    if (val.loss < best_val) {
      best_val = val.loss;
      best = copy_parameters(*model);
      record.best_epoch = epoch;
      record.train_loss = log.train_loss;
      record.val_loss = log.val_loss;
      wait = 0;
    } else if (++wait >= config.patience) {
      break;
    }
  }
  restore_parameters(*model, best);
  record.training_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  result.weights = to_weights(model, scaling, record);
  return result;
}

}  // namespace skyfuse::train
