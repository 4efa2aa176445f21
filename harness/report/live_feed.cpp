#include "report/live_feed.hpp"

#include <chrono>

#include "report/run_channels.hpp"

namespace skyfuse::harness {

LiveFeed::LiveFeed(const RunRecorder& recorder, std::uint64_t epoch_ns,
                   live::LiveServer::Options options, double scene_hz)
    : channels_(std::make_unique<RunChannels>(recorder, epoch_ns)),
      scene_hz_(scene_hz),
      steps_(recorder.plan().scenario.steps) {
  std::vector<live::AdvertisedChannel> advertised;
  for (std::size_t i = 0; i < channels_->specs().size(); ++i) {
    const ChannelSpec& spec = channels_->specs()[i];
    advertised.push_back(
        {static_cast<std::uint32_t>(i), spec.topic, spec.schema_name, spec.schema});
  }
  server_ = std::make_unique<live::LiveServer>(std::move(options), std::move(advertised));
  thread_ = std::thread([this] { run(); });
}

LiveFeed::~LiveFeed() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void LiveFeed::offer(const RoundRecord& round) {
  {
    const std::lock_guard lock(mutex_);
    if (waiting_.size() >= kMaxWaitingRounds) {
      waiting_.pop_front();
      ++dropped_;
    }
    waiting_.push_back(round);
  }
  wake_.notify_one();
}

void LiveFeed::run() {
  using Clock = std::chrono::steady_clock;
  const auto period = [](double hz) {
    return std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(hz > 0.0 ? 1.0 / hz : 0.0));
  };
  const Clock::duration frame = period(scene_hz_);
  const Clock::duration figures = period(scene_hz_ > 0.0 ? kFiguresHz : 0.0);
  Clock::time_point next_frame = Clock::now();
  Clock::time_point next_figures = next_frame;
  for (;;) {
    RoundRecord round;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
      if (waiting_.empty()) return;  // stopping, and nothing left
      round = std::move(waiting_.front());
      waiting_.pop_front();
    }
    // A scene when the display is due one, and for the last round: a viewer ends on it.
    const Clock::time_point now = Clock::now();
    const bool last = round.step + 1 == static_cast<std::uint64_t>(steps_);
    const bool scene = now >= next_frame || last;
    if (scene) next_frame = now + frame;
    if (!scene && now < next_figures) {
      channels_->follow(round);
      continue;
    }
    next_figures = now + figures;
    const auto detail =
        scene ? RunChannels::Detail::kDisplayFrame : RunChannels::Detail::kFiguresOnly;
    for (ChannelMessage& m : channels_->round_messages(round, detail)) {
      server_->publish(static_cast<std::uint32_t>(m.channel), m.log_time_ns, std::move(m.json));
    }
  }
}

void LiveFeed::finish(std::string summary_json) {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();  // every waiting round published
  ChannelMessage summary = channels_->summary_message(std::move(summary_json));
  server_->publish(static_cast<std::uint32_t>(summary.channel), summary.log_time_ns,
                   std::move(summary.json));
  server_->flush(2000);
}

std::uint64_t LiveFeed::rounds_dropped() const {
  const std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace skyfuse::harness
