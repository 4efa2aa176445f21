#pragma once
/// \file
/// An experiment, as read from a scenario YAML file (see scenarios/paper000.yaml for every
/// field with its unit). Plain data: loading and validation live in scenario_loader.hpp.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/height_band.hpp"
#include "skyfuse/picture/tracker_config.hpp"
#include "skyfuse/traffic/detection_model.hpp"

namespace skyfuse {

/// A participant's sensor: its kind (a name in the registry) and its own fields.
struct SensorConfig {
  std::string kind = "range_azimuth_elevation";
  /// Nominal standard deviation of each measured component before scaling, in the order and
  /// units the sensor names them (range_azimuth_elevation: [range m, azimuth rad, elevation
  /// rad]).
  Eigen::VectorXd noise_std;
  /// A sensor of several receivers (multilateration): the sites of those beside the one at the
  /// station's position, world frame (m); empty for every other sensor.
  std::vector<Vector3> receivers_m;
  /// A sensor that measures no height (a 2-D radar): the heights it assumes
  /// (`sensor.height_band_m`); none for every other sensor.
  std::optional<HeightBand> height_band_m;
};

struct StationConfig {
  int id = 0;
  /// Where the station stands; zero, and unused, for a sensor that rides on the target.
  Vector3 position_m = Vector3::Zero();
  SensorConfig sensor;
  /// Fusion weight w_i of this station's increments.
  double weight = 1.0;
  /// A run with many aircraft: this station's probability of detection, field of view and
  /// clutter — its own `detection:` over the scenario's, or the scenario's
  /// (TrafficConfig::detection) — resolved once by the loader; none for one aircraft.
  std::optional<DetectionConfig> detection;
};

/// A change of the target's motion over a time window, aligned to whole steps.
struct Manoeuvre {
  enum class Kind { kAccelerate, kTurn };
  Kind kind = Kind::kAccelerate;
  double start_s = 0.0;
  double duration_s = 0.0;
  /// kAccelerate: constant acceleration, world frame (m/s^2).
  Vector3 acceleration_mps2 = Vector3::Zero();
  /// kTurn: horizontal turn rate, positive counter-clockwise seen from above (rad/s).
  double turn_rate_rad_s = 0.0;
};

struct TargetConfig {
  Vector3 initial_position_m = Vector3::Zero();
  /// Unit vector of the initial direction of flight.
  Vector3 direction = Vector3::UnitX();
  /// Initial speeds to sweep (m/s); a run uses one of them.
  std::vector<double> speeds_mps;
  std::vector<Manoeuvre> manoeuvres;
};

/// How each station's actual noise covariance R_i = s_i * diag(noise_std^2) is drawn per run.
struct NoiseScaleConfig {
  enum class Model {
    kNone,   ///< s_i = 1
    kPaper,  ///< s_i = 1 + delta_i, delta_i ~ N(0,1) redrawn until s_i >= floor (truncated)
  };
  Model model = Model::kPaper;
  double floor = 0.1;
};

/// The filter's motion model: its kind (a name in the registry) and process noise.
struct MotionModelConfig {
  std::string kind = "constant_acceleration_3d";
  /// Per-step standard deviations, in the order of the model's kNoiseFields.
  Eigen::VectorXd process_noise_std;
};

/// Filter kind "imm": the station network's IMM of 3-D modes, mixed in [p; v; a; omega]
/// (models/kinematic_state.hpp): by default constant velocity (CV), the scenario's
/// constant-acceleration model (CA) and a coordinated turn (CT); `modes` may name another set the
/// registry compiles (tracking/imm_modes.hpp). Defaults are this project's choice (docs/imm.md):
/// the CV and CT modes are kept tight, since the paper's 0.5 m per step of position noise would
/// let every mode explain every step equally well and the probabilities would never move.
struct ImmConfig {
  /// The modes, in the order every probability vector and wire sample uses.
  std::vector<std::string> modes = {"constant_velocity", "constant_acceleration",
                                    "coordinated_turn"};
  /// Per-step standard deviations: CV [position m, velocity m/s]; CT [position m, velocity m/s,
  /// turn rate rad/s].
  std::array<double, 2> constant_velocity{0.01, 0.05};
  std::array<double, 3> coordinated_turn{0.01, 0.05, 0.002};
  /// p_ii, the probability of staying in a mode for a step; the rest of each row is shared
  /// equally among the other modes.
  double stay_probability = 0.99;
  /// Variance of the initial turn-rate estimate, (rad/s)^2 (P0 covers [p; v; a]).
  double initial_turn_rate_variance = 1e-4;
};

struct FilterConfig {
  /// A registered filter part (registry/filter_info.hpp, filters/parts/).
  std::string kind = "ekf";
  /// The model of kind "ekf"; the CA mode of kind "imm".
  MotionModelConfig motion_model;
  /// Kind "imm" only.
  ImmConfig imm;
  /// Diagonal of P0, one entry per state component of the motion model.
  Eigen::VectorXd initial_covariance_diag;
  /// Error of the initial estimate: fixed if set, otherwise drawn from N(0, P0) per run.
  std::optional<Eigen::VectorXd> initial_state_error;
};

/// How peers exchange a round's increments (scenario `network: {exchange, fanout}`).
struct ExchangeConfig {
  /// The largest fanout: a cluster's members all reach its aggregator.
  static constexpr int kMaxFanout = 256;
  enum class Kind {
    kFlat,  ///< every station hears every other's increment: M (M - 1) receptions a round
    kTree,  ///< clusters of `fanout` by ascending id, summed by an aggregator each
    kAuto,  ///< the default: chosen by the number of stations (chosen_exchange())
  };
  /// `auto` is the tree from this many stations on, when the filter's station processes take
  /// it: below, both exchanges hold real time at 50 Hz with room to spare and the flat one
  /// has no aggregator to lose; from 16 on the tree's rounds are faster and its tracks younger
  /// (docs/performance.md, "The default exchange").
  static constexpr std::size_t kTreeFromStations = 16;
  Kind kind = Kind::kAuto;
  /// Whether `kind` is auto's choice rather than asked for: a run whose links lose, delay or
  /// re-fuse samples then goes back to flat (options::settle_exchange says why).
  bool chosen_by_size = false;
  /// The tree's stations per cluster, >= 2 (the flat exchange ignores it).
  int fanout = 8;
  /// What PeerRound takes: 0 for the flat exchange, the fanout for the tree. An `auto` not yet
  /// chosen (resolve_exchange()) counts as flat.
  std::size_t round_fanout() const {
    return kind == Kind::kTree ? static_cast<std::size_t>(fanout) : 0;
  }
};
/// "flat", "tree" or "auto"; and back (nothing for another name).
std::string_view to_string(ExchangeConfig::Kind kind);
std::optional<ExchangeConfig::Kind> parse_exchange_kind(std::string_view name);

/// Where the scenario's frame sits on the Earth, reading x as east, y as north and z as up (m):
/// for maps only (a recording's foxglove.LocationFix); no filter uses it. The default, for a
/// scenario without an `anchor`, is an open field near Munich.
struct GeoAnchor {
  double latitude_deg = 48.2400;
  double longitude_deg = 11.6700;
  double altitude_m = 480.0;
};

/// The surveillance network's ASTERIX data source (`asterix: {sac, sic}`; docs/asterix.md): the
/// system area code of every record a run sends, and the system identification code of its
/// system tracks (CAT062). A station's plots and reports carry the same SAC and its id as SIC.
struct AsterixSource {
  int sac = 0;  ///< [0, 255]
  int sic = 1;  ///< [0, 255]
};

struct TrafficConfig;  // scenario/traffic_config.hpp

struct Scenario {
  std::string name;
  std::string description;
  std::uint64_t seed = 0;
  double time_step_s = 0.0;
  int steps = 0;
  TargetConfig target;
  std::vector<StationConfig> stations;
  NoiseScaleConfig noise_scale;
  FilterConfig filter;
  ExchangeConfig exchange;
  GeoAnchor anchor;
  AsterixSource asterix;
  /// Many aircraft instead of one `target` (scenario/traffic_config.hpp); shared so that a
  /// Scenario stays cheap to copy and to include.
  std::shared_ptr<const TrafficConfig> traffic;
  /// Many aircraft: the tracker's parts and settings (`tracker:`), its own part of the scenario
  /// beside the truth (`traffic:`) and the sensors' detection (`detection:`).
  TrackerConfig tracker;
  /// The file it was read from, if any (a recorded-traffic file is found relative to it).
  std::string source_path;

  bool has_many_targets() const { return traffic != nullptr; }
};

/// Applies `--exchange` and `--fanout` to `scenario`; throws std::invalid_argument naming the
/// option when the fanout is out of range.
void apply_exchange_overrides(Scenario& scenario, std::optional<ExchangeConfig::Kind> kind,
                              std::optional<int> fanout);
/// The exchange a run of `stations` uses: the scenario's, or for `auto` the tree from
/// ExchangeConfig::kTreeFromStations stations when the filter's station processes take it.
ExchangeConfig::Kind chosen_exchange(const Scenario& scenario, std::size_t stations);
/// What PeerRound takes for a run of `stations`: the chosen exchange's fanout, 0 for flat.
std::size_t round_fanout_for(const Scenario& scenario, std::size_t stations);

}  // namespace skyfuse
