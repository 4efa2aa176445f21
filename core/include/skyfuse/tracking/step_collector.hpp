#pragma once
/// \file
/// Gathers one sample per participating station for the current step, in ascending station
/// order, from samples that arrive in any order. Samples for the next step are kept (a fast
/// peer may start step k+1 before this process has closed step k); with a lag L, so are late
/// samples for the L steps closed last, for a fixed-lag re-fusion (tracking/fixed_lag_peer.hpp);
/// anything else is refused, and offer() says why: unknown station, stale step (older than the
/// lag), step too far ahead, second copy.
///
/// No allocation after construction: L + 2 fixed rows of slots, reused round robin.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse {

template <typename Payload>
class StepCollector {
 public:
  /// `station_ids` are the participants; they are kept sorted ascending. `lag`: how many closed
  /// steps still take late samples.
  explicit StepCollector(std::span<const int> station_ids, std::size_t lag = 0)
      : ids_(station_ids.begin(), station_ids.end()), rows_(lag + 2) {
    std::sort(ids_.begin(), ids_.end());
    if (std::adjacent_find(ids_.begin(), ids_.end()) != ids_.end()) {
      throw std::invalid_argument("StepCollector: duplicate station id");
    }
    for (Row& row : rows_) {
      row.payloads.resize(ids_.size());
      row.filled.assign(ids_.size(), false);
    }
    // Before any step has closed nobody counts as absent: a new writer may take a station id
    // only after a closed step showed that station silent (see SourceBinding), never at the
    // start, where two writers racing for one id would otherwise take it from each other.
    last_filled_.assign(ids_.size(), true);
    start_at(0);
  }

  /// Makes `step` the current one (a process that joins a run late starts there): nothing
  /// closed is kept.
  void start_at(std::uint64_t step) {
    step_ = step;
    for (Row& row : rows_) row.step.reset();
    open(step);
    open(step + 1);
  }

  /// How many closed steps still take late samples.
  std::size_t lag() const { return rows_.size() - 2; }
  std::uint64_t current_step() const { return step_; }

  /// Why a sample for (step, station_id) would be refused now, or nothing if it would be kept:
  /// unknown station, then stale or future step, then a slot already filled.
  std::optional<DropKind> check(std::uint64_t step, int station_id) const {
    const std::optional<std::size_t> index = index_of(station_id);
    if (!index) return DropKind::kUnknownStation;
    const Row* row = row_for(step);
    if (row == nullptr) return step < step_ ? DropKind::kStaleStep : DropKind::kFutureStep;
    if (row->filled[*index]) return DropKind::kDuplicate;
    return std::nullopt;
  }

  /// Offers a sample; nothing if it was kept, else why it was refused (as check() says).
  std::optional<DropKind> offer(std::uint64_t step, int station_id, const Payload& payload) {
    if (const auto why = check(step, station_id)) return why;
    Row& row = rows_[step % rows_.size()];  // check() found it open
    const std::size_t index = *index_of(station_id);
    row.payloads[index] = payload;
    row.filled[index] = true;
    ++row.count;
    return std::nullopt;
  }

  /// Overwrites the kept sample of (step, station_id), which must be in the window and filled
  /// (check() said kDuplicate): for a receiver that prefers one sender's sample to another's.
  void replace(std::uint64_t step, int station_id, const Payload& payload) {
    Row& row = rows_[step % rows_.size()];
    const std::size_t index = *index_of(station_id);
    if (row.step != step || !row.filled[index]) {
      throw std::logic_error("StepCollector::replace: no kept sample to replace");
    }
    row.payloads[index] = payload;
  }

  bool complete() const { return current().count == ids_.size(); }
  std::size_t count() const { return current().count; }
  /// Whether the i-th station (ascending id) has delivered for the current step.
  bool filled(std::size_t i) const { return current().filled[i]; }
  /// Payloads of the current step in ascending station id (valid once complete()).
  std::span<const Payload> payloads() const { return current().payloads; }
  /// The same for `step`, the current one or one of the `lag()` closed last (which must be
  /// kept: has_step()).
  bool has_step(std::uint64_t step) const { return row_for(step) != nullptr; }
  bool filled_at(std::uint64_t step, std::size_t i) const { return row_for(step)->filled[i]; }
  const Payload& payload_at(std::uint64_t step, std::size_t i) const {
    return row_for(step)->payloads[i];
  }
  std::span<const int> station_ids() const { return ids_; }
  /// Ids of the stations still missing from the current step.
  std::vector<int> missing() const {
    std::vector<int> out;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      if (!current().filled[i]) out.push_back(ids_[i]);
    }
    return out;
  }

  /// Whether the station delivered nothing in the step closed last (false before the first).
  bool absent_last_step(int station_id) const {
    const std::optional<std::size_t> index = index_of(station_id);
    return index && !last_filled_[*index];
  }

  /// Closes the current step and opens the next one; the oldest closed step leaves the lag.
  void advance() {
    last_filled_ = current().filled;  // same size: no allocation
    ++step_;
    open(step_ + 1);  // the row of step_ - 1 - lag, round robin
  }

 private:
  struct Row {
    std::optional<std::uint64_t> step;  // none: holds no step
    std::vector<Payload> payloads;
    std::vector<bool> filled;
    std::size_t count = 0;
  };

  void open(std::uint64_t step) {
    Row& row = rows_[step % rows_.size()];
    row.step = step;
    row.filled.assign(ids_.size(), false);
    row.count = 0;
  }
  const Row& current() const { return rows_[step_ % rows_.size()]; }
  std::optional<std::size_t> index_of(int station_id) const {
    return position_of(ids_, station_id);
  }
  const Row* row_for(std::uint64_t step) const {
    const Row& row = rows_[step % rows_.size()];
    return row.step == step ? &row : nullptr;
  }
  std::vector<int> ids_;
  std::vector<Row> rows_;  // step s in rows_[s % size]: steps step_ - lag .. step_ + 1
  std::vector<bool> last_filled_;
  std::uint64_t step_ = 0;
};

}  // namespace skyfuse
