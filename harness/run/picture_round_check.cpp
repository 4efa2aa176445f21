#include "run/picture_round_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "run/lockstep_driver.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_truth.hpp"

namespace skyfuse::harness {
namespace {

// The center's picture against a peer's: rounds whose tracks (ids and statuses) differ, and the
// largest |x_center - x_p2p| / (1 + |x_center|) over the tracks both hold.
void compare_center(const wire::PictureRound& center, const wire::PictureRound& peer,
                    PictureRunSummary& summary) {
  const auto& mine = peer.tracks();
  const auto& theirs = center.tracks();
  bool same_tracks = mine.size() == theirs.size();
  for (std::size_t i = 0, j = 0; i < mine.size() && j < theirs.size();) {
    if (mine[i].track_id() < theirs[j].track_id()) {
      ++i;
    } else if (theirs[j].track_id() < mine[i].track_id()) {
      ++j;
    } else {
      same_tracks = same_tracks && mine[i].confirmed() == theirs[j].confirmed();
      double gap = 0.0;
      double norm = 0.0;
      for (std::size_t e = 0; e < theirs[j].x().size() && e < mine[i].x().size(); ++e) {
        gap += (theirs[j].x()[e] - mine[i].x()[e]) * (theirs[j].x()[e] - mine[i].x()[e]);
        norm += theirs[j].x()[e] * theirs[j].x()[e];
      }
      summary.max_state_gap_center_vs_p2p =
          std::max(summary.max_state_gap_center_vs_p2p, std::sqrt(gap) / (1.0 + std::sqrt(norm)));
      ++i;
      ++j;
    }
  }
  if (!same_tracks) ++summary.rounds_center_tracks_differ;
}

}  // namespace

std::string hex_digest(std::uint64_t digest) {
  return fmt::format("{:016x}", digest);
}

PictureRoundCheck::PictureRoundCheck(const PicturePlan& plan, const std::vector<TargetTruth>& truth,
                                     const PictureRunResult& twin, PictureRunSummary& summary)
    : plan_(plan),
      truth_(truth),
      twin_(twin),
      summary_(summary),
      score_(plan.scenario.traffic->gospa, truth.size(), plan.scenario.time_step_s) {
  csv_ << "step,station,picture_digest,tracks,confirmed,scans_fused,in_process_digest\n";
}

const PictureStep* PictureRoundCheck::add(int k, const std::vector<wire::PictureRound>& rounds) {
  const auto step = static_cast<std::size_t>(k);
  const wire::PictureRound* center = nullptr;
  const wire::PictureRound* first_peer = nullptr;
  bool in_time = rounds.size() == static_cast<std::size_t>(plan_.stations) + 1;
  for (const wire::PictureRound& r : rounds) {
    if (r.source_id() == kCenterNodeId) {
      center = &r;
    } else if (first_peer == nullptr) {
      first_peer = &r;
    }
    if (r.source_id() != kCenterNodeId &&
        r.scans_fused() != static_cast<std::uint32_t>(plan_.stations)) {
      in_time = false;
    }
  }
  if (in_time) ++summary_.rounds_in_time;
  for (const wire::PictureRound& r : rounds) {
    const bool is_center = r.source_id() == kCenterNodeId;
    const std::uint64_t expected =
        is_center ? twin_.center_digests.at(step) : twin_.peer_digests.at(step);
    const auto confirmed = std::count_if(r.tracks().begin(), r.tracks().end(),
                                         [](const auto& t) { return t.confirmed(); });
    csv_ << fmt::format("{},{},{},{},{},{},{}\n", k, r.source_id(), hex_digest(r.picture_digest()),
                        r.tracks().size(), confirmed, r.scans_fused(), hex_digest(expected));
    if (is_center) {
      if (r.picture_digest() != expected && summary_.center_equals_in_process) {
        summary_.center_equals_in_process = false;
        summary_.first_step_center_apart_from_in_process = k;
      }
      continue;
    }
    if (r.picture_digest() != first_peer->picture_digest() && apart_at_ != k) {
      apart_at_ = k;
      ++summary_.rounds_peers_apart;
      summary_.last_round_peers_apart = k;
      if (summary_.peers_identical) {
        summary_.peers_identical = false;
        summary_.first_divergent_step = k;
      }
    }
    if (r.picture_digest() != expected && summary_.equals_in_process) {
      summary_.equals_in_process = false;
      summary_.first_step_apart_from_in_process = k;
    }
  }
  if (first_peer == nullptr) {
    ++summary_.rounds_without_a_picture;
    return nullptr;
  }
  if (center != nullptr) compare_center(*center, *first_peer, summary_);
  aircraft_at_step(plan_.scenario, plan_.stations, truth_, k, aircraft_);
  confirmed_.clear();
  for (const wire::PictureTrack& t : first_peer->tracks()) {
    if (t.confirmed()) {
      confirmed_.push_back({t.track_id(), Vector3(t.x()[0], t.x()[1], t.x()[2])});
    }
  }
  const PictureStep& scored = score_.add_step(k, aircraft_, confirmed_);
  if (k + 1 == plan_.scenario.steps) {
    summary_.tracks_at_end = first_peer->tracks().size();
    summary_.confirmed_at_end = confirmed_.size();
    summary_.digest_at_end = first_peer->picture_digest();
  }
  return &scored;
}

}  // namespace skyfuse::harness
