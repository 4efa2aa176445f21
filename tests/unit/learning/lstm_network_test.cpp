#include "skyfuse/learning/lstm_network.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::learning {
namespace {

using Window = LstmNetwork::Window;

double sigmoid(double x) {
  return 1.0 / (1.0 + std::exp(-x));
}

// The network written out plainly in double, PyTorch's equations, no padding, no reordering.
Eigen::Vector2d reference(const LstmWeights& w, const Window& window) {
  auto layer = [](const LstmLayerWeights& l, const std::vector<Eigen::VectorXd>& xs) {
    const int hidden = l.hidden();
    Eigen::VectorXd h = Eigen::VectorXd::Zero(hidden);
    Eigen::VectorXd c = Eigen::VectorXd::Zero(hidden);
    std::vector<Eigen::VectorXd> hs;
    for (const Eigen::VectorXd& x : xs) {
      Eigen::VectorXd next_h(hidden);
      for (int u = 0; u < hidden; ++u) {
        double gate[4];
        for (int g = 0; g < 4; ++g) {
          const int row = g * hidden + u;
          double sum = l.bias[row];
          for (Eigen::Index j = 0; j < x.size(); ++j) sum += l.input(row, j) * x[j];
          for (int j = 0; j < hidden; ++j) sum += l.recurrent(row, j) * h[j];
          gate[g] = sum;
        }
        c[u] = sigmoid(gate[1]) * c[u] + sigmoid(gate[0]) * std::tanh(gate[2]);
        next_h[u] = sigmoid(gate[3]) * std::tanh(c[u]);
      }
      h = next_h;
      hs.push_back(h);
    }
    return hs;
  };
  std::vector<Eigen::VectorXd> xs;
  for (int t = 0; t < Window::RowsAtCompileTime; ++t) {
    Eigen::VectorXd x(Window::ColsAtCompileTime);
    for (int f = 0; f < x.size(); ++f) {
      x[f] = (window(t, f) - w.input_mean[f]) / static_cast<double>(w.input_std[f]);
    }
    xs.push_back(x);
  }
  const Eigen::VectorXd h2 = layer(w.lstm2, layer(w.lstm1, xs)).back();
  Eigen::Vector2d out;
  for (int k = 0; k < 2; ++k) {
    double dense = w.dense.bias[k];
    for (Eigen::Index j = 0; j < h2.size(); ++j) dense += w.dense.weight(k, j) * h2[j];
    out[k] = w.output_mean[k] + w.output_scale[k] * dense;
  }
  return out;
}

LstmWeights random_weights(int hidden1, int hidden2, unsigned seed, float bound = 0.4f) {
  LstmWeights w = make_lstm_weights(6, hidden1, hidden2, 2);
  std::mt19937 rng(seed);
  auto fill = [&](auto& array, float lo, float hi) {
    std::uniform_real_distribution<float> u(lo, hi);
    for (Eigen::Index i = 0; i < array.size(); ++i) array.data()[i] = u(rng);
  };
  fill(w.lstm1.input, -bound, bound);
  fill(w.lstm1.recurrent, -bound, bound);
  fill(w.lstm1.bias, -bound, bound);
  fill(w.lstm2.input, -bound, bound);
  fill(w.lstm2.recurrent, -bound, bound);
  fill(w.lstm2.bias, -bound, bound);
  fill(w.dense.weight, -1.0f, 1.0f);
  fill(w.dense.bias, -1.0f, 1.0f);
  fill(w.input_mean, -50.0f, 50.0f);
  fill(w.input_std, 1.0f, 100.0f);
  fill(w.output_mean, -2.0f, 2.0f);
  fill(w.output_scale, 0.5f, 3.0f);
  w.record.network = "se";
  w.record.mode = "reduced";
  w.record.epochs = 12;
  w.record.best_epoch = 11;
  w.record.train_loss = 0.1234567890123;
  w.record.val_loss = 1.0 / 3.0;
  w.record.seed = 18446744073709551615ull;
  w.record.windows = 147000;
  w.record.training_seconds = 412.5;
  return w;
}

Window random_window(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 80.0);
  Window window;
  for (Eigen::Index i = 0; i < window.size(); ++i) window.data()[i] = n(rng);
  return window;
}

