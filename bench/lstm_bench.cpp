// Cost of paper 001's LSTM inference on one 14-step window of 6 features (LstmNetwork, float):
//   BM_LstmWindow   two LSTM layers (128, 32) and the dense layer, random weights (fixed seed)
#include <benchmark/benchmark.h>

#include <random>

#include "skyfuse/learning/lstm_network.hpp"
#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::learning {
namespace {

// Uniform weights of about Keras' initial scale: the gates neither saturate nor vanish.
LstmWeights random_weights(int hidden1, int hidden2, std::uint32_t seed) {
  LstmWeights w =
      make_lstm_weights(LstmNetwork::kFeatures, hidden1, hidden2, LstmNetwork::kOutputs);
  std::mt19937 rng(seed);
  auto fill = [&](auto& array, float bound) {
    std::uniform_real_distribution<float> u(-bound, bound);
    for (Eigen::Index i = 0; i < array.size(); ++i) array.data()[i] = u(rng);
  };
  fill(w.lstm1.input, 0.2f);
  fill(w.lstm1.recurrent, 0.1f);
  fill(w.lstm1.bias, 0.1f);
  fill(w.lstm2.input, 0.1f);
  fill(w.lstm2.recurrent, 0.2f);
  fill(w.lstm2.bias, 0.1f);
  fill(w.dense.weight, 0.4f);
  w.input_std.setConstant(100.0f);
  w.output_scale.setConstant(3.0f);
  return w;
}

void BM_LstmWindow(benchmark::State& state) {
  LstmNetwork network(random_weights(128, 32, 20240001));
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 100.0);
  LstmNetwork::Window window;
  for (Eigen::Index i = 0; i < window.size(); ++i) window.data()[i] = n(rng);
  for (auto _ : state) {
    benchmark::DoNotOptimize(window.data());
    benchmark::DoNotOptimize(network.predict(window));
  }
}
BENCHMARK(BM_LstmWindow)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace skyfuse::learning

BENCHMARK_MAIN();
