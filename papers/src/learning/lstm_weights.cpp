#include "skyfuse/learning/lstm_weights.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace skyfuse::learning {
namespace {

constexpr int kMaxWidth = 4096;
constexpr std::array<std::string_view, 2> kNetworks = {"ec", "se"};
constexpr std::array<std::string_view, 3> kModes = {"smoke", "reduced", "full"};
constexpr std::array<std::string_view, 2> kFrames = {"absolute", "relative"};
// Version 1 had no `frame` key: its networks see absolute positions.
constexpr int kFirstVersionWithFrame = 2;

template <std::size_t N>
bool one_of(const std::string& value, const std::array<std::string_view, N>& names) {
  return std::find(names.begin(), names.end(), value) != names.end();
}

// Every array of the file, in file order, with its name for messages.
template <typename Weights, typename Visit>
void for_each_array(Weights& w, Visit&& visit) {
  visit("input_mean", w.input_mean);
  visit("input_std", w.input_std);
  visit("lstm1.input", w.lstm1.input);
  visit("lstm1.recurrent", w.lstm1.recurrent);
  visit("lstm1.bias", w.lstm1.bias);
  visit("lstm2.input", w.lstm2.input);
  visit("lstm2.recurrent", w.lstm2.recurrent);
  visit("lstm2.bias", w.lstm2.bias);
  visit("dense.weight", w.dense.weight);
  visit("dense.bias", w.dense.bias);
  visit("output_mean", w.output_mean);
  visit("output_scale", w.output_scale);
}

// Empty when the weights are consistent, otherwise what is wrong.
std::string find_problem(const LstmWeights& w) {
  if (!one_of(w.record.network, kNetworks)) {
    return fmt::format("unknown network '{}' (expected ec or se)", w.record.network);
  }
  if (!one_of(w.record.mode, kModes)) {
    return fmt::format("unknown mode '{}' (expected smoke, reduced or full)", w.record.mode);
  }
  if (!one_of(w.record.frame, kFrames)) {
    return fmt::format("unknown frame '{}' (expected absolute or relative)", w.record.frame);
  }
  const LstmTrainingRecord& r = w.record;
  if (r.epochs < 0 || r.best_epoch < 0 || r.best_epoch > r.epochs) {
    return fmt::format("best_epoch {} is outside [0, epochs = {}]", r.best_epoch, r.epochs);
  }
  if (!std::isfinite(r.train_loss) || !std::isfinite(r.val_loss) ||
      !std::isfinite(r.training_seconds) || r.training_seconds < 0.0) {
    return "train_loss, val_loss and training_seconds must be finite (seconds >= 0)";
  }
  const Eigen::Index in = w.input_mean.size();
  const Eigen::Index h1 = w.lstm1.recurrent.cols();
  const Eigen::Index h2 = w.lstm2.recurrent.cols();
  const Eigen::Index out = w.output_mean.size();
  for (const auto& [name, width] : {std::pair{"inputs", in}, std::pair{"hidden1", h1},
                                    std::pair{"hidden2", h2}, std::pair{"outputs", out}}) {
    if (width < 1 || width > kMaxWidth) {
      return fmt::format("{} is {}, outside [1, {}]", name, width, kMaxWidth);
    }
  }
  std::string problem;
  auto expect = [&](const char* name, const auto& array, Eigen::Index rows, Eigen::Index cols) {
    if (problem.empty() && (array.rows() != rows || array.cols() != cols)) {
      problem = fmt::format("{} is {} x {}, expected {} x {}", name, array.rows(), array.cols(),
                            rows, cols);
    }
  };
  expect("input_std", w.input_std, in, 1);
  expect("lstm1.input", w.lstm1.input, 4 * h1, in);
  expect("lstm1.recurrent", w.lstm1.recurrent, 4 * h1, h1);
  expect("lstm1.bias", w.lstm1.bias, 4 * h1, 1);
  expect("lstm2.input", w.lstm2.input, 4 * h2, h1);
  expect("lstm2.recurrent", w.lstm2.recurrent, 4 * h2, h2);
  expect("lstm2.bias", w.lstm2.bias, 4 * h2, 1);
  expect("dense.weight", w.dense.weight, out, h2);
  expect("dense.bias", w.dense.bias, out, 1);
  expect("output_scale", w.output_scale, out, 1);
  if (!problem.empty()) return problem;
  for_each_array(w, [&](const char* name, const auto& array) {
    if (!problem.empty()) return;
    for (Eigen::Index i = 0; i < array.size(); ++i) {
      if (!std::isfinite(array.data()[i])) {
        problem =
            fmt::format("{} has a non-finite value ({}) at index {}", name, array.data()[i], i);
        return;
      }
    }
  });
  if (!problem.empty()) return problem;
  for (Eigen::Index i = 0; i < in; ++i) {
    if (!(w.input_std[i] > 0.0f)) {
      return fmt::format("input_std[{}] is {}, not positive", i, w.input_std[i]);
    }
  }
  return {};
}

// Header values: the whole token must parse.
template <typename T>
bool parse_number(const std::string& text, T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    // libstdc++ 12 has floating-point from_chars; strtod would accept leading blanks.
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
  } else {
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size();
  }
}

