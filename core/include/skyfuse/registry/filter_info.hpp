#pragma once
/// \file
/// What the scenario loader, the command line and the harness need to know of each registered
/// filter, without its types: its name, the parts it runs on, the options it refuses, what its
/// tracks carry. Each filter part states these once (filters/parts/); the registry describes
/// them here. Like part_info.hpp, cheap to include.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skyfuse {

struct FilterInfo {
  std::string_view kind;
  std::string_view summary;
  /// The only motion model it runs on; empty: any registered model.
  std::string_view motion_model;
  /// The only sensor kind its stations may have; empty: any registered sensor.
  std::string_view sensor;
  /// Whether every station of a run must have the same sensor kind.
  bool one_sensor_kind = false;
  /// Whether it takes a fixed-lag re-fusion (`--refusion-lag`).
  bool takes_refusion_lag = true;
  /// Whether it takes a chi^2 gate on measurements (`--nis-gate`): only a filter with an
  /// innovation to gate does.
  bool takes_nis_gate = true;
  /// Its modes, in the order of every probability vector it reports; empty: one model. A
  /// scenario configures the modes under `filter.imm` only for a filter that has them.
  std::vector<std::string_view> mode_names;
  /// Whether its station processes run the tree exchange (`network: {exchange: tree}`): those of
  /// every registered filter do; a new filter's only once its fusion sums partial sums
  /// (stations/tree_exchange.hpp). The in-process sweep runs the tree for every filter.
  bool nodes_take_tree = false;
  /// Degrees of freedom of its NEES: the leading state entries every estimate of it shares
  /// (0: the motion model's whole state).
  int nees_dof = 0;
  /// Whether it keeps a picture of many aircraft (picture/track_filters.hpp): a part whose
  /// station turns one detection into one increment per track by its increment rule does (the
  /// EKF, the unscented filter), and the IMM; the NCRKF's TDOA receivers fix no position.
  bool tracks_many = false;
  /// Whether its picture takes an associator that weighs pairs (JPDA): a station's
  /// contributions of several detections must add up, as an increment rule's do; the IMM's
  /// mode likelihoods do not.
  bool sums_weighed_pairs = false;
};

struct FilterConfig;

/// Every registered filter part; a filter with modes has one part per set of modes.
std::vector<FilterInfo> filter_infos();
/// The first part of kind `kind`: what every part of a kind shares (all but the mode names).
std::optional<FilterInfo> find_filter(std::string_view kind);
/// The part that runs `filter`: its kind and, for a filter with modes, its modes in order.
std::optional<FilterInfo> find_filter(const FilterConfig& filter);
/// "a, b, c": the registered names, for error messages.
std::string filter_kinds();
/// "[a, b], [a, c]": the sets of modes registered for filter `kind`, for error messages.
std::string filter_mode_sets(std::string_view kind);

/// Why `filter` cannot run with these node options (a re-fusion lag, a NIS gate), in words that
/// name the option; nothing if it can.
std::optional<std::string> filter_option_refusal(const FilterInfo& filter, std::size_t refusion_lag,
                                                 bool nis_gate);

}  // namespace skyfuse
