#include "run/lockstep_driver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <utility>

#include "run/realtime_rounds.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/drop_log.hpp"
#include "skyfuse/transport/realtime_schedule.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPollSlice = std::chrono::milliseconds(50);
// A round still open after this repeats its tick: a station restarted just before the round
// may have matched the tick writer a moment after the first copy went out. Nodes take a tick
// once, so a repeat changes nothing for the others.
constexpr auto kTickRepeat = std::chrono::milliseconds(50);

std::vector<int> with_center(std::vector<int> ids) {
  ids.push_back(kCenterNodeId);
  return ids;
}

// What is wrong with a track whatever its step and source's place in the run: another run, a
// mode that does not match its source, a track other than the one aircraft's, numbers that are
// not finite, mode probabilities that are not the run's. The harness records what the nodes fused,
// so it refuses what they refuse; lock-step and real time alike.
std::optional<DropKind> track_content_refusal(const wire::TrackEstimate& t,
                                              const std::optional<DynamicGaussianState>& estimate,
                                              std::uint64_t run_id, std::size_t modes) {
  if (t.run_id() != run_id) return DropKind::kWrongRun;
  if ((t.mode() == wire::CENTRAL) != (t.source_id() == kCenterNodeId)) {
    return DropKind::kUnknownStation;
  }
  // A run of one aircraft has the one track 0, always confirmed.
  if (t.track_id() != 0 || !t.confirmed()) return DropKind::kOutOfRange;
  if (!estimate) return DropKind::kOutOfRange;  // not the run's state dimension
  if (!estimate->mean.allFinite() || !estimate->covariance.allFinite()) {
    return DropKind::kNonFinite;
  }
  if (t.mode_probabilities().size() != modes) return DropKind::kOutOfRange;
  if (modes != 0) {
    return check_mode_probabilities(Eigen::Map<const Eigen::VectorXd>(
        t.mode_probabilities().data(), static_cast<Eigen::Index>(modes)));
  }
  return std::nullopt;
}

ReceivedTrack received_track(const wire::TrackEstimate& t, const DynamicGaussianState& estimate) {
  return {
      estimate,
      {t.contributors().begin(), t.contributors().end()},
      Eigen::Map<const Eigen::VectorXd>(t.mode_probabilities().data(),
                                        static_cast<Eigen::Index>(t.mode_probabilities().size()))};
}

// The same for a measurement: another run, or an observation the center would refuse (its
// content, or a participant's id at another site).
// Any registered sensor, as it measures the truth's kinematics (every sensor's reported values
// and checks are the same whatever the state it is linearised about).
using AnyWireSensor = AnySensor<kKinematicsDim>;

// The same for a measurement: another run, or an observation the center would refuse (its
// content, a participant's id with another sensor or at another site). Its values go to `z`.
std::optional<DropKind> measurement_content_refusal(const wire::Measurement& m,
                                                    std::uint64_t run_id,
                                                    const std::map<int, StationConfig>& stations,
                                                    Eigen::VectorXd& z) {
  if (m.run_id() != run_id) return DropKind::kWrongRun;
  const auto found = stations.find(m.station_id());  // an unknown id: admit() says so
  const StationConfig* station = found == stations.end() ? nullptr : &found->second;
  const auto observation = transport::observation_for<AnyWireSensor>(m, station);
  if (!observation) return DropKind::kOutOfRange;  // no registered sensor, or other lengths
  return with_observation(*observation, [&](const auto& o) {
    z = o.z;
    return check_station_measurement(o, station);
  });
}

std::vector<int> ids_of(std::span<const StationConfig> participants) {
  std::vector<int> ids;
  for (const StationConfig& s : participants) ids.push_back(s.id);
  return ids;
}

}  // namespace

std::string_view to_string(StopCause cause) {
  switch (cause) {
    case StopCause::kFellBehind:
      return "fell_behind";
    case StopCause::kRoundTimeout:
      return "round_timeout";
    case StopCause::kInterrupted:
      return "interrupted";
    case StopCause::kNodeFailed:
      return "node_failed";
    case StopCause::kError:
      break;
  }
  return "error";
}

std::string process_name(std::span<const int> station_ids) {
  return station_ids.size() == 1
             ? node_name(station_ids.front())
             : fmt::format("stations {}-{}", station_ids.front(), station_ids.back());
}

std::uint64_t fresh_run_id() {
  std::random_device device;
  return (static_cast<std::uint64_t>(device()) << 32) ^ device();
}

