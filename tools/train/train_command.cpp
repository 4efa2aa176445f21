#include "train_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <chrono>
#include <fstream>
#include <set>
#include <stdexcept>

#include "lstm_trainer.hpp"

namespace skyfuse::train {
namespace {

// The BLAS libraries mapped into this process (Debian: the libblas.so.3 alternative decides
// which OpenBLAS build libtorch gets).
std::string loaded_blas() {
  std::ifstream maps("/proc/self/maps");
  std::set<std::string> paths;
  for (std::string line; std::getline(maps, line);) {
    const auto slash = line.find('/');
    if (slash != std::string::npos && line.find("blas", slash) != std::string::npos) {
      paths.insert(line.substr(slash));
    }
  }
  std::string joined;
  for (const std::string& p : paths) joined += (joined.empty() ? "" : ", ") + p;
  return joined.empty() ? "none found in /proc/self/maps" : joined;
}

}  // namespace

int run_train_command(const CommandOptions& options, std::ostream& out) {
  using Clock = std::chrono::steady_clock;
  TrainConfig config = preset(options.network, options.mode);
  if (options.seed) config.seed = *options.seed;
  if (options.paths) config.paths = *options.paths;
  if (options.max_epochs) config.max_epochs = *options.max_epochs;
  if (options.patience) config.patience = *options.patience;
  if (options.frame) config.frame = *options.frame;
  if (config.paths < 10) throw std::invalid_argument("--paths must be at least 10");
  if (config.network == paper001::Network::kStateEstimation &&
      config.frame == paper001::WindowFrame::kRelative) {
    throw std::invalid_argument(
        "--frame relative is for ec only: se outputs the position, which a window relative to "
        "its last estimate no longer holds");
  }
  torch::set_num_threads(options.threads);

  paper001::DataSetup data;
  data.paths = config.paths;
  fmt::print(out, "skyfuse-train: network {} mode {} frame {}\n", network_name(config.network),
             mode_name(config.mode), paper001::name_of(config.frame));
  fmt::print(out,
             "  data: {} paths (7:2:1 by path), {} steps each, data seed {}, window stride {}\n",
             data.paths, data.path.steps, data.seed, config.stride);
  fmt::print(out, "  training: batch {}, max epochs {}, patience {}, torch seed {}, threads {}\n",
             config.batch, config.max_epochs, config.patience, config.seed,
             torch::get_num_threads());
  fmt::print(out, "  BLAS: {}\n", loaded_blas());
  // Built only to be counted; train() reseeds before it builds its own.
  fmt::print(out,
             "  parameters: {} trainable (Keras counting: one bias per LSTM layer; PyTorch's "
             "second bias b_hh is held at zero and frozen)\n",
             KerasLstm(paper001::kWindowFeatures, config.hidden1, config.hidden2, 2, config.dropout)
                 ->trainable_parameters());
  out.flush();

  const auto data_begin = Clock::now();
  const WindowTensors train_windows = to_tensors(paper001::make_windows(
      data, paper001::Split::kTrain, config.network, config.stride, config.frame));
  const WindowTensors val_windows = to_tensors(paper001::make_windows(
      data, paper001::Split::kValidation, config.network, config.stride, config.frame));
  fmt::print(out, "  windows: {} train, {} validation ({:.1f} s to build)\n",
             train_windows.inputs.size(0), val_windows.inputs.size(0),
             std::chrono::duration<double>(Clock::now() - data_begin).count());

  std::ofstream csv;
  if (!options.log.empty()) {
    csv.open(options.log, std::ios::trunc);
    if (!csv) throw std::runtime_error("cannot write the log " + options.log);
    csv << "epoch,train_loss,val_loss,val_mse_m2,seconds\n";
  }
  bool first = true;
  const TrainResult result = train(config, train_windows, val_windows, [&](const EpochLog& e) {
    if (first) {
      fmt::print(out, "  {:>5}  {:>12}  {:>12}  {:>12}  {:>9}\n", "epoch", "train_loss", "val_loss",
                 "val_mse_m2", "seconds");
      first = false;
    }
    fmt::print(out, "  {:>5}  {:>12.6g}  {:>12.6g}  {:>12.6g}  {:>9.1f}\n", e.epoch, e.train_loss,
               e.val_loss, e.val_mse_m2, e.seconds);
    out.flush();
    if (csv.is_open()) {
      csv << fmt::format("{},{:.9g},{:.9g},{:.9g},{:.3f}\n", e.epoch, e.train_loss, e.val_loss,
                         e.val_mse_m2, e.seconds);
      csv.flush();
    }
  });
  const learning::LstmTrainingRecord& r = result.weights.record;
  learning::write_lstm_weights(options.out, result.weights);
  fmt::print(out,
             "  done: {} epochs, best epoch {} (train loss {:.6g}, val loss {:.6g}), {:.1f} s; "
             "wrote {}\n",
             r.epochs, r.best_epoch, r.train_loss, r.val_loss, r.training_seconds, options.out);
  return 0;
}

}  // namespace skyfuse::train
