#pragma once
/// \file
/// The round loop every node runs: a station on its peers' increments, the fusion center on the
/// stations' measurements. It joins the run; starts each round on its tick (lock-step) or on the
/// wall clock (real time); takes the input samples through the simulated link (`--loss`,
/// `--link-delay-ms`); closes the round when every input is in or at its deadline; fails a node
/// that hears nothing for too long; after the last round waits for the late samples a
/// re-fusion lag may still take; and ends the run. What a round fuses is the process's: a
/// NodeProcess.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <concepts>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/delayed_inbox.hpp"
#include "skyfuse/transport/drop_log.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/realtime_schedule.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::transport {

/// An exit code when the run must end now; nothing to go on.
using RunEnd = std::optional<int>;

/// What a process reports of its rounds in its last status.
struct ProcessCounts {
  std::uint32_t resyncs = 0;    ///< rounds fused onto another node's prior
  std::uint64_t late_used = 0;  ///< samples kept although their round had closed (re-fused)
};

/// What a node process gives the loop, for its input `Sample`:
/// - `open_round(k)`: its own part as round k starts (a station's measurement and increment);
/// - `receive(sample, writer)`: checks a sample of this run that the link delivered and keeps
///   it, or says why not (the loop counts it);
/// - `round_complete()`: every input the current round waits for is in;
/// - `close_round(k)`: fuses what arrived and publishes the track;
/// - `settle(steps)`: with a re-fusion lag, after the last round: the rounds still in the lag,
///   fused again and published as final;
/// - `counts()`: its share of the last status.
///
/// A process whose round has stages of its own (a tree exchange's aggregator closes its
/// cluster's sum before the round's deadline) may also have `wake_at()`: the system-clock time
/// by which the loop must next ask `round_complete()`, if any.
template <typename P, typename Sample>
concept NodeProcess = requires(P& p, const Sample& sample, const WriterId& writer,
                               std::uint64_t k) {
  { p.open_round(k) } -> std::same_as<RunEnd>;
  { p.receive(sample, writer) } -> std::same_as<std::optional<DropKind>>;
  { p.round_complete() } -> std::convertible_to<bool>;
  { p.close_round(k) } -> std::same_as<RunEnd>;
  { p.settle(k) } -> std::same_as<RunEnd>;
  { p.counts() } -> std::same_as<ProcessCounts>;
};

template <typename Sample>
class NodeLoop {
 public:
  using SystemTime = std::chrono::system_clock::time_point;

  /// `self_id`: this node's id on the simulated links (a station's id, or kCenterSourceId);
  /// `who`: its name in messages ("station 3"); `input`: its input's name in drop counts
  /// ("increment"); `input_partitions`: the DDS partitions its input reader is in (none: the
  /// default one). The tick and input readers are made here, first of the node's endpoints.
  NodeLoop(DdsNode& node, const options::NodeOptions& options, int self_id, std::string who,
           std::string input, double time_step_s,
           const std::vector<std::string>& input_partitions = {})
      : options_(options),
        self_id_(self_id),
        who_(std::move(who)),
        input_(std::move(input)),
        time_step_s_(time_step_s),
        presence_(node, options.run_id, self_id),
        ticks_(node.make_reader<wire::Tick>()),
        inputs_(node.make_reader<Sample>(input_partitions)) {
    wait_set_.attach(ticks_);
    wait_set_.attach(inputs_);
  }

  Reader<wire::Tick>& ticks() { return ticks_; }
  Reader<Sample>& inputs() { return inputs_; }

  /// Samples of `station_id` from `writer` are this node's own, which its reader hears too:
  /// skipped before the link sees them.
  void skip_own(int station_id, const WriterId& writer) { own_ = Own{station_id, writer}; }

  /// Joins the run (join_run): until `all_matched()`, `describe_missing()` saying what is not.
  RunEnd join(const std::function<bool()>& all_matched,
              const std::function<std::string()>& describe_missing) {
    const JoinResult joined =
        join_run(presence_, all_matched, describe_missing, options_.discovery_timeout());
    return exit_code_unless_joined(joined, presence_, who_, options_.run_id,
                                   options_.discovery_timeout_s);
  }

  /// Counts a refused input sample (or, with `what`, another one) and logs it, rate-limited.
  void count_drop(DropKind why, int station_id, std::uint64_t step) {
    count_drop(why, input_, station_id, step);
  }
  void count_drop(DropKind why, std::string_view what, int station_id, std::uint64_t step) {
    transport::count_drop(drops_, why, what, station_id, step);
  }

