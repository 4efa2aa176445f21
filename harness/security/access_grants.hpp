#pragma once
// Who may publish and subscribe to which topic under `skyfuse run --secure`: the least each
// role needs for the endpoints it creates, so that a stolen or misused identity can do no more
// than its role.
//
//   role       publishes                              subscribes
//   station    increment, measurement, track, status  tick, increment, status
//   center     track, status                          tick, measurement, status
//   harness    tick                                   track, measurement, status
//   observer   -                                      tick, track, status
//
// and in a run of many aircraft a station publishes its picture scan, picture and whole picture
// and subscribes to the others' scans and whole pictures; the center subscribes to the scans
// and publishes its picture; the harness and an observer subscribe to the pictures.
//
// and in partition skyfuse-refusal-reports (transport/refusal_reports.hpp) a station and the
// center publish status, the harness subscribes to it; in the partitions of a picture's tree
// exchange (transport/picture_bundles.hpp) a station publishes and subscribes to bundles, the
// center subscribes to them.
//
// The harness subscribes to measurements because it records them (measurements.csv, and the
// replay that rests on it); it still may not publish them, nor read any increment.

#include <string>
#include <vector>

namespace skyfuse::harness {

struct AccessGrant {
  std::string identity;
  std::vector<std::string> publish;    ///< topic names, in the default partition
  std::vector<std::string> subscribe;  ///< topic names, in the default partition
  /// Topic names in kRefusalReportsPartition.
  std::vector<std::string> publish_refusal_reports;
  std::vector<std::string> subscribe_refusal_reports;
  /// Topic names in the partitions of a picture's tree exchange.
  std::vector<std::string> publish_in_picture_tree;
  std::vector<std::string> subscribe_in_picture_tree;
};

/// The grant for a harness, center, station-N or observer identity.
AccessGrant access_grant(const std::string& identity);

}  // namespace skyfuse::harness
