#pragma once
// `skyfuse run --live`: each recorded round handed to a thread of its own, which turns it into
// the recording's messages (run_channels.hpp) and publishes them on the live server. offer()
// never blocks the rounds: it copies the round into a bounded queue, and when the feed falls
// that far behind it drops the oldest waiting round (and counts it).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

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
  static constexpr double kFiguresHz = 250.0;

  /// `scene_hz` 0: everything every round, nothing thinned.
  LiveFeed(const RunRecorder& recorder, std::uint64_t epoch_ns, live::LiveServer::Options options,
           double scene_hz = kDefaultSceneHz);
  ~LiveFeed();  ///< stops the thread and the server
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  std::uint16_t port() const { return server_->port(); }
  void offer(const RoundRecord& round);
  /// Publishes what is waiting and then `summary_json`, and waits up to 2 s for the clients'
  /// sockets to take it all.
  void finish(std::string summary_json);
  std::uint64_t rounds_dropped() const;
  live::LiveServer::Stats stats() const { return server_->stats(); }

 private:
  void run();

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