  /// Logs why the run fails here, tells the run (with what was refused) and returns `code`.
  int fail(std::uint64_t step, const std::string& detail, int code) {
    spdlog::error("{}", detail);
    presence_.set_drops(drops_.counts());
    presence_.announce(wire::FAILED, static_cast<std::uint32_t>(step), detail);
    return code;
  }

  /// Runs rounds [first, steps), settles the lag, announces FINISHED and waits for the
  /// harness's release; `tracks` is the writer the process publishes its results on (tracks,
  /// or a picture). A released node exits here (leave_without_goodbye); otherwise returns the
  /// exit code.
  template <NodeProcess<Sample> Process, typename Result>
  int run(Process& process, std::uint64_t first, std::uint64_t steps, Writer<Result>& tracks) {
    if (realtime()) {  // every node counts the steps from the epoch the start tick carries
      if (const RunEnd end = wait_for(
              process, first, options_.first_tick_timeout(), [&] { return epoch_ns_ != 0; },
              "the start tick")) {
        return *end;
      }
    }
    for (std::uint64_t k = first; k < steps; ++k) {
      if (const RunEnd end = run_round(process, k, first)) return *end;
    }
    if (options_.refusion_lag != 0) {
      if (const RunEnd end = settle(process, steps, tracks)) return *end;
    }
    const ProcessCounts counts = process.counts();
    presence_.set_drops(drops_.counts());
    presence_.set_link_counts(lost_, counts.resyncs, counts.late_used);
    presence_.announce(wire::FINISHED, static_cast<std::uint32_t>(steps));
    const bool released =
        finish_when_released(ticks_, options_.run_id, presence_, tracks, std::chrono::seconds(5));
    spdlog::info(
        "finished {} steps ({} rounds resynchronised, {} samples lost to --loss, {} late ones "
        "re-fused)",
        steps - first, counts.resyncs, lost_, counts.late_used);
    if (released) leave_without_goodbye(options::kExitOk);
    return options::kExitOk;
  }

