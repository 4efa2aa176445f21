#pragma once
// `skyfuse run --live`: each round handed to a thread of its own, which turns it into the
// recording's messages and publishes them on the live server. offer() never blocks the rounds:
// it copies the round into a bounded queue, and when the feed falls that far behind it drops the
// oldest waiting round (and counts it).
//
// The feed's thread wakes on its own clock (the scenes' rate), not once per round: at a
// lock-step run's thousands of rounds a second, a wake-up per round cost the run more than the
// messages did. Each wake takes every waiting round, publishes what is due in one hand-over to
// the server, and builds nothing while no client is subscribed. Its thread and the server's
// run SCHED_IDLE (background_priority.hpp).
//
// What a round is and which messages it makes is the Source's (a run of one aircraft:
// run_live_source.hpp; of many: picture_live_source.hpp):
//
//     using Round = ...;                                   // what offer() copies
//     const std::vector<ChannelSpec>& specs() const;
//     void set_epoch_ns(std::uint64_t);
//     std::vector<ChannelMessage> batch(std::deque<Round>&, LiveWake&);
//     ChannelMessage summary_message(std::string summary_json) const;

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "report/run_channels.hpp"
#include "skyfuse/live/background_priority.hpp"
#include "skyfuse/live/live_server.hpp"

namespace skyfuse::harness {

/// What one wake-up of a feed may send, for its Source's batch().
struct LiveWake {
  bool every_round = false;  ///< nothing thinned (a scene rate of 0)
  bool scene_due = false;    ///< a scene (frames, map fixes) is due with the newest round
  bool trails_due = false;   ///< the trails are due with that scene
  bool wanted = false;       ///< a client is subscribed: without one, nothing is built
  /// Rounds of figures that may go out (a token bucket): a round of figures takes one.
  double figure_tokens = 0.0;

  /// What the wake-up sends of the `i`-th of its `n` rounds, either kind's (`last`: the run's
  /// last round): nothing (the source only follows the round), its figures, or its figures and
  /// the scene, which goes with the newest round of the wake-up and with the run's last, so a
  /// viewer ends on it; the trails with the scene when due.
  struct Send {
    bool figures = false;
    bool scene = false;
    bool trails = false;
  };
  Send send(std::size_t i, std::size_t n, bool last) {
    const bool scene = every_round || last || (scene_due && i + 1 == n);
    if (!wanted || (!scene && figure_tokens < 1.0)) return {};
    figure_tokens = std::max(0.0, figure_tokens - 1.0);
    return {true, scene, scene && (every_round || last || trails_due)};
  }
};

namespace live_rates {
inline constexpr std::size_t kMaxWaitingRounds = 4096;
/// The most rounds of skyfuse's own channels a second while scenes are capped: every round
/// of a real-time run (50 Hz), a sample of a lock-step run's thousands.
inline constexpr double kFiguresHz = 60.0;
/// The most scenes a second that carry the trails (300 points, most of a scene's bytes): a
/// 50 Hz run's trails take a point 5 times a second.
inline constexpr double kTrailsHz = 5.0;
/// Rounds of figures that may go out at once after a quiet spell.
inline constexpr double kFiguresBurst = 4.0;
}  // namespace live_rates

template <typename Source>
class LiveFeedOf {
 public:
  using Round = typename Source::Round;
  static constexpr std::size_t kMaxWaitingRounds = live_rates::kMaxWaitingRounds;

  /// `scene_hz`: the most scenes (frames, map fixes) a second (RunOptions::live_scene_hz); 0:
  /// everything every round, nothing thinned. The Source is made of `args`.
  template <typename... Args>
  LiveFeedOf(live::LiveServer::Options options, double scene_hz, Args&&... args)
      : source_(std::forward<Args>(args)...), scene_hz_(scene_hz) {
    std::vector<live::AdvertisedChannel> advertised;
    for (std::size_t i = 0; i < source_.specs().size(); ++i) {
      const ChannelSpec& spec = source_.specs()[i];
      advertised.push_back(
          {static_cast<std::uint32_t>(i), spec.topic, spec.schema_name, spec.schema});
    }
    server_ = std::make_unique<live::LiveServer>(std::move(options), std::move(advertised));
    thread_ = std::thread([this] {
      live::lower_this_thread_to_idle_priority();
      run();
    });
  }
  ~LiveFeedOf() { stop_thread(); }  ///< stops the thread, then the server
  LiveFeedOf(const LiveFeedOf&) = delete;
  LiveFeedOf& operator=(const LiveFeedOf&) = delete;

