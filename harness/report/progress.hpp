#pragma once
// A progress line on stderr: redrawn in place on a terminal, one line per 10 % otherwise (so
// CI logs stay short).

#include <cstdio>
#include <string>

namespace skyfuse::harness {

class Progress {
 public:
  Progress(std::string label, long total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void set_stage(std::string stage);
  void advance(long amount = 1);
  void finish();

 private:
  void draw();

  std::string label_;
  std::string stage_;
  long total_;
  long done_ = 0;
  int last_decile_ = -1;
  bool interactive_;
  bool finished_ = false;
};

}  // namespace skyfuse::harness
