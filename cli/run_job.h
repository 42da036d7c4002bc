// One render job run from the command line (pipeline/render_job.h does the
// work): its warnings, notes and progress line on stderr, --stats, and under
// mpirun the frame spread over every rank (distributed/frame_spread_ranks.h).
// Shared by the course-compatible flags and the `render` subcommand.
#pragma once

#include "rayform/pipeline/render_job.h"

namespace rayform::cli {

// What the command line says of a job besides errors.
struct Reporting {
  bool quiet = false;  // -q/--quiet: nothing but errors
  bool stats = false;  // --stats: timings and counts
};

// Runs `job`; throws as run_render_job does. With `spread` under mpirun,
// collective: every rank runs the same job, rank 0 reports and writes. A
// batch's renders, each on one rank, pass spread = false.
void run_job(const RenderJob& job, const Reporting& reporting, bool spread);

}  // namespace rayform::cli
