#include "progress.h"

#include "rayform/distributed/mpi_launcher.h"

#include "rayform/image/interrupt_cleanup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace rayform::cli {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) seconds = 0.0;
  const long long total = static_cast<long long>(std::min(seconds, 1e12));
  const long long h = total / 3600, m = total / 60 % 60, s = total % 60;
  char text[64];
  if (h > 0) std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", h, m, s);
  else std::snprintf(text, sizeof text, "%lld:%02lld", m, s);
  return text;
}

std::string progress_text(const std::string& label, float fraction, double elapsed) {
  if (!(fraction >= 0.f)) fraction = 0.f;
  if (fraction > 1.f) fraction = 1.f;
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3d%%", int(fraction * 100.f));
  std::string text = label + " " + percent + "  " + format_duration(elapsed) + " elapsed";
  if (fraction >= 0.01f) text += ", about " + format_duration(elapsed * (1.0 - fraction) / fraction) + " left";
  return text;
}

bool stderr_shows_on_terminal() {
  if (isatty(STDERR_FILENO)) return true;
  if (!distributed::launched_by_mpi_launcher()) return false;
  // mpirun forwards its ranks' stderr through pipes to its own: on the node
  // where it runs, it is the ranks' parent, and its stderr is the user's.
  const std::string parent_stderr = "/proc/" + std::to_string(getppid()) + "/fd/2";
  char target[256];
  const ssize_t n = readlink(parent_stderr.c_str(), target, sizeof target - 1);
  if (n <= 0) return false;
  const std::string device(target, size_t(n));
  return device.starts_with("/dev/pts/") || device.starts_with("/dev/tty");
}

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), enabled_(!quiet && stderr_shows_on_terminal()) {}

Progress::~Progress() { end_line(); }

double Progress::elapsed() const { return std::chrono::duration<double>(clock::now() - start_).count(); }

void Progress::update(float fraction) {
  if (!enabled_) return;
  const int percent = int(fraction * 100.f);
  const double t = elapsed();
  if (percent == last_percent_ && t - last_draw_ < 1.0) return;
  last_percent_ = percent;
  last_draw_ = t;
  // \033[K clears what a longer earlier line left on the right.
  std::fprintf(stderr, "\r%s\033[K", progress_text(label_, fraction, t).c_str());
  std::fflush(stderr);
  if (!line_open_) {
    line_open_ = true;
    set_interrupt_line_open(true);
  }
}

void Progress::finish() {
  if (!line_open_) return;
  std::fprintf(stderr, "\r%s done in %s\033[K", label_.c_str(), format_duration(elapsed()).c_str());
  end_line();
}

void Progress::end_line() {
  if (!line_open_) return;
  std::fprintf(stderr, "\n");
  std::fflush(stderr);
  line_open_ = false;
  set_interrupt_line_open(false);
}

}  // namespace rayform::cli
