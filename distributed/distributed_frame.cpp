#include "rayform/distributed/distributed_frame.h"

#include "rayform/distributed/ranks.h"
#include "rayform/distributed/tile_gather.h"
#include "rayform/distributed/work_counter.h"

#include <chrono>
#include <ctime>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

namespace rayform::distributed {

RenderResult render_frame_over_ranks(const PreparedScene& scene, const RenderOptions& options, FrameShare* share) {
  using clock = std::chrono::steady_clock;
  auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  try {
    RenderOptions o = options;
    o.progress = nullptr;  // the fraction handed out, below, not the fraction rendered here
    const TileGrid grid = tile_grid(o);
    const long long tiles = grid.count();
    RenderResult result = allocate_render_result(scene, o);
    std::vector<int> mine;
    std::mutex mutex;
    WorkCounter counter;
    const auto t_render = clock::now();
    const std::clock_t cpu_render = std::clock();
    render_tiles_from(
        scene, o,
        [&]() -> int {
          const long long t = counter.next();
          if (t >= tiles) return -1;
          std::lock_guard lock(mutex);
          mine.push_back(int(t));
          if (options.progress) options.progress(float(t + 1) / float(tiles));
          return int(t);
        },
        result);
    share->render_s = seconds_since(t_render);
    share->render_cpu_s = double(std::clock() - cpu_render) / CLOCKS_PER_SEC;
    share->tiles = (long long)mine.size();
    const auto t_gather = clock::now();
    gather_tiles(result, grid, mine);
    share->gather_s = seconds_since(t_gather);
    return result;
  } catch (const std::exception& e) {
    // The counter's window is collective to free and the others wait for
    // this rank's tiles: the job cannot go on.
    abort_ranks("rayform: error: rank " + std::to_string(ranks().rank) + " of " + std::to_string(ranks().size) + ": " +
                e.what() + " (ending the MPI job; no output written)");
  }
}

}  // namespace rayform::distributed
