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
// turntable, its orbit. Each job is made when it is asked for (operator[]),
// so that a batch of 10^9 frames starts at once in constant memory.
class BatchJobs {
 public:
  // Throws UsageError when two jobs would write the same file (checked over
  // every input at the first and the last frame: the frames of one input
  // differ by their {frame} number) or a template lacks the placeholder that
  // tells them apart.
  BatchJobs(const RenderJob& job, const std::vector<std::string>& inputs, const Turntable& turntable);
  long long size() const { return (long long)inputs_.size() * frames_; }
  // Job i, 0 <= i < size().
  RenderJob operator[](long long i) const;

 private:
  RenderJob job_;
  std::vector<std::string> inputs_;  // largest file first
  Turntable turntable_;
  long long frames_ = 1;
};

inline BatchJobs batch_jobs(const RenderJob& job, const std::vector<std::string>& inputs, const Turntable& turntable) {
  return BatchJobs(job, inputs, turntable);
}

// Collective. Runs the jobs; returns the exit status: 0 when every render
// succeeded on every rank, else 1 (rank 0 then says how many failed). With
// `turntable`, a rank keeps the last file it read and renders the next
// frame of the same file from it (a copy) instead of reading it again.
int run_render_batch(const BatchJobs& jobs, bool turntable, const Reporting& reporting);

}  // namespace rayform::cli
