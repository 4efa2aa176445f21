#include "run/run_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "report/json_values.hpp"
#include "report/output_files.hpp"
#include "report/statistics.hpp"
#include "run/refusal_rows.hpp"
#include "skyfuse/models/state_position.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/part_info.hpp"

namespace skyfuse::harness {
namespace {

// The largest difference of any mode probability (0 for a single-model run's tracks).
double mode_probability_difference(const ReceivedTrack& a, const ReceivedTrack& b) {
  if (a.mode_probabilities.size() == 0) return 0.0;
  return (a.mode_probabilities - b.mode_probabilities).cwiseAbs().maxCoeff();
}

double max_abs_entry_difference(const ReceivedTrack& a, const ReceivedTrack& b) {
  return std::max({(a.estimate.mean - b.estimate.mean).cwiseAbs().maxCoeff(),
                   (a.estimate.covariance - b.estimate.covariance).cwiseAbs().maxCoeff(),
                   mode_probability_difference(a, b)});
}

// The peer-to-peer estimate of a round: the lowest-id peer that delivered one.
const ReceivedTrack* first_peer(const RoundRecord& r) {
  for (const auto& peer : r.peers) {
    if (peer) return &*peer;
  }
  return nullptr;
}

// Largest difference between any delivered peer track and the first one.
double peer_spread(const RoundRecord& r) {
  const ReceivedTrack* first = first_peer(r);
  double spread = 0.0;
  for (const auto& peer : r.peers) {
    if (peer) spread = std::max(spread, max_abs_entry_difference(*peer, *first));
  }
  return spread;
}

// Whether any peer's track of the round contains station `id`.
bool fused_by_a_peer(const RoundRecord& r, int id) {
  return std::any_of(r.peers.begin(), r.peers.end(), [&](const auto& peer) {
    return peer && std::binary_search(peer->contributors.begin(), peer->contributors.end(), id);
  });
}

std::string node_key(int node) {
  return node == kCenterNodeId    ? std::string("center")
         : node == kHarnessNodeId ? std::string("harness")
                                  : std::to_string(node);
}

}  // namespace

RunRecorder::RunRecorder(const RunPlan& plan, std::vector<int> station_ids,
                         std::vector<StationEvent> restarts)
    : plan_(plan),
      station_ids_(std::move(station_ids)),
      restarts_(std::move(restarts)),
      truth_(plan.truth()),
      model_(*find_motion_model(plan.scenario.filter.motion_model.kind)),
      mode_names_(find_filter(plan.scenario.filter)->mode_names) {
  std::sort(station_ids_.begin(), station_ids_.end());
  rounds_.reserve(static_cast<std::size_t>(plan.scenario.steps));
}

Vector3 RunRecorder::position_of(const ReceivedTrack& track) const {
  return state_position(track.estimate.mean, model_.position_dim);
}

Vector3 RunRecorder::truth_position(std::uint64_t step) const {
  return state_position(truth_.states[step], model_.position_dim);
}

void RunRecorder::set_settled(std::map<std::pair<std::uint64_t, int>, ReceivedTrack> settled) {
  settled_ = std::move(settled);
}

std::optional<SettledFigures> RunRecorder::summarise_settled() const {
  const auto& settled = settled_;
  if (settled.empty()) return std::nullopt;
  SettledFigures f;
  f.tracks = static_cast<int>(settled.size());
  double sq = 0.0;
  double sq_central = 0.0;
  int central_rounds = 0;
  // Ordered by step, then source: the center (source 0) first, then the lowest-id peer's.
  const ReceivedTrack* first = nullptr;
  std::uint64_t step = 0;
  for (const auto& [key, track] : settled) {
    if (key.second == kCenterNodeId) {
      sq_central += (truth_position(key.first) - position_of(track)).squaredNorm();
      ++central_rounds;
      continue;
    }
    if (first == nullptr || key.first != step) {
      first = &track;
      step = key.first;
      ++f.rounds;
      sq += (truth_position(step) - position_of(track)).squaredNorm();
      f.peer_spread_end = 0.0;
      continue;
    }
    const double difference = max_abs_entry_difference(track, *first);
    f.max_abs_diff_between_peers = std::max(f.max_abs_diff_between_peers, difference);
    f.peer_spread_end = std::max(f.peer_spread_end, difference);
  }
  if (f.rounds > 0) f.rmse_p2p_m = std::sqrt(sq / f.rounds);
  if (central_rounds > 0) f.rmse_central_m = std::sqrt(sq_central / central_rounds);
  return f;
}

void RunRecorder::add(RoundRecord round) {
  rounds_.push_back(std::move(round));
}

namespace {

// summary.json's `ended`.
std::string_view ended(const RunSummary& s) {
  return s.stop_cause ? to_string(*s.stop_cause) : "complete";
}

// Tracks by age on arrival, in bins from 1 ms to 5 s (1-2-5 steps) and one beyond.
std::vector<std::pair<double, int>> age_histogram(const std::vector<double>& ages_ms) {
  std::vector<std::pair<double, int>> bins;
  for (double decade = 1.0; decade <= 1000.0; decade *= 10.0) {
    for (double step : {1.0, 2.0, 5.0}) bins.emplace_back(decade * step, 0);
  }
  bins.emplace_back(std::numeric_limits<double>::infinity(), 0);
  for (double age : ages_ms) {
    const auto bin =
        std::find_if(bins.begin(), bins.end(), [&](const auto& b) { return age <= b.first; });
    ++bin->second;
  }
  return bins;
}

}  // namespace

RunSummary RunRecorder::summarise(double discovery_s, double rounds_elapsed_s) const {
  RunSummary s;
  s.stations = plan_.stations;
  s.steps = static_cast<int>(rounds_.size());
  s.exchange = std::string(to_string(plan_.scenario.exchange.kind));
  s.fanout = static_cast<int>(plan_.scenario.exchange.round_fanout());
  s.speed_kmh = plan_.speed_mps * 3.6;
  s.discovery_s = discovery_s;
  s.imm = !mode_names_.empty();
  double sq_central = 0.0;
  double sq_p2p = 0.0;
  int n_central = 0;
  int n_p2p = 0;
  std::vector<double> latencies_us;
  for (int id : station_ids_) s.rounds_missing_by_station[id] = 0;
  for (const RoundRecord& r : rounds_) {
    const Vector3 p = truth_position(r.step);
    const ReceivedTrack* peer = first_peer(r);
    if (r.central) {
      sq_central += (p - position_of(*r.central)).squaredNorm();
      ++n_central;
    }
    if (peer) {
      sq_p2p += (p - position_of(*peer)).squaredNorm();
      ++n_p2p;
      s.max_abs_diff_between_peers = std::max(s.max_abs_diff_between_peers, peer_spread(r));
    }
    if (r.central && peer) {
      s.max_abs_diff_central_vs_p2p = std::max(
          s.max_abs_diff_central_vs_p2p, (position_of(*r.central) - position_of(*peer)).norm());
      s.max_abs_diff_mode_probability_central_vs_p2p =
          std::max(s.max_abs_diff_mode_probability_central_vs_p2p,
                   mode_probability_difference(*r.central, *peer));
    }
    for (int id : station_ids_) {
      if (!fused_by_a_peer(r, id)) ++s.rounds_missing_by_station[id];
    }
    if (!r.central || std::any_of(r.peers.begin(), r.peers.end(), [](auto& t) { return !t; })) {
      ++s.rounds_closed_incomplete;
    }
    latencies_us.push_back(std::chrono::duration<double, std::micro>(r.latency).count());
  }
  if (!rounds_.empty() && first_peer(rounds_.back()))
    s.peer_spread_end = peer_spread(rounds_.back());
  for (const StationEvent& restart : restarts_) {
    for (const RoundRecord& r : rounds_) {
      if (r.step >= restart.step && fused_by_a_peer(r, restart.station_id)) {
        s.rejoin_step_by_station[restart.station_id] = r.step;
        break;
      }
    }
  }
  std::vector<double> ages_ms;
  int in_time = 0;
  for (const RoundRecord& r : rounds_) {
    for (double age : r.track_age_us) ages_ms.push_back(age / 1000.0);
    if (r.all_inputs_in_time) ++in_time;
  }
  if (!ages_ms.empty()) {
    s.track_age_ms_p50 = percentile(ages_ms, 0.50);
    s.track_age_ms_p90 = percentile(ages_ms, 0.90);
    s.track_age_ms_p99 = percentile(ages_ms, 0.99);
    s.track_age_ms_max = *std::max_element(ages_ms.begin(), ages_ms.end());
    s.track_age_ms_histogram = age_histogram(ages_ms);
  }
  // Over the run's steps: a step never recorded (the run stopped first) was not in time.
  s.steps_planned = plan_.scenario.steps;
  s.rounds_all_inputs_in_time = in_time / std::max(1.0, static_cast<double>(s.steps_planned));
  s.rmse_central_m = std::sqrt(sq_central / std::max(1, n_central));
  s.rmse_p2p_m = std::sqrt(sq_p2p / std::max(1, n_p2p));
  s.rounds_per_s =
      rounds_elapsed_s > 0.0 ? static_cast<double>(rounds_.size()) / rounds_elapsed_s : 0.0;
  s.round_latency_us_p50 = percentile(latencies_us, 0.50);
  s.round_latency_us_p99 = percentile(latencies_us, 0.99);
  s.round_latency_us_max =
      latencies_us.empty() ? 0.0 : *std::max_element(latencies_us.begin(), latencies_us.end());
  return s;
}

bool RunRecorder::one_sensor_kind() const {
  for (const StationConfig& station : plan_.participants()) {
    if (station.sensor.kind != plan_.participants().front().sensor.kind) return false;
  }
  return true;
}

std::string RunRecorder::sensor_kind_of(int station_id) const {
  const StationConfig* station = plan_.participant(station_id);
  return station != nullptr ? station->sensor.kind : std::string();
}

std::string RunRecorder::measurements_header() const {
  if (!one_sensor_kind()) {
    int widest = 0;
    for (const StationConfig& station : plan_.participants()) {
      widest = std::max(widest, static_cast<int>(station.sensor.noise_std.size()));
    }
    std::string header = "step,station_id,sensor";
    for (int i = 0; i < widest; ++i) header += fmt::format(",z{}", i);
    return header + "\n";
  }
  const std::optional<SensorInfo> sensor = find_sensor(plan_.participants().front().sensor.kind);
  return fmt::format("step,station_id,{}\n", fmt::join(sensor->components, ","));
}

void RunRecorder::write(const std::filesystem::path& dir, const RunSummary& summary,
                        std::uint64_t run_id) const {
  std::string steps =
      "step,time_s,truth_x,truth_y,truth_z,central_x,central_y,central_z,p2p_x,p2p_y,p2p_z,"
      "error_central_m,error_p2p_m,central_minus_p2p_m,peer_spread\n";
  // tracks.csv: the state, then the covariance's upper triangle row by row (p<i>_<j>, i <= j),
  // then whether the row is a settled (re-fused) track rather than the live one.
  std::string tracks = "step,source";
  for (int i = 0; i < model_.state_dim; ++i) tracks += fmt::format(",x{}", i);
  for (int i = 0; i < model_.state_dim; ++i) {
    for (int j = i; j < model_.state_dim; ++j) tracks += fmt::format(",p{}_{}", i, j);
  }
  tracks += ",settled\n";
  const auto track_row = [&](std::uint64_t step, int source, const ReceivedTrack& track,
                             bool settled) {
    // %.17g round-trips a double exactly: the value read back is the value computed.
    tracks += fmt::format("{},{}", step, source);
    for (double v : track.estimate.mean) tracks += fmt::format(",{:.17g}", v);
    const Eigen::MatrixXd& p = track.estimate.covariance;
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
      for (Eigen::Index j = i; j < p.cols(); ++j) tracks += fmt::format(",{:.17g}", p(i, j));
    }
    tracks += settled ? ",1\n" : ",0\n";
  };
  std::string measurements = measurements_header();
  std::string rounds = "step,latency_us\n";
  std::string refusals(kRefusalsHeader);  // run/refusal_rows.hpp
  const bool imm = !mode_names_.empty();
  std::string modes = fmt::format("step,source,{}\n", fmt::join(mode_names_, ","));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const RoundRecord& r : rounds_) {
    // A node that delivered nothing leaves NaN in steps.csv and no row in the other files.
    const Vector3 p = truth_position(r.step);
    const ReceivedTrack* peer = first_peer(r);
    const Vector3 c = r.central ? position_of(*r.central) : Vector3::Constant(nan);
    const Vector3 d = peer ? position_of(*peer) : Vector3::Constant(nan);
    steps += fmt::format(
        "{},{:.3f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6e},{:.6e},{:."
        "3e},{:.3e}\n",
        r.step, static_cast<double>(r.step) * plan_.scenario.time_step_s, p.x(), p.y(), p.z(),
        c.x(), c.y(), c.z(), d.x(), d.y(), d.z(), (p - c).norm(), (p - d).norm(), (c - d).norm(),
        peer ? peer_spread(r) : nan);
    const auto add_track = [&](int source, const std::optional<ReceivedTrack>& track) {
      if (!track) return;
      track_row(r.step, source, *track, false);
      if (imm) {
        modes += fmt::format("{},{}", r.step, source);
        for (double mu : track->mode_probabilities) modes += fmt::format(",{:.17g}", mu);
        modes += '\n';
      }
    };
    add_track(0, r.central);
    for (std::size_t i = 0; i < r.peers.size(); ++i) add_track(station_ids_[i], r.peers[i]);
    for (std::size_t i = 0; i < r.measurements.size(); ++i) {
      if (!r.measurements[i]) continue;
      measurements += fmt::format("{},{}", r.step, station_ids_[i]);
      if (!one_sensor_kind()) measurements += fmt::format(",{}", sensor_kind_of(station_ids_[i]));
      for (double v : *r.measurements[i]) measurements += fmt::format(",{:.17g}", v);
      measurements += '\n';
    }
    rounds += fmt::format("{},{:.1f}\n", r.step,
                          std::chrono::duration<double, std::micro>(r.latency).count());
    append_refusal_rows(refusals, r.step, r.refused);
  }
  append_refusal_rows(refusals, static_cast<std::uint64_t>(plan_.scenario.steps),
                      refusals_after_run_);
  for (const auto& [key, track] : settled_) track_row(key.first, key.second, track, true);
  write_file_atomically(dir / "steps.csv", steps);
  write_file_atomically(dir / "tracks.csv", tracks);
  write_file_atomically(dir / "measurements.csv", measurements);
  write_file_atomically(dir / "rounds.csv", rounds);
  write_file_atomically(dir / "refusals.csv", refusals);
  if (imm) write_file_atomically(dir / "modes.csv", modes);

  write_file_atomically(dir / "summary.json", summary_json(summary, run_id) + "\n");
}

