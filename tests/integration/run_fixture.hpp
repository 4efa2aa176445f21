#pragma once
// Shared by the DDS integration tests: where the executables are, a fresh folder per test, and
// readers for what `skyfuse run` writes.

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "support/process.hpp"

namespace skyfuse::test {

inline std::string bin(const std::string& name) {
  return std::string(SKYFUSE_BIN_DIR) + "/" + name;
}

/// A clean folder named after the running test.
inline std::filesystem::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  const auto dir = std::filesystem::path(SKYFUSE_TEST_WORK_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

using StateRow = std::vector<double>;  // a track's state: as many entries as the run's model
using TrackRows = std::map<std::pair<int, int>, StateRow>;
/// tracks.csv as (step, source) -> state; %.17g in the file makes the values exact.
TrackRows read_tracks(const std::filesystem::path& csv);          ///< the live tracks' states
TrackRows read_settled_tracks(const std::filesystem::path& csv);  ///< the settled ones'
/// The live tracks' covariances: the upper triangle, row by row.
TrackRows read_track_covariances(const std::filesystem::path& csv);

/// The column of steps.csv named `name`, by step; throws if there is none.
std::vector<double> steps_column(const std::filesystem::path& steps_csv, const std::string& name);
/// steps.csv's peer_spread column, by step.
std::vector<double> peer_spread(const std::filesystem::path& steps_csv);

/// For a run of `steps` rounds whose links lost samples in rounds [loss_from, loss_to): expects
/// its steps.csv to show every peer the same bits before, some difference during, and the same
/// bits again from round `agree_from` on.
void expect_peers_differ_only_around_the_loss(const std::filesystem::path& steps_csv, int steps,
                                              int loss_from, int loss_to, int agree_from);

/// The in-process twin of a DDS run: its (central, peer-to-peer) means per step, as
/// simulate_run computes them (with `gate`); its trace into `trace` if given.
using TwinTracks = std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>;
TwinTracks in_process_twin(const RunPlan& plan, const NisGate& gate = {},
                           RunTrace* trace = nullptr);

/// Nothing if, at every step of the twin, the center's and every participant's state in
/// tracks.csv equal the twin's bit for bit; else the first difference, in words.
std::optional<std::string> difference_from_twin(const TrackRows& tracks, const RunPlan& plan,
                                                const TwinTracks& twin);

/// For a run of the default scenario with `stations` and `steps` that wrote its files to `out`:
/// expects every track in tracks.csv, each equal to the in-process run's bit for bit, every
/// peer the same bits and nothing refused. Returns summary.json.
nlohmann::json expect_default_run_equals_twin(const std::filesystem::path& out, int stations,
                                              int steps);

/// A long `skyfuse run` (10^6 steps) of `stations` on `domain`, writing into `dir`/out and its
/// output to `dir`/harness.log, with `extra` options; returned once its first rounds have been
/// driven (its progress line), which must happen within `started_within` (a failure otherwise).
std::unique_ptr<Process> start_long_run(
    int domain, int stations, const std::filesystem::path& dir,
    const std::vector<std::string>& extra = {},
    std::chrono::seconds started_within = std::chrono::seconds(30));

/// refusals.csv of a run of either kind in `out` lists what each node refused as the run went
/// on: its rows add up to `summary`'s counts, node by node and kind by kind, and every node's
/// first ones were reported in a round of the run's `steps`, not only in its last status.
void expect_refusals_listed_as_reported(const std::filesystem::path& out,
                                        const nlohmann::json& summary, int steps);

// The end of a small picture scenario: GOSPA's cut-off, four 3-D radars on the corners of a
// 9 km square and the EKF on constant velocity. A test's own scenario puts its traffic, detection
// and tracker before it.
inline constexpr const char* kFourRadarsAndAnEkf = R"(metrics:
  gospa_cutoff_m: 50.0
stations:
  - id: 1
    position_m: [-4500.0, -4500.0, 60.0]
    sensor: &radar {kind: range_azimuth_elevation, noise_std: [5.0, 0.0026, 0.0026]}
  - {id: 2, position_m: [4500.0, -4500.0, 80.0], sensor: *radar}
  - {id: 3, position_m: [4500.0, 4500.0, 70.0], sensor: *radar}
  - {id: 4, position_m: [-4500.0, 4500.0, 90.0], sensor: *radar}
measurement_noise:
  scale: none
filter:
  kind: ekf
  motion_model:
    kind: constant_velocity_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0}
  initial_covariance_diag: 100.0
)";

}  // namespace skyfuse::test
