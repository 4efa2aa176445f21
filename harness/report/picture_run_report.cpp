#include "report/picture_run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string_view>

#include "report/json_values.hpp"
#include "run/picture_round_check.hpp"

namespace skyfuse::harness {
namespace {

DropCounts refused_by_kind(const PictureRunSummary& s) {
  DropCounts sum{};
  for (const auto& [node, counts] : s.dropped_by_node) {
    for (std::size_t i = 0; i < kDropKinds; ++i) sum[i] += counts[i];
  }
  return sum;
}

}  // namespace

void print_picture_run_table(const PictureRunSummary& s, std::FILE* out) {
  fmt::print(out,
             "many aircraft over DDS: scenario '{}', {} station processes and the center, {} "
             "rounds{}, {}\n",
             s.scenario, s.stations, s.steps,
             s.stop_cause ? fmt::format(" (of {}: stopped early, {})", s.steps_planned,
                                        to_string(*s.stop_cause))
                          : std::string(),
             s.fanout > 0 ? fmt::format("tree exchange (clusters of {})", s.fanout)
                          : std::string("flat exchange"));
  const auto row = [&](std::string_view what, const std::string& value) {
    fmt::print(out, "  {:<36} {}\n", what, value);
  };
  row("peers' pictures",
      s.peers_identical
          ? "bit-identical in every round"
          : fmt::format("apart in {} rounds ({}-{}), bit-identical in the others",
                        s.rounds_peers_apart, s.first_divergent_step, s.last_round_peers_apart));
  if (s.loss) {
    row("samples lost (--loss)",
        fmt::format("{}; {} rounds a station took the lowest station's picture", s.lost,
                    s.resyncs));
  }
  row("peers equal to the in-process run",
      s.equals_in_process ? "yes, every round"
                          : fmt::format("no, from round {}", s.first_step_apart_from_in_process));
  row("center equal to its in-process run",
      s.center_equals_in_process
          ? "yes, every round"
          : fmt::format("no, from round {}", s.first_step_center_apart_from_in_process));
  if (const auto& feed = s.asterix_feed) {
    row("ASTERIX feed (--asterix-replay)",
        fmt::format("{} datagrams: {} plots, {} reports, {} system tracks; {} refused{}",
                    feed->datagrams, feed->plots, feed->reports, feed->system_tracks,
                    feed->refused.total(),
                    feed->refused.total() == 0 ? "" : " (by kind in summary.json)"));
  }
  row("center vs peer-to-peer",
      fmt::format("max |dx| / (1 + |x|) {:.2e}; {} rounds with other "
                  "tracks",
                  s.max_state_gap_center_vs_p2p, s.rounds_center_tracks_differ));
  row(s.realtime ? "rounds in time" : "rounds with every scan fused",
      fmt::format(
          "{} of {} ({:.1f} %){}", s.rounds_in_time, s.steps,
          100.0 * s.rounds_in_time / std::max(s.steps, 1),
          s.rounds_without_a_picture > 0
              ? fmt::format("; {} rounds without any station's picture", s.rounds_without_a_picture)
              : std::string()));
  if (const DropCounts refused = refused_by_kind(s); refused != DropCounts{}) {
    std::string kinds;
    for (std::size_t i = 0; i < kDropKinds; ++i) {
      if (refused[i] == 0) continue;
      kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ",
                           to_string(static_cast<DropKind>(i)), refused[i]);
    }
    row("samples refused (every node)", kinds);
  }
  row("tracks at the end", fmt::format("{} ({} confirmed)", s.tracks_at_end, s.confirmed_at_end));
  row("GOSPA, mean over rounds",
      fmt::format("{:.2f} over the aircraft in view, {:.2f} over every one (the in-process run, "
                  "without faults: {:.2f}, {:.2f})",
                  s.gospa_in_view_mean, s.gospa_mean, s.in_process_gospa_in_view_mean,
                  s.in_process_gospa_mean));
  row("discovery", fmt::format("{}: {:.2f} s, then {:.2f} s until quiet{}", s.discovery,
                               s.discovery_s, s.settle_s, s.settled_quiet ? "" : " (not quiet)"));
  row("rounds per second", fmt::format("{:.0f}", s.rounds_per_s));
  row("datagrams received per round",
      s.datagrams_per_round
          ? fmt::format("{:.0f}  (kernel's count, every process)", *s.datagrams_per_round)
          : std::string("unknown"));
  row("CPU per station-round",
      fmt::format("{:.2f} ms  (stations, center and harness)", s.cpu_ms_per_station_round));
  if (!s.host_verdict.empty()) fmt::print(out, "  {}\n", s.host_verdict);
}

