#pragma once
/// \file
/// A station's scans read back from a file of ASTERIX (`--asterix-replay FILE`: a pcap of UDP
/// datagrams, or raw data blocks one after another): the CAT048 plots or CAT021 reports of its
/// own data source, round by round, as a station fed that feed holds them (scan_feed.hpp).
/// A raw file is read as one datagram: a block whose length cannot be trusted costs the rest
/// of it (asterix/refusal.hpp). A file `skyfuse run --asterix-record` wrote of the
/// same scenario gives each station the scans it simulated, quantised as the items hold them.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string_view>

#include "skyfuse/asterix/refusal.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/transport/fed_scans.hpp"

namespace skyfuse::transport {

/// What a feed file holds, as a run reports it in summary.json: its UDP datagrams, the records
/// read by category, the records and blocks refused by kind, and the frames the pcap reader
/// skipped (not IPv4 UDP, fragments, truncated).
struct AsterixFeedCounts {
  std::uint64_t datagrams = 0;
  std::uint64_t plots = 0;          ///< CAT048
  std::uint64_t reports = 0;        ///< CAT021
  std::uint64_t system_tracks = 0;  ///< CAT062
  asterix::RefusalCounts refused;
  std::uint64_t frames_skipped = 0;
};

/// Counts `file` (AsterixFeedCounts); throws std::runtime_error naming it where it cannot be read.
AsterixFeedCounts count_asterix_feed(const std::filesystem::path& file);

class ReplayedScans final : public FedScans {
 public:
  /// `station`'s scans (the scenario's SAC, its id as SIC) in `file`: each record's time of day
  /// (I048/140, I021/071) names its round, k = round(t / dt). Throws std::runtime_error naming
  /// the file where it cannot be read, std::invalid_argument for a sensor ASTERIX does not
  /// carry (carried_by_asterix) or a station id past SIC's 255.
  ReplayedScans(const std::filesystem::path& file, const Scenario& scenario,
                const StationConfig& station);

  /// Round k's scan, with `noise` as its R: empty where the file holds nothing of the round.
  Scan scan_at(std::uint64_t k, const DetectionNoise& noise) override;
  std::string started() const override { return summary(); }  // the file is read: its counts
  std::string summary() const override;

  std::size_t rounds() const { return scans_.size(); }
  std::size_t detections() const { return detections_; }
  /// What the decoder refused in the file, by kind (asterix/refusal.hpp), and the plots or
  /// reports of this station that could not be a detection (scan_of_plots).
  const asterix::RefusalCounts& refusals() const { return refusals_; }
  std::size_t skipped() const { return skipped_; }

 private:
  std::filesystem::path file_;
  int station_id_;
  std::map<std::uint64_t, Scan> scans_;
  std::size_t detections_ = 0;
  asterix::RefusalCounts refusals_;
  std::size_t skipped_ = 0;
};

}  // namespace skyfuse::transport
