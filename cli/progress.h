// Progress on stderr, only when stderr is shown on a terminal and not
// silenced: one line, redrawn in place, with the time elapsed and an estimate of the time
// left. An interrupted run (SIGINT, SIGTERM, SIGHUP) ends the line before its
// message (image/interrupt_cleanup.h).
#pragma once

#include <chrono>
#include <string>

namespace rayform::cli {

// Whether stderr is a terminal, or, under an MPI launcher, a pipe to the
// launcher's stderr that is one (mpirun, the parent of the ranks on its own
// node, draws what they write; ranks started by a remote daemon or srun show
// no progress line).
bool stderr_shows_on_terminal();

// A duration for people: "0:07", "1:05" (minutes:seconds), "1:02:03" (hours
// too); negative or non-finite values are "0:00"; fractions are rounded down.
std::string format_duration(double seconds);

// The progress line's text for `fraction` (0..1) done after `elapsed`
// seconds: "rendering  42%  0:12 elapsed, about 0:16 left". The estimate
// (elapsed * (1 - fraction) / fraction) is left out below 1 % done.
std::string progress_text(const std::string& label, float fraction, double elapsed);

class Progress {
 public:
  Progress(std::string label, bool quiet);
  ~Progress();  // ends an open line (an error is then printed on a line of its own)
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool enabled() const { return enabled_; }
  // Redraws the line when the percentage changes, or a second after the last draw.
  void update(float fraction);
  // "rendering done in 0:12" and a newline.
  void finish();

 private:
  using clock = std::chrono::steady_clock;
  double elapsed() const;
  void end_line();

  std::string label_;
  bool enabled_;
  clock::time_point start_ = clock::now();
  double last_draw_ = -1.0;
  int last_percent_ = -1;
  bool line_open_ = false;
};

}  // namespace rayform::cli
