#pragma once
// `skyfuse run --live`: each recorded round handed to a thread of its own, which turns it into
// the recording's messages (run_channels.hpp) and publishes them on the live server. offer()
// never blocks the rounds: it copies the round into a bounded queue, and when the feed falls
// that far behind it drops the oldest waiting round (and counts it).
//
// The feed's thread wakes on its own clock (the scenes' rate), not once per round: at a
// lock-step run's thousands of rounds a second, a wake-up per round cost the run more than the
// messages did. Each wake takes every waiting round, publishes what is due in one hand-over to
// the server, and builds nothing while no client is subscribed. Its thread and the server's
// run SCHED_IDLE (background_priority.hpp).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "run/run_report.hpp"
#include "skyfuse/live/live_server.hpp"

namespace skyfuse::harness {

class RunChannels;

class LiveFeed {
 public:
  static constexpr std::size_t kMaxWaitingRounds = 4096;
  /// The most scenes (and frames and map fixes) a second: a display's rate.
  static constexpr double kDefaultSceneHz = 30.0;
  /// The most rounds of skyfuse's own channels a second while scenes are capped: every round
  /// of a real-time run (50 Hz), a sample of a lock-step run's thousands.
  static constexpr double kFiguresHz = 60.0;
  /// The most scenes a second that carry the trails (300 points, most of a scene's bytes): a
  /// 50 Hz run's trails take a point 5 times a second.
  static constexpr double kTrailsHz = 5.0;
  /// Rounds of figures that may go out at once after a quiet spell (a token bucket).
  static constexpr double kFiguresBurst = 4.0;

  /// `scene_hz` 0: everything every round, nothing thinned.
  LiveFeed(const RunRecorder& recorder, live::LiveServer::Options options,
           double scene_hz = kDefaultSceneHz);
  ~LiveFeed();  ///< stops the thread and the server
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  std::uint16_t port() const { return server_->port(); }
  /// Step 0's log time, the recording's (call before the first offer): the stream and the
  /// recording of one run stamp every message alike.
  void set_epoch_ns(std::uint64_t epoch_ns);
  void offer(const RoundRecord& round);
  /// Publishes what is waiting and then `summary_json`, and waits up to 2 s for the clients'
  /// sockets to take it all.
  void finish(std::string summary_json);
  std::uint64_t rounds_dropped() const;
  live::LiveServer::Stats stats() const { return server_->stats(); }

 private:
  void run();
  void stop_thread();  ///< after the rounds still waiting are published
  /// The messages for the rounds taken in one wake-up; trails follow every round.
  std::vector<live::LiveServer::Message> batch_messages(std::deque<RoundRecord>& rounds,
                                                        bool scene_due, bool trails_due,
                                                        double& figure_tokens);

  std::unique_ptr<RunChannels> channels_;
  double scene_hz_;
  int steps_;
  std::unique_ptr<live::LiveServer> server_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<RoundRecord> waiting_;
  std::uint64_t dropped_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace skyfuse::harness
