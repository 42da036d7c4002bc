#include "run_job.h"

#include "messages.h"
#include "progress.h"
#include "rayform/distributed/frame_spread_ranks.h"
#include "rayform/distributed/ranks.h"

#include <iostream>
#include <memory>
#include <optional>

namespace rayform::cli {

void run_job(const RenderJob& job, const Reporting& reporting, bool spread) {
  set_quiet(reporting.quiet);
  std::unique_ptr<FrameSpread> ranks;
  if (spread && distributed::ranks().distributed())
    ranks = distributed::spread_frame_over_ranks(job.input, reporting.stats);
  // Warnings, notes and progress from rank 0 only: the others would repeat them.
  const bool quiet = reporting.quiet || (ranks && !ranks->writer());
  JobHooks hooks;
  hooks.spread = ranks.get();
  if (!quiet) {
    hooks.warn = [](const std::string& w) { warn(w); };
    hooks.note = [](const std::string& n) { note(n); };
  }
  std::optional<Progress> progress;
  if (!quiet && stderr_shows_on_terminal()) {
    hooks.render_started = [&] { progress.emplace("rendering", false); };
    hooks.progress = [&](float f) { progress->update(f); };
    hooks.render_done = [&] { progress->finish(); };
  }
  const JobReport r = run_render_job(job, hooks);
  if (reporting.stats && r.wrote)
    std::cerr << "stats: load " << r.load_s << " s, prepare " << r.prepare_s << " s, render " << r.render_s
              << " s, write " << r.write_s << " s (" << r.render_path << " path, " << r.width << "x" << r.height << ", "
              << r.sampling << "), accel " << r.accel_bytes / 1024 << " KiB\n";
}

}  // namespace rayform::cli
