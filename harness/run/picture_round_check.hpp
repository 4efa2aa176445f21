#pragma once
// Every round of a run of many aircraft over DDS checked as its pictures come: each station's
// against the others' and its in-process twin's, the center's against its twin's and its tracks
// against a peer's, the first station's scored against the truth (GOSPA), and a row per node
// for picture_rounds.csv.

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "run/picture_run.hpp"
#include "skyfuse/metrics/picture_score.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/target_truth.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::harness {

/// A picture digest as picture_rounds.csv and summary.json write it: 16 hex digits.
std::string hex_digest(std::uint64_t digest);

class PictureRoundCheck {
 public:
  /// Checks the rounds of `plan` against `truth` and the in-process `twin` into `summary`.
  PictureRoundCheck(const PicturePlan& plan, const std::vector<TargetTruth>& truth,
                    const PictureRunResult& twin, PictureRunSummary& summary);

  /// Round k's pictures: those that came, in node order (the center first). Returns the first
  /// station's score against the aircraft (valid until the next add), or nothing when no
  /// station's picture came.
  const PictureStep* add(int k, const std::vector<wire::PictureRound>& rounds);

  /// picture_rounds.csv: a row per node and round.
  std::string csv() const { return csv_.str(); }
  /// The first station's confirmed tracks scored over the rounds added (GOSPA, SIAP).
  PictureSummary score() const { return score_.summary(); }

 private:
  const PicturePlan& plan_;
  const std::vector<TargetTruth>& truth_;
  const PictureRunResult& twin_;
  PictureRunSummary& summary_;
  PictureScore score_;
  std::ostringstream csv_;
  int apart_at_ = -1;  // the last round found with peers apart
  std::vector<TruthPoint> aircraft_;
  std::vector<TrackPoint> confirmed_;
};

}  // namespace skyfuse::harness
