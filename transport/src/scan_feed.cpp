#include "skyfuse/transport/scan_feed.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

namespace skyfuse::transport {

ScanFeed::ScanFeed(std::string_view option, const Scenario& scenario, const StationConfig& station)
    : station_id_(station.id),
      sensor_kind_(station.sensor.kind),
      reports_(station.sensor.kind == "position_velocity"),
      anchor_(scenario.anchor),
      time_step_s_(scenario.time_step_s) {
  const std::string who = std::string(option) + ": station " + std::to_string(station.id);
  if (!carried_by_asterix(station.sensor.kind)) {
    throw std::invalid_argument(who + "'s sensor (" + station.sensor.kind +
                                ") has no ASTERIX item that carries its detections");
  }
  const auto source = station_source(scenario, station.id);
  if (!source) throw std::invalid_argument(who + " is past SIC's 255");
  source_ = *source;
}

std::uint64_t ScanFeed::round_of(double time_of_day_s) const {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, time_of_day_s) / time_step_s_));
}

void ScanFeed::passed(double time_of_day_s) {
  const std::uint64_t k = round_of(time_of_day_s);
  if (!latest_round_ || k > *latest_round_) latest_round_ = k;
}

void ScanFeed::take(std::span<const std::uint8_t> datagram, std::uint64_t first_open) {
  ++datagrams_;
  const asterix::Decoded decoded = asterix::decode_datagram(datagram);
  refusals_ += decoded.refusals;
  const auto keep = [&](auto& by_round, double time_of_day_s, const auto& record) {
    const std::uint64_t k = round_of(time_of_day_s);
    if (k < first_open) {
      ++late_;
      return;
    }
    by_round[k].push_back(record);
    ++records_;
  };
  // Only this network's records (its SAC) tell the time: another system on the same group may
  // keep another clock.
  const auto ours = [&](const asterix::DataSource& source) { return source.sac == source_.sac; };
  for (const asterix::RadarPlot& p : decoded.plots) {
    if (ours(p.source)) passed(p.time_of_day_s);
    if (!reports_ && p.source == source_) keep(plots_, p.time_of_day_s, p);
  }
  for (const asterix::AdsbReport& r : decoded.reports) {
    if (ours(r.source)) passed(r.time_of_applicability_s);
    if (reports_ && r.source == source_) keep(reports_by_round_, r.time_of_applicability_s, r);
  }
  for (const asterix::SystemTrack& t : decoded.tracks) {
    if (ours(t.source)) passed(t.time_of_track_s);
  }
}

Scan ScanFeed::take_scan(std::uint64_t k, const DetectionNoise& noise) {
  // Rounds before k that were never asked for (a station that joins late) are late too.
  const auto forget_before = [&](auto& by_round) {
    for (auto at = by_round.begin(); at != by_round.end() && at->first < k;) {
      late_ += at->second.size();
      records_ -= at->second.size();
      at = by_round.erase(at);
    }
  };
  forget_before(plots_);
  forget_before(reports_by_round_);
  std::optional<Scan> scan;
  if (reports_) {
    const auto at = reports_by_round_.find(k);
    if (at != reports_by_round_.end()) {
      scan = scan_of_reports(station_id_, at->second, anchor_, skipped_);
      reports_by_round_.erase(at);
    }
  } else {
    const auto at = plots_.find(k);
    if (at != plots_.end()) {
      scan = scan_of_plots(station_id_, sensor_kind_, at->second, skipped_);
      plots_.erase(at);
    }
  }
  if (!scan) scan = Scan{station_id_, {}, {}, {}};
  detections_ += scan->detections.size();
  scan->noise = noise;
  return std::move(*scan);
}

std::vector<std::uint64_t> ScanFeed::rounds() const {
  std::vector<std::uint64_t> out;
  for (const auto& [k, records] : plots_) out.push_back(k);
  for (const auto& [k, records] : reports_by_round_) out.push_back(k);
  return out;  // one of the two maps is empty: ascending
}

}  // namespace skyfuse::transport
