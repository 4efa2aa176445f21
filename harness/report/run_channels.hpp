#pragma once
// What a run shows a person: each round as messages on the channels Foxglove, Lichtblick and
// skyfuse's own page draw (docs/view.md) — the scene (stations, truth, the center's and every
// peer's track with its covariance ellipsoid and trail), frames, map fixes, and skyfuse's own
// round, error and mode-probability channels. JSON with JSON schemas: the foxglove.* schemas
// are written here for the fields skyfuse fills, under the names the tools know.
//
// The recording (run_recording.hpp) writes every message; a live stream sends the same ones.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "run/run_report.hpp"

namespace skyfuse::harness {

/// A channel: topic, schema name and JSON schema text.
struct ChannelSpec {
  std::string topic;
  std::string schema_name;
  std::string schema;
};

/// One message for channel `channel` (an index into RunChannels::specs()).
struct ChannelMessage {
  std::size_t channel = 0;
  std::uint64_t log_time_ns = 0;
  std::string json;
};

class RunChannels {
 public:
  // Indices into specs(); kModes only when the filter has modes.
  enum Channel : std::size_t {
    kScene,
    kStations,
    kTransforms,
    kCenterLocation,
    kTruthLocation,
    kRounds,
    kTrackErrors,
    kSummary,
    kModes,
  };

  /// `epoch_ns`: the log time of step 0 (steps follow at the scenario's time step).
  RunChannels(const RunRecorder& recorder, std::uint64_t epoch_ns);

  const std::vector<ChannelSpec>& specs() const { return specs_; }

  /// How much of a round to send. kEveryRound (a recording, or a live frame due its trails):
  /// every channel, the trails when they took a point since they were last sent (every
  /// kTrailEvery steps in a recording). kDisplayFrame (a live stream's other frames): every
  /// channel, the trails only in the first scene (an entity stays until replaced).
  /// kFiguresOnly (a live stream between frames): skyfuse's own channels, without the scene,
  /// frames and map fixes. The stations go in the first scene and every kStationsEvery scenes
  /// after it.
  enum class Detail { kEveryRound, kDisplayFrame, kFiguresOnly };

  /// The messages of `round`, in channel order.
  std::vector<ChannelMessage> round_messages(const RoundRecord& round,
                                             Detail detail = Detail::kEveryRound);
  /// A round that is not sent (a live stream thinned to its display): the trails still take
  /// its point.
  void follow(const RoundRecord& round);
  /// The run's summary (summary.json's text) at the log time after the last step.
  ChannelMessage summary_message(std::string summary_json) const;

  std::uint64_t log_time_ns(std::uint64_t step) const;
  /// Moves step 0's log time (a live stream learns it when the rounds begin).
  void set_epoch_ns(std::uint64_t epoch_ns) { epoch_ns_ = epoch_ns; }

  static constexpr std::uint64_t kTrailEvery = 10;
  static constexpr std::size_t kTrailPoints = 50;
  static constexpr std::uint64_t kStationsEvery = 250;

 private:
  struct Trail {
    std::vector<Vector3> points;
  };
  /// A round as the message builders read it: its log time, the truth's position, and every
  /// track as (node, track), the center first.
  struct RoundView {
    const RoundRecord& round;
    std::uint64_t ns = 0;
    Vector3 truth;
    std::vector<std::pair<int, const ReceivedTrack*>> tracks;
  };
  void scene_messages(const RoundView& r, bool with_trails, std::vector<ChannelMessage>& out);
  void figure_messages(const RoundView& r, std::vector<ChannelMessage>& out) const;
  void extend_trails(const RoundRecord& round);

  const RunRecorder& recorder_;
  std::uint64_t epoch_ns_;
  std::vector<ChannelSpec> specs_;
  std::uint64_t scenes_ = 0;   ///< scenes sent so far
  std::vector<Trail> trails_;  ///< truth, center, then the stations in ascending id
  bool trails_unsent_ = true;  ///< a point taken since the trails were last in a scene
};

}  // namespace skyfuse::harness
