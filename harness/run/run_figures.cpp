#include "run/run_figures.hpp"

#include <fmt/format.h>

namespace skyfuse::harness {

void RunFigures::take(const ProcessMeasures& measured) {
  if (measured.stopped) {
    stop_cause = measured.stopped->cause();
    end_detail = measured.stopped->what();
  }
  discovery = measured.discovery;
  discovery_s = measured.discovery_s;
  settle_s = measured.settle_s;
  settled_quiet = measured.settled_quiet;
  datagrams_per_round = measured.datagrams_per_round;
  cpu_ms_per_station_round = measured.cpu_ms_per_station_round;
  node_peak_resident_mib = measured.node_peak_resident_mib;
  node_exits = measured.node_exits;
}

std::string host_verdict(const RunFigures& s, const RealtimeLoad& load, double time_step_s,
                         const std::string& cpu, unsigned cores) {
  if (load.deadline_ms <= 0.0) return {};
  const bool fell_behind = s.stop_cause == StopCause::kFellBehind;
  if (!fell_behind && load.share_in_time >= 0.99) return {};
  const double rate_hz = 1.0 / time_step_s;
  // CPU per station-round times the stations a step, over a step's time: cores kept busy.
  const double cores_needed = s.cpu_ms_per_station_round * s.stations / (1e3 * time_step_s);
  const std::string host = fmt::format("this host ({}, {} cores)", cpu, cores);
  const std::string rate = fmt::format("{} stations at {:.0f} Hz with a {:g} ms deadline",
                                       s.stations, rate_hz, load.deadline_ms);
  const std::string cost = fmt::format(
      "the run used {:.2f} ms of CPU per station-round, {:.1f} cores' worth at that rate",
      s.cpu_ms_per_station_round, cores_needed);
  if (fell_behind) {
    return fmt::format(
        "{} could not carry {}: {} of {} steps complete ({} recorded), {:.1f} s behind the "
        "schedule when the run stopped; {}",
        host, rate, load.rounds_complete, s.steps_planned, s.steps, load.behind_s, cost);
  }
  return fmt::format(
      "{} carried {} only in part: {:.1f} % of the rounds had every input in time; {}", host, rate,
      100.0 * load.share_in_time, cost);
}

}  // namespace skyfuse::harness
