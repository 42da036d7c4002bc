// Bringing the tiles every rank rendered to rank 0's result (render.h:
// render_tiles_from; render/tile_pixels.h packs them).
#pragma once

#include "rayform/render/render.h"

#include <vector>

namespace rayform::distributed {

// Collective. Each rank passes its result and the tiles it rendered into
// it; afterwards rank 0's `result` holds every rank's tiles (the others' are
// unchanged). Ranks send in pieces of about 16 MiB, rank 0 receives rank by
// rank: besides the image, each holds one piece at a time.
void gather_tiles(RenderResult& result, const TileGrid& grid, const std::vector<int>& mine);

}  // namespace rayform::distributed