std::string RunRecorder::summary_json(const RunSummary& summary, std::uint64_t run_id) const {
  const bool imm = !mode_names_.empty();
  const nlohmann::json json = {{"ended", ended(summary)},
                               {"scenario", plan_.scenario.name},
                               {"seed", plan_.scenario.seed},
                               {"mc_run", plan_.mc_run},
                               {"run_id", run_id},
                               {"stations", summary.stations},
                               {"exchange", summary.exchange},
                               {"fanout", summary.fanout},
                               {"steps", summary.steps},
                               {"steps_planned", summary.steps_planned},
                               {"speed_kmh", summary.speed_kmh},
                               {"rmse_central_m", summary.rmse_central_m},
                               {"rmse_p2p_m", summary.rmse_p2p_m},
                               {"max_abs_diff_central_vs_p2p", summary.max_abs_diff_central_vs_p2p},
                               {"max_abs_diff_between_peers", summary.max_abs_diff_between_peers},
                               {"peer_spread_end", summary.peer_spread_end},
                               {"rounds_closed_incomplete", summary.rounds_closed_incomplete},
                               {"round_deadline_ms", summary.round_deadline_ms},
                               {"rounds_per_s", summary.rounds_per_s},
                               {"round_latency_us_p50", summary.round_latency_us_p50},
                               {"round_latency_us_p99", summary.round_latency_us_p99},
                               {"round_latency_us_max", summary.round_latency_us_max},
                               {"discovery_s", summary.discovery_s}};
  nlohmann::json full = json;
  if (imm) {
    full["filter"] = plan_.scenario.filter.kind;
    full["max_abs_diff_mode_probability_central_vs_p2p"] =
        summary.max_abs_diff_mode_probability_central_vs_p2p;
  }
  full["kernel"] = {{"datagrams_received_per_round", number_or_null(summary.datagrams_per_round)},
                    {"cpu_ms_per_station_round", summary.cpu_ms_per_station_round},
                    {"node_peak_resident_mib", summary.node_peak_resident_mib}};
  if (!summary.end_detail.empty()) full["end_detail"] = summary.end_detail;
  if (!summary.host_verdict.empty()) full["host_verdict"] = summary.host_verdict;
  if (!summary.node_exits.empty()) full["node_exits"] = summary.node_exits;
  if (summary.realtime_deadline_ms > 0.0) {
    nlohmann::json histogram = nlohmann::json::array();
    for (const auto& [up_to, tracks] : summary.track_age_ms_histogram) {
      histogram.push_back(
          {{"up_to_ms", std::isinf(up_to) ? nlohmann::json(nullptr) : nlohmann::json(up_to)},
           {"tracks", tracks}});
    }
    full["realtime"] = {{"deadline_ms", summary.realtime_deadline_ms},
                        {"rounds_all_inputs_in_time", summary.rounds_all_inputs_in_time},
                        {"steps_scheduled", summary.realtime_steps_scheduled},
                        {"steps_reached", summary.realtime_steps_reached},
                        {"behind_s", summary.realtime_behind_s},
                        {"track_age_ms_p50", summary.track_age_ms_p50},
                        {"track_age_ms_p90", summary.track_age_ms_p90},
                        {"track_age_ms_p99", summary.track_age_ms_p99},
                        {"track_age_ms_max", summary.track_age_ms_max},
                        {"track_age_ms_histogram", histogram}};
  }
  // Every kind appears, zeros included, so that a reader can tell "none" from "not counted".
  nlohmann::json by_kind = nlohmann::json::object();
  nlohmann::json by_node = nlohmann::json::object();
  nlohmann::json lost = nlohmann::json::object();
  nlohmann::json resyncs = nlohmann::json::object();
  nlohmann::json late_used = nlohmann::json::object();
  for (std::size_t i = 0; i < kDropKinds; ++i) {
    std::uint64_t total = 0;
    for (const auto& [node, counts] : summary.node_counts) total += counts.dropped[i];
    by_kind[std::string(to_string(static_cast<DropKind>(i)))] = total;
  }
  for (const auto& [node, counts] : summary.node_counts) {
    nlohmann::json kinds = nlohmann::json::object();
    for (std::size_t i = 0; i < kDropKinds; ++i) {
      if (counts.dropped[i] != 0) {
        kinds[std::string(to_string(static_cast<DropKind>(i)))] = counts.dropped[i];
      }
    }
    by_node[node_key(node)] = kinds;
    if (node != kHarnessNodeId) lost[node_key(node)] = counts.lost;
    if (node > 0) resyncs[node_key(node)] = counts.resyncs;
    if (node != kHarnessNodeId) late_used[node_key(node)] = counts.late_used;
  }
  nlohmann::json missing = nlohmann::json::object();
  for (const auto& [id, count] : summary.rounds_missing_by_station) missing[node_key(id)] = count;
  nlohmann::json rejoin = nlohmann::json::object();
  for (const auto& [id, step] : summary.rejoin_step_by_station) rejoin[node_key(id)] = step;
  full["rounds_missing_by_station"] = missing;
  full["rejoin_step_by_station"] = rejoin;
  full["lost_by_node"] = lost;
  full["resyncs_by_station"] = resyncs;
  // Late samples used (kept and re-fused within --refusion-lag; increments at the stations,
  // measurements at the center) and too late for it (stale_step in dropped_by_node).
  full["late_used_by_node"] = late_used;
  full["refusion_lag"] = summary.refusion_lag;
  if (summary.settled) {
    full["settled"] = {{"tracks", summary.settled->tracks},
                       {"rounds", summary.settled->rounds},
                       {"rmse_p2p_m", summary.settled->rmse_p2p_m},
                       {"rmse_central_m", summary.settled->rmse_central_m},
                       {"max_abs_diff_between_peers", summary.settled->max_abs_diff_between_peers},
                       {"peer_spread_end", summary.settled->peer_spread_end}};
  }
  if (summary.loss.probability > 0.0 || summary.best_effort) {
    full["loss"] = {
        {"probability", summary.loss.probability},
        {"first_step", summary.loss.first_step},
        {"end_step", std::min<std::uint64_t>(summary.loss.end_step,
                                             static_cast<std::uint64_t>(plan_.scenario.steps))},
        {"seed", summary.loss.seed},
        {"best_effort", summary.best_effort}};
  }
  // Whom each node had discovered when it finished: every process with multicast discovery, its
  // exchange partners with peer discovery.
  nlohmann::json known = nlohmann::json::object();
  for (const auto& [node, counts] : summary.node_counts) {
    if (node != kHarnessNodeId) known[node_key(node)] = counts.participants_known;
  }
  full["network"] = {{"hosts", summary.hosts},
                     {"discovery", summary.discovery},
                     {"stations_per_process", summary.stations_per_process},
                     {"settle_s", summary.settle_s},
                     {"settled_quiet", summary.settled_quiet},
                     {"participants_known_by_node", known}};
  full["dropped_by_kind"] = by_kind;
  full["dropped_by_node"] = by_node;
  return full.dump(2);
}