double default_discovery_timeout_s(int nodes) {
  constexpr double kFloorS = 30.0;
  constexpr double kPerNodeS = 2.0;
  return std::max(kFloorS, kPerNodeS * nodes);
}

struct LockstepDriver::Impl {
  Impl(const transport::NodeConfig& config, std::uint64_t run,
       std::span<const StationConfig> participants, TrackShape shape,
       std::function<void()> check_fn)
      : run_id(run),
        state_dim(shape.state_dim),
        modes(shape.modes),
        station_ids(ids_of(participants)),
        roster(config, run, with_center(station_ids), std::move(check_fn)),
        tracks(roster.node().make_reader<wire::TrackEstimate>()),
        measurements(roster.node().make_reader<wire::Measurement>()),
        track_collector(with_center(station_ids)),
        measurement_collector(station_ids) {
    std::sort(station_ids.begin(), station_ids.end());
    for (const StationConfig& s : participants) stations.emplace(s.id, s);
    roster.wait_set().attach(tracks);
    roster.wait_set().attach(measurements);
    const int m = static_cast<int>(station_ids.size());
    roster.expect_matched(
        "track writers", [this] { return tracks.matched(); }, m + 1);
    roster.expect_matched(
        "measurement writers", [this] { return measurements.matched(); }, m);
    roster.while_waiting([this] { drain_samples(); });
  }

  // The refusals reported since the last call, the harness's own (as of round k) with them.
  std::vector<Refusal> take_refusals(std::uint64_t k) {
    return roster.take_refusals(k, own_drops.counts());
  }

  void drain_samples() {
    wire::TrackEstimate t;
    transport::WriterId writer;
    while (tracks.take(t, &writer)) {
      if (const auto why = track_refusal(t, writer)) {
        transport::count_drop(own_drops, *why, "track", t.source_id(), t.step());
      }
    }
    wire::Measurement m;
    while (measurements.take(m, &writer)) {
      if (const auto why = measurement_refusal(m, writer)) {
        transport::count_drop(own_drops, *why, "measurement", m.station_id(), m.step());
      }
    }
  }

  // A settled track (a round's final estimate, sent as it leaves a node's lag): the content
  // checks, its source (a station's PEER track or the center's CENTRAL one), then one per
  // (step, source).
  std::optional<DropKind> settled_refusal(const wire::TrackEstimate& t,
                                          const std::optional<DynamicGaussianState>& estimate,
                                          const transport::WriterId& writer) {
    if (const auto why = track_content_refusal(t, estimate, run_id, modes)) return why;
    // (The content checks tie CENTRAL to the center's id and PEER to every other.)
    if (t.source_id() != kCenterNodeId &&
        !std::binary_search(station_ids.begin(), station_ids.end(), t.source_id())) {
      return DropKind::kUnknownStation;
    }
    if (!track_sources.accept(t.source_id(), writer)) return DropKind::kDuplicate;
    const bool inserted =
        settled.try_emplace({t.step(), t.source_id()}, received_track(t, *estimate)).second;
    if (!inserted) return DropKind::kDuplicate;
    return std::nullopt;
  }

  // The content checks, then the step window, the source and duplicates (admit).
  std::optional<DropKind> track_refusal(const wire::TrackEstimate& t,
                                        const transport::WriterId& writer) {
    const auto estimate = transport::estimate_from_wire(t, state_dim);
    if (t.settled()) return settled_refusal(t, estimate, writer);
    if (const auto why = track_content_refusal(t, estimate, run_id, modes)) return why;
    const ReceivedTrack track = received_track(t, *estimate);
    return transport::admit(track_collector, track_sources, t.step(), t.source_id(), writer, track);
  }
  std::optional<DropKind> measurement_refusal(const wire::Measurement& m,
                                              const transport::WriterId& writer) {
    Eigen::VectorXd z;
    if (const auto why = measurement_content_refusal(m, run_id, stations, z)) return why;
    return transport::admit(measurement_collector, measurement_sources, m.step(), m.station_id(),
                            writer, z);
  }