std::string number_text(double value) {
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), end);
}

std::uint32_t to_little_endian(std::uint32_t bits) {
  if constexpr (std::endian::native == std::endian::big) {
    return ((bits & 0xffu) << 24) | ((bits & 0xff00u) << 8) | ((bits >> 8) & 0xff00u) |
           (bits >> 24);
  } else {
    return bits;
  }
}

}  // namespace

long LstmWeights::parameter_count() const {
  long count = 0;
  for_each_array(*this, [&](const char* name, const auto& array) {
    const std::string_view n(name);
    if (n.starts_with("lstm") || n.starts_with("dense")) count += static_cast<long>(array.size());
  });
  return count;
}

LstmWeights make_lstm_weights(int inputs, int hidden1, int hidden2, int outputs) {
  LstmWeights w;
  w.input_mean = Eigen::VectorXf::Zero(inputs);
  w.input_std = Eigen::VectorXf::Ones(inputs);
  w.lstm1.input = RowMatrixXf::Zero(4 * hidden1, inputs);
  w.lstm1.recurrent = RowMatrixXf::Zero(4 * hidden1, hidden1);
  w.lstm1.bias = Eigen::VectorXf::Zero(4 * hidden1);
  w.lstm2.input = RowMatrixXf::Zero(4 * hidden2, hidden1);
  w.lstm2.recurrent = RowMatrixXf::Zero(4 * hidden2, hidden2);
  w.lstm2.bias = Eigen::VectorXf::Zero(4 * hidden2);
  w.dense.weight = RowMatrixXf::Zero(outputs, hidden2);
  w.dense.bias = Eigen::VectorXf::Zero(outputs);
  w.output_mean = Eigen::VectorXf::Zero(outputs);
  w.output_scale = Eigen::VectorXf::Ones(outputs);
  return w;
}

void validate_lstm_weights(const LstmWeights& weights) {
  if (const std::string problem = find_problem(weights); !problem.empty()) {
    throw std::invalid_argument("LSTM weights: " + problem);
  }
}

