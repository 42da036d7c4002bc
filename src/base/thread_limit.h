// The one place that bounds rayform's worker threads (oneTBB's
// max_allowed_parallelism): a render job bounds the whole job with it (load,
// BVH builds, render), render() its tiles.
#pragma once

#include <memory>

namespace rayform {

// While the returned handle lives, parallel work uses at most `threads`
// threads (the calling thread included); 0 or less: no bound (all hardware
// threads). Handles nest: the smallest bound in force applies.
std::shared_ptr<void> limit_threads(int threads);

// Starts oneTBB's worker threads on a helper thread (a process's first
// parallel loop pays for their start, 0.5 to 1 ms), so that the start
// overlaps other work; the returned handle joins it.
std::shared_ptr<void> start_worker_threads();

}  // namespace rayform
