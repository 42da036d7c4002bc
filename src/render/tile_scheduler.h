// The tile scheduler: which tiles a render pass renders, on which threads,
// and the progress it reports. Every tile over oneTBB (ranges split down to one tile), or
// the tiles a NextTile hook hands out (render_tiles_from: processes sharing a
// frame); with RenderOptions::threads 1 all on the calling thread, else on at
// most that many threads (base/thread_limit.h) while the scheduler lives.
#pragma once

#include "rayform/render/render.h"

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>

namespace rayform {

// A call on one tile index, by reference to a callable that outlives it (no
// copy, no allocation; one indirect call per tile).
class TileFunction {
 public:
  template <class F>
  TileFunction(const F& f)  // implicit: a lambda passes as it is
      : object_(&f), call_([](const void* object, int tile) { (*static_cast<const F*>(object))(tile); }) {}
  void operator()(int tile) const { call_(object_, tile); }

 private:
  const void* object_;
  void (*call_)(const void*, int);
};

class TileScheduler {
 public:
  // `tiles`: how many the image has; `passes`: how often a render renders
  // each (the progress fraction counts tiles of all passes).
  TileScheduler(int tiles, int threads, int passes, const std::function<void(float)>& progress);

  // Renders every tile.
  void every_tile(TileFunction render_tile);
  // Renders the tiles `next` hands out (indices checked against the image's
  // tiles) until it returns a negative number; every tile when next is null.
  void tiles_from(const NextTile* next, TileFunction render_tile);

 private:
  void tile_done();

  int tiles_, threads_, progress_steps_;
  const std::function<void(float)>& progress_;
  std::shared_ptr<void> thread_limit_;
  std::atomic<int> done_{0};
  std::mutex progress_mutex_;
};

}  // namespace rayform