  std::uint16_t port() const { return server_->port(); }
  /// Step 0's log time, the recording's (call before the first offer): the stream and the
  /// recording of one run stamp every message alike.
  void set_epoch_ns(std::uint64_t epoch_ns) {
    const std::lock_guard lock(mutex_);  // the feed's thread reads it after taking a round
    source_.set_epoch_ns(epoch_ns);
  }
  void offer(const Round& round) {
    const std::lock_guard lock(mutex_);
    if (waiting_.size() >= kMaxWaitingRounds) {
      waiting_.pop_front();
      ++dropped_;
    }
    waiting_.push_back(round);  // no notify: the feed wakes on its own clock
  }
  /// Publishes what is waiting and then `summary_json`, and waits up to 2 s for the clients'
  /// sockets to take it all.
  void finish(std::string summary_json) {
    stop_thread();
    std::vector<live::LiveServer::Message> last;
    last.push_back(to_live(source_.summary_message(std::move(summary_json))));
    server_->publish(std::move(last));
    server_->flush(2000);
  }
  std::uint64_t rounds_dropped() const {
    const std::lock_guard lock(mutex_);
    return dropped_;
  }
  live::LiveServer::Stats stats() const { return server_->stats(); }

 private:
  static live::LiveServer::Message to_live(ChannelMessage&& m) {
    return {static_cast<std::uint32_t>(m.channel), m.log_time_ns, std::move(m.json)};
  }

  void stop_thread() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();  // every waiting round published
  }

  void run() {
    using Clock = std::chrono::steady_clock;
    const auto period = [](double hz) {
      return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
    };
    const bool capped = scene_hz_ > 0.0;
    // Waking at the display's rate, not faster: each wake-up also wakes the clients, and both
    // take cores from the run at moments the run did not choose.
    const Clock::duration tick = period(capped ? scene_hz_ : live_rates::kFiguresHz);
    const Clock::duration frame = capped ? period(scene_hz_) : Clock::duration::zero();
    const Clock::duration trails_period = period(live_rates::kTrailsHz);
    Clock::time_point next_frame = Clock::now();
    Clock::time_point next_trails = next_frame;
    Clock::time_point last_wake = next_frame;
    LiveWake wake;
    wake.every_round = !capped;
    wake.figure_tokens = live_rates::kFiguresBurst;
    for (;;) {
      std::deque<Round> rounds;
      {
        std::unique_lock lock(mutex_);
        wake_.wait_for(lock, tick, [this] { return stopping_; });
        rounds.swap(waiting_);
        if (rounds.empty() && stopping_) return;
      }
      const Clock::time_point now = Clock::now();
      wake.figure_tokens =
          std::min(live_rates::kFiguresBurst,
                   wake.figure_tokens + std::chrono::duration<double>(now - last_wake).count() *
                                            live_rates::kFiguresHz);
      last_wake = now;
      wake.scene_due = now >= next_frame;
      wake.trails_due = wake.scene_due && now >= next_trails;
      wake.wanted = server_->has_subscribers();
      if (wake.scene_due && !rounds.empty()) next_frame = now + frame;
      if (wake.trails_due && !rounds.empty()) next_trails = now + trails_period;
      std::vector<live::LiveServer::Message> out;
      for (ChannelMessage& m : source_.batch(rounds, wake)) out.push_back(to_live(std::move(m)));
      server_->publish(std::move(out));
    }
  }

  Source source_;
  double scene_hz_;
  std::unique_ptr<live::LiveServer> server_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Round> waiting_;
  std::uint64_t dropped_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace skyfuse::harness
