#pragma once
// What a run of many aircraft shows a person, round by round, on the channels Foxglove,
// Lichtblick and skyfuse's own page draw (docs/view.md): the picture (every track with its id,
// status and 95 % ellipsoid, the confirmed ones with a trail), every station's detections of the
// round (false alarms apart), the aircraft, the stations, a GeoJSON of the tracks for a map, and
// skyfuse's own round and picture (GOSPA and its parts, counts) channels.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "report/run_channels.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/metrics/picture_score.hpp"
#include "skyfuse/sim/picture_detections.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/sensor_bias.hpp"

namespace skyfuse::harness {

/// One track of a round's picture, as drawn.
struct FrameTrack {
  std::uint64_t id = 0;
  std::uint16_t number = 0;  ///< the short number its node gave it (0: none)
  bool confirmed = false;
  Vector3 position = Vector3::Zero();
  Eigen::Matrix3d position_covariance = Eigen::Matrix3d::Identity();
};

/// One node's part in a round: whether its picture came, and how many stations' scans it fused.
struct FrameNode {
  int node = 0;
  bool delivered = false;
  std::uint32_t scans_fused = 0;
};

/// A registered station's bias estimate after a round, as the first station's picture holds it.
struct FrameBias {
  int station_id = 0;
  SensorBias estimate;
  SensorBias sigma;  ///< 0 for an entry the station's sensor does not have
};

/// A round of a run of many aircraft, as the harness saw it.
struct PictureFrame {
  int step = 0;
  std::vector<FrameTrack> tracks;    ///< the first station's picture, ascending id
  std::vector<TruthPoint> aircraft;  ///< filled by add_scene (run/picture_frame.hpp)
  std::vector<ScanPositions> scans;  ///< filled by add_scene
  PictureStep score;                 ///< the first station's confirmed tracks against the aircraft
  std::vector<FrameNode> nodes;      ///< the center (0) first, then the stations ascending
  bool peers_agree = true;
  std::uint64_t digest = 0;
  double latency_ms = 0.0;  ///< how long the round took to come in (picture_run.cpp says from when)
  std::vector<FrameBias> biases;  ///< the first station's, where the tracker registers
};

class PictureChannels {
 public:
  /// kRegistration only where the scenario registers its stations.
  enum Channel : std::size_t {
    kScene,
    kStations,
    kTracksGeoJson,
    kRounds,
    kPicture,
    kSummary,
    kRegistration
  };

  /// `epoch_ns`: the log time of step 0 (steps follow at the scenario's time step).
  PictureChannels(const PicturePlan& plan, std::uint64_t epoch_ns);

  const std::vector<ChannelSpec>& specs() const { return specs_; }
  /// The messages of `frame`, in channel order; the trails take a point every kTrailEvery
  /// steps and go out when they took one. Without `scene` (a live stream between frames) only
  /// skyfuse's round and picture channels.
  std::vector<ChannelMessage> frame_messages(const PictureFrame& frame, bool scene = true);
  /// A round that is not sent (a live stream thinned to its display): the trails still take
  /// its point, and the tracks it dropped leave the next scene sent.
  void follow(const PictureFrame& frame);
  /// Moves step 0's log time (a live stream learns it when the rounds begin).
  void set_epoch_ns(std::uint64_t epoch_ns) { epoch_ns_ = epoch_ns; }
  /// The run's summary (summary.json's text) at the log time after the last step.
  ChannelMessage summary_message(std::string summary_json, int steps) const;
  std::uint64_t log_time_ns(int step) const;
  /// A track's label: "T" and the short number its node gave it (its long id past the
  /// numbers).
  static std::string track_name(const FrameTrack& track);

  static constexpr int kTrailEvery = 10;
  static constexpr std::size_t kTrailPoints = 30;

 private:
  void scene_messages(const PictureFrame& frame, std::uint64_t ns,
                      std::vector<ChannelMessage>& out);
  void figure_messages(const PictureFrame& frame, std::uint64_t ns,
                       std::vector<ChannelMessage>& out) const;

  const PicturePlan& plan_;
  std::uint64_t epoch_ns_;
  std::vector<ChannelSpec> specs_;
  bool stations_sent_ = false;
  std::map<std::uint64_t, std::vector<Vector3>> trails_;  ///< confirmed tracks' trails
  bool trails_unsent_ = false;   ///< a trail took a point since the trails were last sent
  std::set<std::string> shown_;  ///< the tracks' and aircraft's entities of the last round
  std::set<std::string> gone_;   ///< entities gone since the last scene sent
};

}  // namespace skyfuse::harness