  std::uint64_t run_id;
  int state_dim;      // the run's: every track's estimate has it
  std::size_t modes;  // mode probabilities every track carries
  std::vector<int> station_ids;
  std::map<int, StationConfig> stations;  // by id: where each measurement must come from
  NodeRoster roster;
  transport::Reader<wire::TrackEstimate> tracks;
  transport::Reader<wire::Measurement> measurements;
  // Whether every node that is up has delivered its track (and every station its measurement)
  // for the current step.
  bool all_in() const {
    const auto track_ids = track_collector.station_ids();  // ascending: the center (0) first
    for (std::size_t i = 0; i < track_ids.size(); ++i) {
      if (!roster.is_down(track_ids[i]) && !track_collector.filled(i)) return false;
    }
    const auto ids = measurement_collector.station_ids();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (!roster.is_down(ids[i]) && !measurement_collector.filled(i)) return false;
    }
    return true;
  }

  StepCollector<ReceivedTrack> track_collector;
  StepCollector<Eigen::VectorXd> measurement_collector;
  std::map<int, Clock::time_point> last_heard;  // per node: when its last track arrived
  transport::SourceBinding track_sources;
  transport::SourceBinding measurement_sources;
  std::map<std::pair<std::uint64_t, int>, ReceivedTrack> settled;  // by (step, source)
  DropTally own_drops;
  LockstepDriver::RealtimeProgress realtime;  // a real-time run's, as of its last check
};

LockstepDriver::LockstepDriver(const transport::NodeConfig& config, std::uint64_t run_id,
                               std::span<const StationConfig> participants, TrackShape shape,
                               std::function<void()> check)
    : impl_(std::make_unique<Impl>(config, run_id, participants, shape, std::move(check))) {}

LockstepDriver::~LockstepDriver() = default;

NodeRoster& LockstepDriver::roster() {
  return impl_->roster;
}

RoundRecord LockstepDriver::run_round(std::uint64_t k, std::chrono::milliseconds close_after,
                                      std::chrono::milliseconds silence_limit) {
  Impl& d = *impl_;
  const auto step = static_cast<std::uint32_t>(k);
  const auto sent = Clock::now();
  d.roster.send_tick(step);
  auto last_sent = sent;

  while (true) {
    d.drain_samples();
    if (d.all_in()) break;
    d.roster.check();
    const auto now = Clock::now();
    if (now - sent >= close_after) break;  // close with what has arrived
    if (now - last_sent >= kTickRepeat) {
      d.roster.send_tick(step);
      last_sent = now;
    }
    d.roster.wait(kPollSlice);
  }

  RoundRecord record;
  record.step = k;
  record.latency = Clock::now() - sent;
  const auto track_ids = d.track_collector.station_ids();
  const auto tracks = d.track_collector.payloads();
  for (std::size_t i = 0; i < track_ids.size(); ++i) {
    const int id = track_ids[i];
    std::optional<ReceivedTrack> track;
    if (d.track_collector.filled(i)) {
      track = tracks[i];
      d.last_heard[id] = Clock::now();
    } else if (!d.roster.is_down(id) &&
               Clock::now() - std::max(d.last_heard[id], d.roster.up_since(id)) > silence_limit) {
      throw RunAborted(
          fmt::format("{} is running but sent no track for {:.1f} s (step {})", node_name(id),
                      std::chrono::duration<double>(silence_limit).count(), k),
          StopCause::kRoundTimeout);
    }
    if (id == kCenterNodeId) {
      record.central = std::move(track);
    } else {
      record.peers.push_back(std::move(track));
    }
  }
  const auto z = d.measurement_collector.payloads();
  for (std::size_t i = 0; i < z.size(); ++i) {
    record.measurements.push_back(d.measurement_collector.filled(i) ? std::optional(z[i])
                                                                    : std::nullopt);
  }
  record.refused = d.take_refusals(k);
  d.track_collector.advance();
  d.measurement_collector.advance();
  return record;
}

