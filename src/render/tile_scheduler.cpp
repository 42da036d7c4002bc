#include "rayform/render/tile_scheduler.h"

#include "rayform/base/error.h"
#include "rayform/base/thread_limit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <string>

namespace rayform {

TileScheduler::TileScheduler(int tiles, int threads, int passes, const std::function<void(float)>& progress)
    : tiles_(tiles),
      threads_(threads),
      progress_steps_(passes * tiles),
      progress_(progress),
      thread_limit_(limit_threads(threads)) {}

void TileScheduler::tile_done() {
  if (!progress_) return;
  const int n = ++done_;
  std::lock_guard lock(progress_mutex_);
  progress_(float(n) / float(progress_steps_));
}

void TileScheduler::every_tile(TileFunction render_tile) {
  auto run = [&](int t) {
    render_tile(t);
    tile_done();
  };
  if (threads_ == 1) {
    for (int t = 0; t < tiles_; ++t) run(t);
  } else {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t < r.end(); ++t) run(t);
    });
  }
}

void TileScheduler::tiles_from(const NextTile* next, TileFunction render_tile) {
  if (!next) return every_tile(render_tile);
  auto work = [&] {
    for (int t; (t = (*next)()) >= 0;) {
      if (t >= tiles_)
        throw Error("render: tile " + std::to_string(t) + " handed out, the image has " + std::to_string(tiles_));
      render_tile(t);
      tile_done();
    }
  };
  if (threads_ == 1) work();
  else tbb::parallel_for(0, tbb::this_task_arena::max_concurrency(), [&](int) { work(); });
}

}  // namespace rayform
