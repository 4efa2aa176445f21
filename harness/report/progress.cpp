#include "report/progress.hpp"

#include <unistd.h>

#include <algorithm>

namespace skyfuse::harness {

Progress::Progress(std::string label, long total)
    : label_(std::move(label)), total_(std::max(total, 1L)), interactive_(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  finish();
}

void Progress::set_stage(std::string stage) {
  stage_ = std::move(stage);
  if (interactive_) draw();
}

void Progress::advance(long amount) {
  done_ = std::min(done_ + amount, total_);
  draw();
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (interactive_) std::fputc('\n', stderr);
}

void Progress::draw() {
  const int percent = static_cast<int>(100 * done_ / total_);
  if (interactive_) {
    std::fprintf(stderr, "\r%s [%3d%%] %ld/%ld %s\033[K", label_.c_str(), percent, done_, total_,
                 stage_.c_str());
    std::fflush(stderr);
    return;
  }
  const int decile = percent / 10;
  if (decile != last_decile_) {
    last_decile_ = decile;
    std::fprintf(stderr, "%s [%3d%%] %s\n", label_.c_str(), percent, stage_.c_str());
  }
}

}  // namespace skyfuse::harness