// By hand: with every weight matrix zero, each gate is its bias, the same at every step, so
// c_t = F c_{t-1} + I G with I = sigma(b_i), F = sigma(b_f), G = tanh(b_g), i.e.
// c_14 = I G (1 - F^14) / (1 - F), and h_14 = sigma(b_o) tanh(c_14). Layer 2 sees layer 1 only
// through its zero input weights, and the output is mean + scale (w . h2 + b).
TEST(LstmNetwork, MatchesTheClosedFormOfAnLstmWithBiasesOnly) {
  LstmWeights w = make_lstm_weights(6, 2, 1, 2);
  w.lstm1.bias << 0.5f, -0.25f, 1.0f, 0.0f, 0.3f, 0.2f, -0.7f, 0.9f;
  w.lstm2.bias << 0.4f, 1.0f, 0.8f, -0.2f;
  w.dense.weight << 2.0f, -1.5f;
  w.dense.bias << 0.1f, 0.2f;
  w.output_mean << 10.0f, -3.0f;
  w.output_scale << 2.0f, 0.5f;
  const double i = sigmoid(0.4);
  const double f = sigmoid(1.0);
  const double g = std::tanh(0.8);
  const double c14 = i * g * (1.0 - std::pow(f, 14)) / (1.0 - f);
  const double h2 = sigmoid(-0.2) * std::tanh(c14);
  const Eigen::Vector2d expected(10.0 + 2.0 * (2.0 * h2 + 0.1), -3.0 + 0.5 * (-1.5 * h2 + 0.2));

  LstmNetwork network(w);
  const Eigen::Vector2d out = network.predict(random_window(1));
  EXPECT_NEAR(out[0], expected[0], 1e-5);
  EXPECT_NEAR(out[1], expected[1], 1e-5);
}

// Float against the double reference: sizes that need padding (2/1, 5/3, 20/17) and the
// shipped 128/32. Tolerance: 1e-5 of the output's scale (|mean| + |scale|).
TEST(LstmNetwork, MatchesTheDoubleReference) {
  struct Size {
    int hidden1;
    int hidden2;
  };
  for (const Size size : {Size{2, 1}, Size{5, 3}, Size{20, 17}, Size{128, 32}}) {
    const float bound = size.hidden1 >= 64 ? 0.15f : 0.5f;
    const LstmWeights w = random_weights(size.hidden1, size.hidden2, 11u + size.hidden1, bound);
    LstmNetwork network(w);
    for (unsigned k = 0; k < 5; ++k) {
      const Window window = random_window(100 + k);
      const Eigen::Vector2d expected = reference(w, window);
      const Eigen::Vector2d out = network.predict(window);
      for (int c = 0; c < 2; ++c) {
        const double scale = std::abs(w.output_mean[c]) + std::abs(w.output_scale[c]);
        EXPECT_NEAR(out[c], expected[c], 1e-5 * scale)
            << "widths " << size.hidden1 << "/" << size.hidden2 << ", window " << k;
      }
    }
  }
}

TEST(LstmNetwork, RepeatedCallsGiveTheSameOutput) {
  LstmNetwork network(random_weights(128, 32, 3, 0.15f));
  const Window a = random_window(5);
  const Window b = random_window(6);
  const Eigen::Vector2d first = network.predict(a);
  network.predict(b);
  EXPECT_EQ(network.predict(a), first);
}

TEST(LstmNetwork, RefusesWeightsOfOtherInputOrOutputWidths) {
  EXPECT_THROW(LstmNetwork(make_lstm_weights(5, 4, 2, 2)), std::invalid_argument);
  EXPECT_THROW(LstmNetwork(make_lstm_weights(6, 4, 2, 3)), std::invalid_argument);
}

TEST(LstmWeights, CountsParametersAsKerasDoes) {
  // 4*128*(6+128+1) + 4*32*(128+32+1) + 2*(32+1): one bias per LSTM layer.
  EXPECT_EQ(make_lstm_weights(6, 128, 32, 2).parameter_count(), 89794);
}

class LstmWeightsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("skyfuse_lstm_") + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path path(const std::string& name) const { return dir_ / name; }

  std::string bytes_of(const std::filesystem::path& p) const {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  void write_bytes(const std::filesystem::path& p, const std::string& bytes) const {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // A valid file of widths 5/3, as bytes.
  std::string valid_file() {
    const auto p = path("valid.lstm");
    write_lstm_weights(p, random_weights(5, 3, 21));
    return bytes_of(p);
  }
  // Reading `bytes` must throw a runtime_error whose message names the file and contains
  // `what`.
  void expect_refusal(const std::string& bytes, const std::string& what) {
    const auto p = path("bad.lstm");
    write_bytes(p, bytes);
    try {
      read_lstm_weights(p);
      ADD_FAILURE() << "read a bad file, expected '" << what << "'";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(p.string()), std::string::npos) << message;
      EXPECT_NE(message.find(what), std::string::npos) << message;
    }
  }
  static std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  }

  std::filesystem::path dir_;
};

TEST_F(LstmWeightsFile, RoundTripsEveryArrayAndTheRecordExactly) {
  LstmWeights w = random_weights(5, 3, 31);
  w.record.frame = "relative";
  write_lstm_weights(path("w.lstm"), w);
  const LstmWeights r = read_lstm_weights(path("w.lstm"));
  EXPECT_EQ(r.input_mean, w.input_mean);
  EXPECT_EQ(r.input_std, w.input_std);
  EXPECT_EQ(r.lstm1.input, w.lstm1.input);
  EXPECT_EQ(r.lstm1.recurrent, w.lstm1.recurrent);
  EXPECT_EQ(r.lstm1.bias, w.lstm1.bias);
  EXPECT_EQ(r.lstm2.input, w.lstm2.input);
  EXPECT_EQ(r.lstm2.recurrent, w.lstm2.recurrent);
  EXPECT_EQ(r.lstm2.bias, w.lstm2.bias);
  EXPECT_EQ(r.dense.weight, w.dense.weight);
  EXPECT_EQ(r.dense.bias, w.dense.bias);
  EXPECT_EQ(r.output_mean, w.output_mean);
  EXPECT_EQ(r.output_scale, w.output_scale);
  EXPECT_EQ(r.record.network, w.record.network);
  EXPECT_EQ(r.record.mode, w.record.mode);
  EXPECT_EQ(r.record.frame, "relative");
  EXPECT_EQ(r.record.epochs, w.record.epochs);
  EXPECT_EQ(r.record.best_epoch, w.record.best_epoch);
  EXPECT_EQ(r.record.train_loss, w.record.train_loss);
  EXPECT_EQ(r.record.val_loss, w.record.val_loss);
  EXPECT_EQ(r.record.seed, w.record.seed);
  EXPECT_EQ(r.record.windows, w.record.windows);
  EXPECT_EQ(r.record.training_seconds, w.record.training_seconds);
  // And the network built from it computes the same.
  const Window window = random_window(4);
  EXPECT_EQ(LstmNetwork(r).predict(window), LstmNetwork(w).predict(window));
}

TEST_F(LstmWeightsFile, StartsWithTheMagicLineAndIsHeaderPlusFloats) {
  const std::string bytes = valid_file();
  EXPECT_EQ(bytes.rfind("skyfuse-lstm 2\n", 0), 0u);
  const auto data = bytes.find("\ndata\n");
  ASSERT_NE(data, std::string::npos);
  // 6+6 + 4*5*(6+5+1) + 4*3*(5+3+1) + 2*3+2 + 2+2 floats.
  EXPECT_EQ(bytes.size() - (data + 6), 4u * (12 + 240 + 108 + 8 + 4));
}

TEST_F(LstmWeightsFile, RefusesAWrongMagic) {
  expect_refusal(replaced(valid_file(), "skyfuse-lstm 2", "skyfuse-lstn 2"),
                 "not a skyfuse LSTM weights file");
  expect_refusal("", "is empty");
}

TEST_F(LstmWeightsFile, RefusesAnotherVersion) {
  expect_refusal(replaced(valid_file(), "skyfuse-lstm 2", "skyfuse-lstm 3"),
                 "unsupported format version 3");
  expect_refusal(replaced(valid_file(), "skyfuse-lstm 2", "skyfuse-lstm 0"),
                 "unsupported format version 0");
}