void LockstepDriver::run_realtime(int steps, double time_step_s,
                                  std::chrono::system_clock::time_point epoch,
                                  std::chrono::milliseconds timeout,
                                  const std::function<void(RoundRecord)>& on_round) {
  Impl& d = *impl_;
  const auto epoch_ns = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(epoch.time_since_epoch()).count());
  d.roster.send_start(epoch_ns);

  const auto total = static_cast<std::uint64_t>(steps);
  RealtimeRounds rounds(d.station_ids, total);
  std::uint64_t handed_over = 0;
  std::vector<RoundRecord> done;
  const double limit_s = std::chrono::duration<double>(timeout).count();
  // Where the run stands against its schedule; kept for realtime_progress().
  const auto note_progress = [&] {
    const auto now = std::chrono::system_clock::now();
    const double since_epoch_s = std::chrono::duration<double>(now - epoch).count();
    const auto scheduled = static_cast<std::uint64_t>(
        std::clamp(std::floor(since_epoch_s / time_step_s) + 1.0, 0.0, static_cast<double>(total)));
    const double behind_s = std::chrono::duration<double>(
                                now - transport::step_start(epoch_ns, handed_over, time_step_s))
                                .count();
    d.realtime = {scheduled, rounds.steps_reached(), std::max(0.0, behind_s)};
  };
  while (handed_over < total) {
    // The same refusals as in lock-step, by kind: content, then where the sample belongs,
    // then whether its writer speaks for its node, then duplicates.
    wire::TrackEstimate t;
    transport::WriterId writer;
    while (d.tracks.take(t, &writer)) {
      const auto estimate = transport::estimate_from_wire(t, d.state_dim);
      if (t.settled()) {
        if (const auto why = d.settled_refusal(t, estimate, writer)) {
          transport::count_drop(d.own_drops, *why, "settled track", t.source_id(), t.step());
        }
        continue;
      }
      auto why = track_content_refusal(t, estimate, d.run_id, d.modes);
      if (!why) why = rounds.check_track(t.source_id(), t.step());
      if (!why && !d.track_sources.accept(t.source_id(), writer)) why = DropKind::kDuplicate;
      if (!why) {
        const auto scheduled = transport::step_start(epoch_ns, t.step(), time_step_s);
        const double age_us =
            std::chrono::duration<double, std::micro>(std::chrono::system_clock::now() - scheduled)
                .count();
        why = rounds.offer_track(t.source_id(), t.step(), received_track(t, *estimate), age_us);
      }
      if (why) transport::count_drop(d.own_drops, *why, "track", t.source_id(), t.step());
    }
    wire::Measurement z;
    while (d.measurements.take(z, &writer)) {
      Eigen::VectorXd values;
      auto why = measurement_content_refusal(z, d.run_id, d.stations, values);
      if (!why) why = rounds.check_measurement(z.station_id(), z.step());
      if (!why && !d.measurement_sources.accept(z.station_id(), writer)) {
        why = DropKind::kDuplicate;
      }
      if (!why) why = rounds.offer_measurement(z.station_id(), z.step(), values);
      if (why) transport::count_drop(d.own_drops, *why, "measurement", z.station_id(), z.step());
    }
    handed_over = rounds.hand_over(done);
    if (!done.empty()) done.back().refused = d.take_refusals(done.back().step);
    for (RoundRecord& r : done) on_round(std::move(r));
    done.clear();
    note_progress();
    if (handed_over == total) break;
    d.roster.check();
    // The first step not yet complete was due longer ago than the limit (the schedule's end
    // included): the nodes are not catching up on this host.
    if (d.realtime.behind_s > limit_s) {
      // The steps the nodes got to, complete or not, go to the files with what arrived.
      rounds.hand_over_rest(done);
      for (RoundRecord& r : done) on_round(std::move(r));
      throw RunAborted(
          fmt::format("real-time run fell behind: {} of {} steps complete, the first step not "
                      "complete was due {:.1f} s ago (limit --round-timeout {:.1f} s); the nodes "
                      "had got to step {}",
                      handed_over, steps, d.realtime.behind_s, limit_s, d.realtime.steps_reached),
          StopCause::kFellBehind);
    }
    d.roster.wait(kPollSlice);
  }
  if (rounds.tracks_lost() + rounds.measurements_lost() > 0) {
    spdlog::warn(
        "real time: {} track(s) and {} measurement(s) never reached the harness; their steps were "
        "recorded without them once {} steps later had every track",
        rounds.tracks_lost(), rounds.measurements_lost(), RealtimeRounds::kLostAfterSteps);
  }
}

LockstepDriver::RealtimeProgress LockstepDriver::realtime_progress() const {
  return impl_->realtime;
}

std::vector<Refusal> LockstepDriver::take_refusals(std::uint64_t step) {
  return impl_->take_refusals(step);
}

std::map<int, NodeCounts> LockstepDriver::finished_counts() {
  std::map<int, NodeCounts> all = impl_->roster.finished();
  all[kHarnessNodeId].dropped = impl_->own_drops.counts();
  return all;
}

const std::map<std::pair<std::uint64_t, int>, ReceivedTrack>& LockstepDriver::settled_tracks()
    const {
  return impl_->settled;
}

}  // namespace skyfuse::harness