 private:
  static constexpr std::chrono::microseconds kPollSlice{50'000};

  struct Own {
    int station_id;
    WriterId writer;
  };

  bool realtime() const { return options_.realtime_deadline_ms > 0.0; }

  // Round k: starts on tick k (lock-step) or at the step's time (real time); the process's own
  // part; then inputs until every one is in or the round's deadline passes; then its fusion.
  template <typename Process>
  RunEnd run_round(Process& process, std::uint64_t k, std::uint64_t first) {
    SystemTime close;
    if (realtime()) {
      const SystemTime start = step_start(epoch_ns_, k, time_step_s_);
      if (const RunEnd end = wait_until(process, k, start, [] { return false; })) return end;
      close = start + options_.realtime_deadline();
    } else {
      const auto limit = k == first ? options_.first_tick_timeout() : options_.idle_timeout();
      if (const RunEnd end = wait_for(
              process, k, limit, [&] { return last_tick_ == k; }, "the tick")) {
        return end;
      }
      close = std::chrono::system_clock::now() + options_.round_deadline();
    }
    if (const RunEnd end = process.open_round(k)) return end;
    if (const RunEnd end = wait_until(process, k, close, [&] { return process.round_complete(); }))
      return end;
    const RunEnd end = process.close_round(k);
    if (!end) report_new_refusals(k);
    return end;
  }

  // After a round in which this node refused something: a status with the counts so far, so
  // that whoever watches the run (the harness, a recording) learns what was refused and why
  // while it goes on. Rounds with nothing refused send nothing; the last status carries every
  // count. The reports go to the harness alone (kRefusalReportsPartition).
  void report_new_refusals(std::uint64_t k) {
    const DropCounts counts = drops_.counts();
    if (counts == reported_drops_) return;
    reported_drops_ = counts;
    presence_.set_drops(counts);
    presence_.report_refusals(static_cast<std::uint32_t>(k));
  }

  // After the last round: in real time, a lag's worth of steps for late samples; then the
  // process's final tracks, acknowledged before FINISHED (the harness stops reading then).
  template <typename Process, typename Result>
  RunEnd settle(Process& process, std::uint64_t steps, Writer<Result>& tracks) {
    if (realtime()) {
      const SystemTime until =
          std::chrono::system_clock::now() + steps_duration(options_.refusion_lag, time_step_s_);
      if (const RunEnd end = wait_until(process, steps, until, [] { return false; })) return end;
    }
    if (const RunEnd end = process.settle(steps)) return end;
    tracks.wait_acknowledged(std::chrono::seconds(2));
    return std::nullopt;
  }

  // Takes samples until `done()` or `close` passes (either is fine); wakes by the process's
  // wake_at() too, if it has one.
  template <typename Process, typename Done>
  RunEnd wait_until(Process& process, std::uint64_t k, SystemTime close, Done done) {
    while (true) {
      if (const RunEnd end = drain(process, k)) return end;
      if (done()) return std::nullopt;
      if (shutdown_requested()) return 128 + shutdown_signal();
      const SystemTime now = std::chrono::system_clock::now();
      if (close <= now) return std::nullopt;
      SystemTime wake = close;
      if constexpr (requires { process.wake_at(); }) {
        if (const std::optional<SystemTime> stage = process.wake_at()) {
          wake = std::clamp(*stage, now, close);
        }
      }
      const auto left = std::chrono::ceil<std::chrono::microseconds>(wake - now);
      wait_set_.wait(wait_slice(std::min(left, kPollSlice)));
    }
  }

  // Takes samples until `done()`; a node that waits longer than `limit` fails the run.
  template <typename Process, typename Done>
  RunEnd wait_for(Process& process, std::uint64_t k, std::chrono::milliseconds limit, Done done,
                  std::string_view what) {
    const auto give_up = std::chrono::steady_clock::now() + limit;
    while (true) {
      if (const RunEnd end = drain(process, k)) return end;
      if (done()) return std::nullopt;
      if (shutdown_requested()) return 128 + shutdown_signal();
      if (std::chrono::steady_clock::now() >= give_up) {
        return fail(k,
                    fmt::format("no progress for {} s at step {} waiting for {}",
                                std::chrono::duration<double>(limit).count(), k, what),
                    options::kExitIdleTimeout);
      }
      wait_set_.wait(wait_slice(kPollSlice));
    }
  }

  // A poll slice at most, and not past the next delayed sample.
  std::chrono::microseconds wait_slice(std::chrono::microseconds longest) const {
    return delayed_.wait_limit(std::chrono::steady_clock::now(), longest);
  }

  // Takes what both readers hold: ticks (a stop ends the run), and inputs through the
  // simulated link, handing the process what is due.
  template <typename Process>
  RunEnd drain(Process& process, std::uint64_t k) {
    if (const auto code = exit_code_if_duplicate(presence_, who_, options_.run_id)) return code;
    wire::Tick tick;
    while (ticks_.take(tick)) {
      if (tick.run_id() != options_.run_id) {
        count_drop(DropKind::kWrongRun, "tick", 0, tick.step());
        continue;
      }
      if (tick.stop()) {
        spdlog::info("stopped by the harness at step {}", k);
        return options::kExitOk;
      }
      if (tick.epoch_ns() != 0) epoch_ns_ = tick.epoch_ns();
      last_tick_ = tick.step();
    }
    Sample sample;
    WriterId writer;
    const auto now = std::chrono::steady_clock::now();
    while (inputs_.take(sample, &writer)) {
      const auto sender = static_cast<int>(sample.station_id());
      if (own_ && sender == own_->station_id && writer == own_->writer) continue;
      if (options_.loss.lost(self_id_, sender, sample.step())) {
        ++lost_;  // the simulated link lost it: as if it never arrived
        continue;
      }
      if (options_.delay.enabled()) {  // the simulated link holds it back
        delayed_.hold(sample, writer,
                      now + options_.delay.of(options_.loss.seed, self_id_, sender, sample.step()));
        continue;
      }
      deliver(process, sample, writer);
    }
    delayed_.release_due(now, [&](const Sample& s, const WriterId& w) { deliver(process, s, w); });
    return std::nullopt;
  }

  template <typename Process>
  void deliver(Process& process, const Sample& sample, const WriterId& writer) {
    const std::optional<DropKind> why = sample.run_id() != options_.run_id
                                            ? std::optional<DropKind>(DropKind::kWrongRun)
                                            : process.receive(sample, writer);
    if (why) count_drop(*why, static_cast<int>(sample.station_id()), sample.step());
  }

  const options::NodeOptions& options_;
  int self_id_;
  std::string who_;
  std::string input_;
  double time_step_s_;
  NodePresence presence_;
  Reader<wire::Tick> ticks_;
  Reader<Sample> inputs_;
  ReaderWaitSet wait_set_;
  std::optional<Own> own_;
  DelayedInbox<Sample> delayed_;  // held by --link-delay-ms
  DropTally drops_;
  DropCounts reported_drops_{};  // as last announced
  std::uint64_t epoch_ns_ = 0;   // real time: the system-clock start of step 0
  std::optional<std::uint64_t> last_tick_;
  std::uint64_t lost_ = 0;  // samples removed by the simulated loss
};

}  // namespace skyfuse::transport
