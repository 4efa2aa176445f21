#include "report/live_feed.hpp"

#include <algorithm>
#include <chrono>

#include "report/run_channels.hpp"
#include "skyfuse/live/background_priority.hpp"

namespace skyfuse::harness {

LiveFeed::LiveFeed(const RunRecorder& recorder, live::LiveServer::Options options, double scene_hz)
    : channels_(std::make_unique<RunChannels>(recorder, 0)),
      scene_hz_(scene_hz),
      steps_(recorder.plan().scenario.steps) {
  std::vector<live::AdvertisedChannel> advertised;
  for (std::size_t i = 0; i < channels_->specs().size(); ++i) {
    const ChannelSpec& spec = channels_->specs()[i];
    advertised.push_back(
        {static_cast<std::uint32_t>(i), spec.topic, spec.schema_name, spec.schema});
  }
  server_ = std::make_unique<live::LiveServer>(std::move(options), std::move(advertised));
  thread_ = std::thread([this] {
    live::lower_this_thread_to_idle_priority();
    run();
  });
}

namespace {

live::LiveServer::Message to_live(ChannelMessage&& m) {
  return {static_cast<std::uint32_t>(m.channel), m.log_time_ns, std::move(m.json)};
}

}  // namespace

LiveFeed::~LiveFeed() {
  stop_thread();
}

void LiveFeed::stop_thread() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();  // every waiting round published
}

void LiveFeed::set_epoch_ns(std::uint64_t epoch_ns) {
  const std::lock_guard lock(mutex_);  // the feed's thread reads it after taking a round
  channels_->set_epoch_ns(epoch_ns);
}

void LiveFeed::offer(const RoundRecord& round) {
  const std::lock_guard lock(mutex_);
  if (waiting_.size() >= kMaxWaitingRounds) {
    waiting_.pop_front();
    ++dropped_;
  }
  waiting_.push_back(round);  // no notify: the feed wakes on its own clock
}

void LiveFeed::run() {
  using Clock = std::chrono::steady_clock;
  const auto period = [](double hz) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
  };
  const bool capped = scene_hz_ > 0.0;
  // Waking at the display's rate, not faster: each wake-up also wakes the clients, and both
  // take cores from the run at moments the run did not choose.
  const Clock::duration tick = period(capped ? scene_hz_ : kFiguresHz);
  const Clock::duration frame = capped ? period(scene_hz_) : Clock::duration::zero();
  const Clock::duration trails_period = period(kTrailsHz);
  Clock::time_point next_frame = Clock::now();
  Clock::time_point next_trails = next_frame;
  Clock::time_point last_wake = next_frame;
  double figure_tokens = kFiguresBurst;
  for (;;) {
    std::deque<RoundRecord> rounds;
    {
      std::unique_lock lock(mutex_);
      wake_.wait_for(lock, tick, [this] { return stopping_; });
      rounds.swap(waiting_);
      if (rounds.empty() && stopping_) return;
    }
    const Clock::time_point now = Clock::now();
    figure_tokens = std::min(
        kFiguresBurst,
        figure_tokens + std::chrono::duration<double>(now - last_wake).count() * kFiguresHz);
    last_wake = now;
    const bool scene_due = now >= next_frame;
    const bool trails_due = scene_due && now >= next_trails;
    if (scene_due && !rounds.empty()) next_frame = now + frame;
    if (trails_due && !rounds.empty()) next_trails = now + trails_period;
    server_->publish(batch_messages(rounds, scene_due, trails_due, figure_tokens));
  }
}

std::vector<live::LiveServer::Message> LiveFeed::batch_messages(std::deque<RoundRecord>& rounds,
                                                                bool scene_due, bool trails_due,
                                                                double& figure_tokens) {
  std::vector<live::LiveServer::Message> out;
  const bool wanted = server_->has_subscribers();
  const bool every_round = scene_hz_ <= 0.0;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    const RoundRecord& round = rounds[i];
    // The scene goes with the newest round of the wake-up, and with the last round of the run:
    // a viewer ends on it.
    const bool last = round.step + 1 == static_cast<std::uint64_t>(steps_);
    const bool scene = every_round || last || (scene_due && i + 1 == rounds.size());
    const bool figures = scene || figure_tokens >= 1.0;
    if (!wanted || !figures) {
      channels_->follow(round);
      continue;
    }
    figure_tokens = std::max(0.0, figure_tokens - 1.0);
    using Detail = RunChannels::Detail;
    const bool trails = every_round || last || trails_due;
    const Detail detail = !scene   ? Detail::kFiguresOnly
                          : trails ? Detail::kEveryRound
                                   : Detail::kDisplayFrame;
    for (ChannelMessage& m : channels_->round_messages(round, detail)) {
      out.push_back(to_live(std::move(m)));
    }
  }
  return out;
}

void LiveFeed::finish(std::string summary_json) {
  stop_thread();
  std::vector<live::LiveServer::Message> last;
  last.push_back(to_live(channels_->summary_message(std::move(summary_json))));
  server_->publish(std::move(last));
  server_->flush(2000);
}

std::uint64_t LiveFeed::rounds_dropped() const {
  const std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace skyfuse::harness
