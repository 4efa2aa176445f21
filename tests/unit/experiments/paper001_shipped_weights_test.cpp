// The networks shipped in data/paper001, which `skyfuse reproduce paper001` runs: their format
// version, shape, frame and one known window -> output pair each. Every build runs this, with
// or without libtorch, so a changed file or a changed inference shows here.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "skyfuse/experiments/paper001/dataset.hpp"
#include "skyfuse/learning/lstm_network.hpp"
#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::paper001 {
namespace {

struct ShippedNetwork {
  const char* file;
  const char* network;
  const char* frame;
  const char* first_line;
  Vector<2> output;  ///< for the window ending at step 100 of the first test path
};

std::string first_line_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(ShippedLstmWeights, HaveThePapersShapeTheirFrameAndAKnownOutput) {
  const ShippedNetwork shipped[] = {
      {"ec.lstm", "ec", "relative", "skyfuse-lstm 2", Vector<2>(-0.267690241, 0.373758703)},
      {"ec-absolute.lstm", "ec", "absolute", "skyfuse-lstm 1", Vector<2>(-1.03365064, 0.157479793)},
      {"se.lstm", "se", "absolute", "skyfuse-lstm 1", Vector<2>(186.721725, -17.1098518)},
  };
  const DataSetup setup;
  const TrackedPath tracked = track_path(setup, paths_in(setup, Split::kTest).front());
  for (const ShippedNetwork& s : shipped) {
    SCOPED_TRACE(s.file);
    const auto path = std::filesystem::path(SKYFUSE_SOURCE_DIR) / "data" / "paper001" / s.file;
    EXPECT_EQ(first_line_of(path), s.first_line);
    const learning::LstmWeights weights = learning::read_lstm_weights(path);
    EXPECT_EQ(weights.inputs(), kWindowFeatures);
    EXPECT_EQ(weights.lstm1.hidden(), 128);
    EXPECT_EQ(weights.lstm2.hidden(), 32);
    EXPECT_EQ(weights.outputs(), 2);
    EXPECT_EQ(weights.parameter_count(), 89794);
    EXPECT_EQ(weights.record.network, s.network);
    EXPECT_EQ(weights.record.mode, "reduced");
    EXPECT_EQ(weights.record.frame, s.frame);
    learning::LstmNetwork network(weights);
    const Vector<2> output =
        network.predict(window_features(tracked, 100, window_frame_named(s.frame)));
    // Float inference; its kernels differ by CPU (AVX2 or not) in the last bits only.
    EXPECT_NEAR(output(0), s.output(0), 1e-4 * (1.0 + std::abs(s.output(0))));
    EXPECT_NEAR(output(1), s.output(1), 1e-4 * (1.0 + std::abs(s.output(1))));
  }
}

}  // namespace
}  // namespace skyfuse::paper001