LstmWeights read_lstm_weights(const std::filesystem::path& path) {
  auto fail = [&](const std::string& what) {
    return std::runtime_error(fmt::format("LSTM weights file {}: {}", path.string(), what));
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fail("cannot be opened");

  std::string line;
  if (!std::getline(in, line)) throw fail("is empty");
  const std::string magic = std::string(kLstmMagic) + ' ';
  if (!line.starts_with(magic)) {
    throw fail(fmt::format("not a skyfuse LSTM weights file (first line must be '{}{}')", magic,
                           kLstmFormatVersion));
  }
  int version = 0;
  if (!parse_number(line.substr(magic.size()), version)) {
    throw fail(fmt::format("malformed version in first line '{}'", line));
  }
  if (version < 1 || version > kLstmFormatVersion) {
    throw fail(fmt::format("unsupported format version {} (this build reads versions 1 to {})",
                           version, kLstmFormatVersion));
  }

  LstmWeights w;
  LstmTrainingRecord& r = w.record;
  int inputs = 0;
  int hidden1 = 0;
  int hidden2 = 0;
  int outputs = 0;
  using Parser = std::function<bool(const std::string&)>;
  auto number = [](auto& field) -> Parser {
    return [&field](const std::string& v) { return parse_number(v, field); };
  };
  auto text = [](std::string& field) -> Parser {
    return [&field](const std::string& v) {
      field = v;
      return !v.empty();
    };
  };
  std::map<std::string, Parser, std::less<>> parsers = {
      {"network", text(r.network)},
      {"mode", text(r.mode)},
      {"epochs", number(r.epochs)},
      {"best_epoch", number(r.best_epoch)},
      {"train_loss", number(r.train_loss)},
      {"val_loss", number(r.val_loss)},
      {"seed", number(r.seed)},
      {"windows", number(r.windows)},
      {"training_seconds", number(r.training_seconds)},
      {"inputs", number(inputs)},
      {"hidden1", number(hidden1)},
      {"hidden2", number(hidden2)},
      {"outputs", number(outputs)},
  };
  if (version >= kFirstVersionWithFrame) parsers.emplace("frame", text(r.frame));
  std::map<std::string, bool, std::less<>> seen;
  bool header_ended = false;
  for (int line_number = 2; std::getline(in, line); ++line_number) {
    if (line == "data") {
      header_ended = true;
      break;
    }
    if (line_number > 64) throw fail("header has no 'data' line within 64 lines");
    const std::size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    const auto parser = parsers.find(key);
    if (space == std::string::npos || parser == parsers.end()) {
      throw fail(fmt::format("line {}: expected 'key value' with a known key, got '{}'",
                             line_number, line));
    }
    if (seen[key]) throw fail(fmt::format("line {}: key '{}' given twice", line_number, key));
    seen[key] = true;
    if (!parser->second(line.substr(space + 1))) {
      throw fail(fmt::format("line {}: malformed value for '{}': '{}'", line_number, key,
                             line.substr(space + 1)));
    }
  }
  if (!header_ended) throw fail("header ends without a 'data' line");
  for (const auto& entry : parsers) {
    if (!seen[entry.first]) throw fail(fmt::format("header lacks the key '{}'", entry.first));
  }
  if (!one_of(r.network, kNetworks)) throw fail(fmt::format("unknown network '{}'", r.network));
  if (!one_of(r.mode, kModes)) throw fail(fmt::format("unknown mode '{}'", r.mode));
  if (!one_of(r.frame, kFrames)) throw fail(fmt::format("unknown frame '{}'", r.frame));
  for (const auto& [name, width] : {std::pair{"inputs", inputs}, std::pair{"hidden1", hidden1},
                                    std::pair{"hidden2", hidden2}, std::pair{"outputs", outputs}}) {
    if (width < 1 || width > kMaxWidth) {
      throw fail(fmt::format("bad shape: {} is {}, outside [1, {}]", name, width, kMaxWidth));
    }
  }

  const LstmTrainingRecord record = r;
  w = make_lstm_weights(inputs, hidden1, hidden2, outputs);
  w.record = record;
  std::size_t expected = 0;
  for_each_array(w, [&](const char*, const auto& array) {
    expected += static_cast<std::size_t>(array.size()) * sizeof(float);
  });
  std::vector<char> bytes(expected);
  in.read(bytes.data(), static_cast<std::streamsize>(expected));
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got != expected) {
    throw fail(fmt::format("truncated: the header's widths need {} bytes of data, found {}",
                           expected, got));
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    throw fail(fmt::format("more than the {} bytes of data the header's widths need", expected));
  }
  std::size_t offset = 0;
  for_each_array(w, [&](const char*, auto& array) {
    for (Eigen::Index i = 0; i < array.size(); ++i) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, bytes.data() + offset, sizeof bits);
      array.data()[i] = std::bit_cast<float>(to_little_endian(bits));
      offset += sizeof bits;
    }
  });
  if (const std::string problem = find_problem(w); !problem.empty()) throw fail(problem);
  return w;
}

void write_lstm_weights(const std::filesystem::path& path, const LstmWeights& weights) {
  validate_lstm_weights(weights);
  const LstmTrainingRecord& r = weights.record;
  std::string header = fmt::format("{} {}\n", kLstmMagic, kLstmFormatVersion);
  header += fmt::format("network {}\nmode {}\nframe {}\n", r.network, r.mode, r.frame);
  header += fmt::format("epochs {}\nbest_epoch {}\n", r.epochs, r.best_epoch);
  header += fmt::format("train_loss {}\nval_loss {}\n", number_text(r.train_loss),
                        number_text(r.val_loss));
  header += fmt::format("seed {}\nwindows {}\n", r.seed, r.windows);
  header += fmt::format("training_seconds {}\n", number_text(r.training_seconds));
  header += fmt::format("inputs {}\nhidden1 {}\nhidden2 {}\noutputs {}\n", weights.inputs(),
                        weights.lstm1.hidden(), weights.lstm2.hidden(), weights.outputs());
  header += "data\n";

  std::vector<char> bytes(header.begin(), header.end());
  for_each_array(weights, [&](const char*, const auto& array) {
    for (Eigen::Index i = 0; i < array.size(); ++i) {
      const std::uint32_t bits = to_little_endian(std::bit_cast<std::uint32_t>(array.data()[i]));
      char raw[sizeof bits];
      std::memcpy(raw, &bits, sizeof bits);
      bytes.insert(bytes.end(), raw, raw + sizeof bits);
    }
  });
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw std::runtime_error(
        fmt::format("LSTM weights file {}: cannot be opened for writing", path.string()));
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    throw std::runtime_error(fmt::format("LSTM weights file {}: write failed", path.string()));
  }
}

}  // namespace skyfuse::learning
