// Progress on stderr, only when stderr is a terminal and not silenced.
#pragma once

#include <cstdio>
#include <string>
#include <unistd.h>

namespace rayform::cli {

class Progress {
 public:
  Progress(std::string label, bool quiet) : label_(std::move(label)), enabled_(!quiet && isatty(STDERR_FILENO)) {}
  bool enabled() const { return enabled_; }
  void update(float fraction) {
    int percent = int(fraction * 100.f);
    if (!enabled_ || percent == last_) return;
    last_ = percent;
    std::fprintf(stderr, "\r%s %3d%%", label_.c_str(), percent);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_ && last_ >= 0) std::fprintf(stderr, "\r%s done\n", label_.c_str());
  }

 private:
  std::string label_;
  bool enabled_;
  int last_ = -1;
};

}  // namespace rayform::cli