void print_run_table(const RunSummary& s, std::FILE* out) {
  fmt::print(out, "\n{} stations + center, {} steps at {:.0f} km/h{}\n", s.stations, s.steps,
             s.speed_kmh,
             s.steps < s.steps_planned
                 ? fmt::format(" (of {}: stopped early, {})", s.steps_planned, ended(s))
                 : "");
  fmt::print(out, "  RMSE central             {:.4f} m\n", s.rmse_central_m);
  fmt::print(out, "  RMSE peer-to-peer        {:.4f} m\n", s.rmse_p2p_m);
  fmt::print(out, "  max |central - p2p|      {:.2e} m\n", s.max_abs_diff_central_vs_p2p);
  if (s.imm) {
    fmt::print(out, "  max |central - p2p| mode probability {:.2e}\n",
               s.max_abs_diff_mode_probability_central_vs_p2p);
  }
  fmt::print(out, "  max |peer - peer|        {:.2e}{}\n", s.max_abs_diff_between_peers,
             s.max_abs_diff_between_peers == 0.0 ? "  (every peer bit-identical)" : "");
  if (s.max_abs_diff_between_peers != 0.0) {
    fmt::print(out, "  |peer - peer| at the end {:.2e}\n", s.peer_spread_end);
  }
  if (s.settled) {
    fmt::print(out,
               "  settled (re-fused) RMSE p2p {:.4f} m, central {:.4f} m, |peer - peer| max "
               "{:.2e}, at the "
               "end {:.2e}\n",
               s.settled->rmse_p2p_m, s.settled->rmse_central_m,
               s.settled->max_abs_diff_between_peers, s.settled->peer_spread_end);
  }
  fmt::print(out, "  exchange                 {}\n",
             s.fanout > 0 ? fmt::format("tree, clusters of {}", s.fanout) : s.exchange);
  fmt::print(out, "  rounds per second        {:.0f}\n", s.rounds_per_s);
  fmt::print(out, "  round latency p50/p99/max {:.0f} / {:.0f} / {:.0f} us\n",
             s.round_latency_us_p50, s.round_latency_us_p99, s.round_latency_us_max);
  fmt::print(out, "  discovery                {:.2f} s", s.discovery_s);
  // Every run waits a window or two (the participants' first announcements); more says that
  // discovery went on past READY.
  if (s.settle_s > 1.0) {
    fmt::print(out, ", then {:.1f} s until the processes were quiet{}", s.settle_s,
               s.settled_quiet ? "" : " (not quiet: started at the limit)");
  }
  fmt::print(out, "\n");
  if (s.datagrams_per_round) {
    fmt::print(out, "  datagrams received/round {:.0f}  (kernel's count, every process)\n",
               *s.datagrams_per_round);
  }
  fmt::print(out, "  CPU per station-round    {:.2f} ms  (stations, center and harness)\n",
             s.cpu_ms_per_station_round);
  std::uint64_t dropped = 0;
  std::uint64_t lost = 0;
  for (const auto& [node, counts] : s.node_counts) {
    for (std::uint64_t c : counts.dropped) dropped += c;
    lost += counts.lost;
  }
  fmt::print(out, "  samples refused          {}{}\n", dropped,
             dropped == 0 ? "" : "  (by kind in summary.json)");
  if (lost != 0) fmt::print(out, "  samples lost (--loss)    {}\n", lost);
  if (s.rounds_closed_incomplete != 0) {
    fmt::print(out, "  rounds closed at the deadline with a track missing: {}\n",
               s.rounds_closed_incomplete);
  }
  for (const auto& [id, rounds] : s.rounds_missing_by_station) {
    if (rounds != 0) fmt::print(out, "  station {} missing from {} rounds\n", id, rounds);
  }
  for (const auto& [id, step] : s.rejoin_step_by_station) {
    fmt::print(out, "  station {} contributed again from step {}\n", id, step);
  }
  if (s.realtime_deadline_ms > 0.0) {
    fmt::print(out, "  real time: deadline {} ms; rounds with every input in time {:.2f} %\n",
               s.realtime_deadline_ms, 100.0 * s.rounds_all_inputs_in_time);
    fmt::print(out, "  track age on arrival p50/p90/p99/max {:.2f} / {:.2f} / {:.2f} / {:.2f} ms\n",
               s.track_age_ms_p50, s.track_age_ms_p90, s.track_age_ms_p99, s.track_age_ms_max);
    if (s.realtime_behind_s > 0.0) {
      fmt::print(out, "  behind the schedule      {:.1f} s when the rounds ended\n",
                 s.realtime_behind_s);
    }
  }
  if (!s.host_verdict.empty()) fmt::print(out, "  {}\n", s.host_verdict);
}

}  // namespace skyfuse::harness
