// skyfuse-train: trains paper 001's error-compensation (ec) or state-estimation (se) LSTM and
// writes its weights file (docs/lstm.md).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>
#include <string>

#include "skyfuse/options/number_checks.hpp"
#include "train_command.hpp"

int main(int argc, char** argv) {
  using skyfuse::paper001::Network;
  using skyfuse::train::Mode;
  CLI::App app{"Train paper 001's EC or SE LSTM with libtorch and write its weights file"};
  skyfuse::train::CommandOptions o;
  const std::map<std::string, Network> networks = {{"ec", Network::kErrorCompensation},
                                                   {"se", Network::kStateEstimation}};
  const std::map<std::string, Mode> modes = {
      {"smoke", Mode::kSmoke}, {"reduced", Mode::kReduced}, {"full", Mode::kFull}};
  std::string network;
  std::string mode;
  std::string frame;
  app.add_option("--network", network, "ec (error compensation) or se (state estimation)")
      ->required()
      ->check(CLI::IsMember({"ec", "se"}));
  app.add_option("--mode", mode, "smoke, reduced or full (docs/lstm.md)")
      ->required()
      ->check(CLI::IsMember({"smoke", "reduced", "full"}));
  app.add_option("--out", o.out, "the weights file to write")->required();
  app.add_option("--seed", o.seed, "torch seed (initialisation, shuffling, dropout); default 1");
  app.add_option("--threads", o.threads, "torch intra-op threads")
      ->capture_default_str()
      ->check(skyfuse::options::whole_number_in(1, 64));
  app.add_option("--paths", o.paths, "paths in all three splits (overrides the mode's)");
  app.add_option("--max-epochs", o.max_epochs, "overrides the mode's")
      ->check(skyfuse::options::whole_number_at_least(1));
  app.add_option("--patience", o.patience, "early-stopping patience")
      ->check(skyfuse::options::whole_number_at_least(1));
  app.add_option("--log", o.log, "CSV with one line per epoch");
  app.add_option("--frame", frame,
                 "the windows' positions: absolute, or relative to the window's last estimate "
                 "(default: relative for ec, absolute for se; docs/lstm.md)")
      ->check(CLI::IsMember({"absolute", "relative"}));
  CLI11_PARSE(app, argc, argv);
  o.network = networks.at(network);
  o.mode = modes.at(mode);
  if (!frame.empty()) o.frame = skyfuse::paper001::window_frame_named(frame);
  try {
    return skyfuse::train::run_train_command(o, std::cout);
  } catch (const std::exception& e) {
    std::cerr << "skyfuse-train: " << e.what() << '\n';
    return 1;
  }
}
