#pragma once
/// \file
/// One station's plots or reports gathered from an ASTERIX feed, datagram by datagram, round by
/// round: what a file replayed (`--asterix-replay`, asterix_replay.hpp) and a live UDP feed
/// (`--asterix-in`, asterix_live.hpp) both hand a station. The station's records are those of
/// its own data source (SAC 0, SIC its id); each record's time of day (I048/140, I021/071)
/// names its round, k = round(t / dt). Every record of the network's own area (its SAC), of
/// any station or category, tells how far the feed has come (latest_round): a live station
/// takes its round once the feed has passed it. The station's data source is the scenario's SAC and
/// its id as SIC.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/refusal.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::transport {

class ScanFeed {
 public:
  /// `station`'s records, in `scenario`'s frame and rounds. Throws std::invalid_argument,
  /// naming `option`, for a sensor ASTERIX does not carry (carried_by_asterix) or a station id
  /// past SIC's 255.
  ScanFeed(std::string_view option, const Scenario& scenario, const StationConfig& station);

  /// Decodes one datagram: what the decoder refused is counted by kind, this station's records
  /// are kept by round, except those of a round before `first_open` (already taken: late,
  /// counted).
  void take(std::span<const std::uint8_t> datagram, std::uint64_t first_open = 0);

  /// The latest round a record of the network's SAC named, of whatever SIC; nullopt before any.
  std::optional<std::uint64_t> latest_round() const { return latest_round_; }

  /// Round k's records as a scan, with `noise` as its R (empty where none came), and forgets
  /// them, and those of rounds before k (late). A plot or report that cannot be a detection
  /// (scan_of_plots) is skipped and counted.
  Scan take_scan(std::uint64_t k, const DetectionNoise& noise);

  /// The rounds of which records are kept, ascending.
  std::vector<std::uint64_t> rounds() const;

  int station_id() const { return station_id_; }
  std::size_t datagrams() const { return datagrams_; }
  std::size_t records() const { return records_; }        ///< this station's, kept now
  std::size_t late() const { return late_; }              ///< this station's, of a taken round
  std::size_t detections() const { return detections_; }  ///< handed out by take_scan
  std::size_t skipped() const { return skipped_; }
  const asterix::RefusalCounts& refusals() const { return refusals_; }

 private:
  std::uint64_t round_of(double time_of_day_s) const;
  void passed(double time_of_day_s);

  int station_id_;
  asterix::DataSource source_;
  std::string sensor_kind_;
  bool reports_;  // CAT021 (an ADS-B / Remote ID receiver); CAT048 otherwise
  GeoAnchor anchor_;
  double time_step_s_;
  std::map<std::uint64_t, std::vector<asterix::RadarPlot>> plots_;
  std::map<std::uint64_t, std::vector<asterix::AdsbReport>> reports_by_round_;
  std::optional<std::uint64_t> latest_round_;
  std::size_t datagrams_ = 0;
  std::size_t records_ = 0;
  std::size_t late_ = 0;
  std::size_t detections_ = 0;
  std::size_t skipped_ = 0;
  asterix::RefusalCounts refusals_;
};

}  // namespace skyfuse::transport
