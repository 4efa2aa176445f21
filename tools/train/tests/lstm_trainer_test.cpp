// The trainer: it learns, its model is the one skyfuse's Eigen inference computes, and what it
// writes reads back. Built only with SKYFUSE_BUILD_TRAINING (ctest label `training`).
#include "lstm_trainer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "skyfuse/learning/lstm_network.hpp"
#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::train {
namespace {

using paper001::Network;

struct TinyData {
  WindowTensors train;
  WindowTensors validation;
};

// 30 paths of the real data set (21 train, 6 validation), every 14th step.
// Windows in the frame each network's preset uses.
TinyData tiny_data(Network network) {
  paper001::DataSetup setup;
  setup.paths = 30;
  const paper001::WindowFrame frame = preset(network, Mode::kSmoke).frame;
  return {
      to_tensors(paper001::make_windows(setup, paper001::Split::kTrain, network, 14, frame)),
      to_tensors(paper001::make_windows(setup, paper001::Split::kValidation, network, 14, frame))};
}

// Smoke training: 12 epochs of 4-5 batches on the tiny set (SE, narrower layers). The
// full-batch training MSE after them (through LstmNetwork) must be well below that of the
// initial weights (through libtorch, eval mode), and the epoch loss must fall.
TEST(LstmTrainer, SmokeTrainingLowersTheLoss) {
  torch::set_num_threads(1);
  const TinyData data = tiny_data(Network::kStateEstimation);
  TrainConfig config = preset(Network::kStateEstimation, Mode::kSmoke);
  config.batch = 128;
  config.max_epochs = 12;
  config.hidden1 = 32;
  config.hidden2 = 16;

  torch::manual_seed(config.seed);
  const Scaling scaling = fit_scaling(data.train, config.network);
  KerasLstm initial(6, config.hidden1, config.hidden2, 2, config.dropout);
  const double before = evaluate(initial, apply_scaling(data.train, scaling), scaling, 0.0).mse_m2;

  const TrainResult result = train(config, data.train, data.validation);
  ASSERT_EQ(result.log.size(), 12u);
  // The trained weights through skyfuse's inference, MSE in metres^2 as `before`.
  learning::LstmNetwork trained(result.weights);
  double after = 0.0;
  const std::int64_t n = data.train.inputs.size(0);
  const torch::Tensor inputs = data.train.inputs.to(torch::kDouble).contiguous();
  for (std::int64_t k = 0; k < n; ++k) {
    const Eigen::Map<const Eigen::Matrix<double, 14, 6, Eigen::RowMajor>> window(
        inputs[k].data_ptr<double>());
    const Eigen::Vector2d target(data.train.targets[k][0].item<double>(),
                                 data.train.targets[k][1].item<double>());
    after += (trained.predict(window) - target).squaredNorm() / 2.0;
  }
  after /= static_cast<double>(n);
  EXPECT_LT(after, 0.8 * before) << "initial MSE " << before << " m^2";
  EXPECT_LT(result.log.back().train_loss, result.log.front().train_loss);
}

TEST(LstmTrainer, CountsKerasParameters) {
  KerasLstm model(6, 128, 32, 2, 0.1);
  EXPECT_EQ(model->trainable_parameters(), 89794);
}

// The Eigen forward pass (LstmNetwork, float) against libtorch's (eval mode) on the same
// weights: random Keras-initialised weights with random nonzero biases in both b_ih and b_hh
// (the file stores their sum), a non-trivial input and output scaling, 64 random windows.
// Tolerance: 1e-5 times the largest |output| over the windows (per component), plus 1e-6.
TEST(LstmTrainer, EigenForwardMatchesLibtorch) {
  torch::manual_seed(7);
  KerasLstm model(6, 128, 32, 2, 0.1);
  {
    torch::NoGradGuard no_grad;
    for (auto& p : model->named_parameters()) {
      if (p.key().find("bias") != std::string::npos) p.value().uniform_(-0.3, 0.3);
    }
  }
  model->eval();
  Scaling scaling;
  scaling.input_mean = torch::tensor({10.0f, -2.0f, 30.0f, 4.0f, 11.0f, 29.0f});
  scaling.input_std = torch::tensor({200.0f, 12.0f, 210.0f, 13.0f, 201.0f, 211.0f});
  scaling.output_mean = torch::tensor({1.0f, 0.04f});
  scaling.output_scale = torch::tensor({210.0f, 213.0f});
  learning::LstmTrainingRecord record;
  record.network = "se";
  record.mode = "smoke";
  learning::LstmNetwork network(to_weights(model, scaling, record));

  const torch::Tensor raw = torch::randn({64, 14, 6}) * 150.0;
  torch::Tensor expected;
  {
    torch::NoGradGuard no_grad;
    expected =
        model->forward((raw - scaling.input_mean) / scaling.input_std) * scaling.output_scale +
        scaling.output_mean;
  }
  const torch::Tensor raw_double = raw.to(torch::kDouble).contiguous();
  const double magnitude = expected.abs().max().item<double>();
  for (std::int64_t k = 0; k < raw.size(0); ++k) {
    const Eigen::Map<const Eigen::Matrix<double, 14, 6, Eigen::RowMajor>> window(
        raw_double[k].data_ptr<double>());
    const Eigen::Vector2d out = network.predict(window);
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(out[c], expected[k][c].item<double>(), 1e-5 * magnitude + 1e-6)
          << "window " << k << " output " << c;
    }
  }
}

TEST(LstmTrainer, WrittenFileReadsBackWithTheSameShapes) {
  const TinyData data = tiny_data(Network::kErrorCompensation);
  TrainConfig config = preset(Network::kErrorCompensation, Mode::kSmoke);
  config.max_epochs = 1;
  const TrainResult result = train(config, data.train, data.validation);
  const auto path = std::filesystem::temp_directory_path() /
                    ("skyfuse_train_test_" + std::to_string(::getpid()) + ".lstm");
  learning::write_lstm_weights(path, result.weights);
  const learning::LstmWeights back = learning::read_lstm_weights(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.inputs(), 6);
  EXPECT_EQ(back.outputs(), 2);
  EXPECT_EQ(back.lstm1.hidden(), 128);
  EXPECT_EQ(back.lstm2.hidden(), 32);
  EXPECT_EQ(back.lstm1.input.rows(), 512);
  EXPECT_EQ(back.lstm1.input.cols(), 6);
  EXPECT_EQ(back.lstm2.input.cols(), 128);
  EXPECT_EQ(back.dense.weight.rows(), 2);
  EXPECT_EQ(back.dense.weight.cols(), 32);
  EXPECT_EQ(back.parameter_count(), 89794);
  EXPECT_EQ(back.record.network, "ec");
  EXPECT_EQ(back.record.mode, "smoke");
  EXPECT_EQ(back.record.frame, "relative");
  EXPECT_EQ(back.record.epochs, 1);
  EXPECT_EQ(back.record.best_epoch, 1);
  EXPECT_EQ(back.record.windows, static_cast<std::uint64_t>(data.train.inputs.size(0)));
  EXPECT_EQ(back.lstm1.recurrent, result.weights.lstm1.recurrent);
  // EC's targets stay in metres.
  EXPECT_EQ(back.output_scale, Eigen::Vector2f::Ones());
}

}  // namespace
}  // namespace skyfuse::train