std::string picture_run_json(const PictureRunSummary& summary, std::uint64_t run_id,
                             const PictureRunResult& twin) {
  // What each node refused, by kind (the center is "center"), and the kinds summed.
  const auto by_kind = [](const DropCounts& counts) {
    nlohmann::json kinds = nlohmann::json::object();
    for (std::size_t i = 0; i < kDropKinds; ++i) {
      kinds[std::string(to_string(static_cast<DropKind>(i)))] = counts[i];
    }
    return kinds;
  };
  nlohmann::json by_node = nlohmann::json::object();
  for (const auto& [node, counts] : summary.dropped_by_node) {
    by_node[node == 0 ? std::string("center") : std::to_string(node)] = by_kind(counts);
  }
  const nlohmann::json json = {
      {"scenario", summary.scenario},
      {"stations", summary.stations},
      {"exchange", summary.exchange},
      {"fanout", summary.fanout},
      {"stations_per_process", summary.stations_per_process},
      {"steps", summary.steps},
      {"steps_planned", summary.steps_planned},
      {"ended", summary.stop_cause ? to_string(*summary.stop_cause) : "complete"},
      {"run_id", run_id},
      {"peers_identical", summary.peers_identical},
      {"first_divergent_step", summary.first_divergent_step},
      {"rounds_peers_apart", summary.rounds_peers_apart},
      {"realtime", summary.realtime},
      {"rounds_in_time", summary.rounds_in_time},
      {"share_of_rounds_in_time",
       static_cast<double>(summary.rounds_in_time) / std::max(summary.steps, 1)},
      {"rounds_without_a_picture", summary.rounds_without_a_picture},
      {"last_round_peers_apart", summary.last_round_peers_apart},
      {"loss", summary.loss},
      {"faults", summary.faults},
      {"samples_lost", summary.lost},
      {"resyncs", summary.resyncs},
      {"dropped_by_kind", by_kind(refused_by_kind(summary))},
      {"dropped_by_node", std::move(by_node)},
      {"gospa_mean", summary.gospa_mean},
      {"gospa_in_view_mean", summary.gospa_in_view_mean},
      {"equals_in_process", summary.equals_in_process},
      {"first_step_apart_from_in_process", summary.first_step_apart_from_in_process},
      {"center_equals_in_process", summary.center_equals_in_process},
      {"first_step_center_apart_from_in_process", summary.first_step_center_apart_from_in_process},
      {"max_state_gap_center_vs_p2p", summary.max_state_gap_center_vs_p2p},
      {"rounds_center_tracks_differ", summary.rounds_center_tracks_differ},
      {"discovery", summary.discovery},
      {"discovery_s", summary.discovery_s},
      {"settle_s", summary.settle_s},
      {"settled_quiet", summary.settled_quiet},
      {"node_peak_resident_mib", summary.node_peak_resident_mib},
      {"rounds_per_s", summary.rounds_per_s},
      {"datagrams_received_per_round", number_or_null(summary.datagrams_per_round)},
      {"cpu_ms_per_station_round", summary.cpu_ms_per_station_round},
      {"tracks_at_end", summary.tracks_at_end},
      {"confirmed_at_end", summary.confirmed_at_end},
      {"picture_digest_at_end", hex_digest(summary.digest_at_end)},
      {"in_process",
       {{"peers_identical", twin.peers_identical},
        {"confirmed_at_end", twin.confirmed_at_end},
        {"max_state_gap_center_vs_p2p", twin.max_state_gap},
        {"association_flips", twin.association_flips},
        {"gospa_mean", twin.score.gospa_mean},
        {"gospa_in_view_mean", twin.score.in_view.distance}}}};
  nlohmann::json full = json;
  if (const auto& feed = summary.asterix_feed) {
    nlohmann::json refused = nlohmann::json::object();
    for (std::size_t i = 0; i < asterix::kRefusalKinds; ++i) {
      const auto kind = static_cast<asterix::Refusal>(i);
      refused[std::string(asterix::refusal_name(kind))] = feed->refused[kind];
    }
    full["asterix_replay"] = {{"datagrams", feed->datagrams},
                              {"cat048_plots", feed->plots},
                              {"cat021_reports", feed->reports},
                              {"cat062_tracks", feed->system_tracks},
                              {"refused", std::move(refused)},
                              {"refused_total", feed->refused.total()},
                              {"pcap_frames_skipped", feed->frames_skipped}};
  }
  if (!summary.end_detail.empty()) full["end_detail"] = summary.end_detail;
  if (!summary.node_exits.empty()) full["node_exits"] = summary.node_exits;
  if (!summary.host_verdict.empty()) full["host_verdict"] = summary.host_verdict;
  return full.dump(2);
}

}  // namespace skyfuse::harness