// Version 1 predates the frame key: its networks saw absolute positions. A version-1 file
// must not carry the key, and a version-2 file must.
TEST_F(LstmWeightsFile, ReadsVersionOneAsAbsoluteAndRequiresTheFrameFromVersionTwo) {
  const std::string v2 = valid_file();
  const std::string v1 =
      replaced(replaced(v2, "skyfuse-lstm 2", "skyfuse-lstm 1"), "frame absolute\n", "");
  write_bytes(path("v1.lstm"), v1);
  const LstmWeights old = read_lstm_weights(path("v1.lstm"));
  EXPECT_EQ(old.record.frame, "absolute");
  EXPECT_EQ(old.lstm1.input, read_lstm_weights(path("valid.lstm")).lstm1.input);
  expect_refusal(replaced(v2, "skyfuse-lstm 2", "skyfuse-lstm 1"), "known key");
  expect_refusal(replaced(v2, "frame absolute\n", ""), "lacks the key 'frame'");
  expect_refusal(replaced(v2, "frame absolute\n", "frame sideways\n"), "unknown frame 'sideways'");
}

TEST_F(LstmWeightsFile, RefusesTruncatedOrOverlongData) {
  const std::string bytes = valid_file();
  expect_refusal(bytes.substr(0, bytes.size() - 1), "truncated");
  expect_refusal(bytes.substr(0, bytes.find("data\n")), "without a 'data' line");
  expect_refusal(bytes + '\0', "more than the");
}

TEST_F(LstmWeightsFile, RefusesNonFiniteValues) {
  std::string bytes = valid_file();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // The last float is output_scale[1]; little-endian float32 (this host is little-endian).
  std::memcpy(bytes.data() + bytes.size() - 4, &nan, 4);
  expect_refusal(bytes, "output_scale has a non-finite value");
  bytes = valid_file();
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(bytes.data() + bytes.find("data\n") + 5 + 4 * 12, &inf, 4);  // lstm1.input[0]
  expect_refusal(bytes, "lstm1.input has a non-finite value");
}

TEST_F(LstmWeightsFile, RefusesBadHeaders) {
  const std::string bytes = valid_file();
  expect_refusal(replaced(bytes, "hidden1 5\n", "hidden1 0\n"), "bad shape: hidden1 is 0");
  expect_refusal(replaced(bytes, "hidden2 3\n", "hidden2 9999\n"), "bad shape: hidden2 is 9999");
  expect_refusal(replaced(bytes, "hidden1 5\n", "hidden1 6\n"), "truncated");
  expect_refusal(replaced(bytes, "hidden1 5\n", "hidden1 five\n"), "malformed value for 'hidden1'");
  expect_refusal(replaced(bytes, "hidden1 5\n", ""), "lacks the key 'hidden1'");
  expect_refusal(replaced(bytes, "hidden1 5\n", "hidden1 5\nhidden1 5\n"), "given twice");
  expect_refusal(replaced(bytes, "hidden1 5\n", "hidden1 5\ncolour blue\n"), "known key");
  expect_refusal(replaced(bytes, "network se\n", "network xy\n"), "unknown network 'xy'");
  expect_refusal(replaced(bytes, "mode reduced\n", "mode huge\n"), "unknown mode 'huge'");
  expect_refusal(replaced(bytes, "val_loss ", "val_loss nan"), "malformed value for 'val_loss'");
}

TEST_F(LstmWeightsFile, RefusesAMissingFile) {
  EXPECT_THROW(read_lstm_weights(path("absent.lstm")), std::runtime_error);
}

TEST_F(LstmWeightsFile, WriterRefusesInconsistentWeights) {
  LstmWeights w = random_weights(5, 3, 41);
  w.lstm2.input.resize(12, 4);
  EXPECT_THROW(write_lstm_weights(path("w.lstm"), w), std::invalid_argument);
  w = random_weights(5, 3, 41);
  w.input_std[2] = 0.0f;
  EXPECT_THROW(write_lstm_weights(path("w.lstm"), w), std::invalid_argument);
  w = random_weights(5, 3, 41);
  w.dense.bias[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(write_lstm_weights(path("w.lstm"), w), std::invalid_argument);
  w = random_weights(5, 3, 41);
  w.record.frame = "sideways";
  EXPECT_THROW(write_lstm_weights(path("w.lstm"), w), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path("w.lstm")));
}

}  // namespace
}  // namespace skyfuse::learning
