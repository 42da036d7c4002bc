// A batch render in one process, or spread over the ranks of an MPI job:
// several input files (`rayform render a.glb b.obj c.txt -o 'out/{stem}.png'`)
// and/or a turntable of one scene (`--frames N`). Each render is a whole
// RenderJob on one rank; the renders are handed out dynamically (a
// WorkCounter), the largest input files first, so a rank that finishes early
// takes the next. A render that fails prints one line naming its input and
// the others still run.
#pragma once

#include "run_job.h"

#include <string>
#include <vector>

namespace rayform::cli {

// --frames N: N pictures with the --orbit camera (Orbit{} without it) turned
// about +y: frame k at azimuth AZ + k * sweep_deg / N.
struct Turntable {
  int frames = 0;  // 0: no turntable
  float sweep_deg = 360.f;
};

// The render jobs of the batch, in the order they are handed out (largest
// input file first, then frame by frame): `job` with each input, its
// outputs' {stem} and {frame} expanded (output_names.h) and, with a
// turntable, its orbit. Throws UsageError when two jobs would write the same
// file or a template lacks the placeholder that tells them apart.
std::vector<RenderJob> batch_jobs(const RenderJob& job, const std::vector<std::string>& inputs,
                                  const Turntable& turntable);

// Collective. Runs the jobs; returns the exit status: 0 when every render
// succeeded on every rank, else 1 (rank 0 then says how many failed). With
// `turntable`, a rank keeps the last file it read and renders the next
// frame of the same file from it (a copy) instead of reading it again.
int run_render_batch(const std::vector<RenderJob>& jobs, bool turntable, const Reporting& reporting);

}  // namespace rayform::cli
