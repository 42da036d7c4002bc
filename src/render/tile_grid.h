// The tiles a render splits its image into: squares of RenderOptions::tile_size
// pixels (smaller at the right and bottom edges), numbered row by row from the
// top left. A tile is the unit of work handed to threads and, through
// render_tiles_from (render.h), to other processes.
#pragma once

namespace rayform {

struct TileRect {
  int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1), rows from the top
};

struct TileGrid {
  int width = 0, height = 0;
  int tile_size = 16;
  int tiles_x = 0, tiles_y = 0;

  int count() const { return tiles_x * tiles_y; }
  TileRect rect(int tile) const {
    const int x0 = (tile % tiles_x) * tile_size, y0 = (tile / tiles_x) * tile_size;
    return {x0, y0, x0 + tile_size < width ? x0 + tile_size : width, y0 + tile_size < height ? y0 + tile_size : height};
  }
};

// The grid of a width x height image with tiles of tile_size pixels (at least 1).
inline TileGrid make_tile_grid(int width, int height, int tile_size) {
  const int ts = tile_size < 1 ? 1 : tile_size;
  return {width, height, ts, (width + ts - 1) / ts, (height + ts - 1) / ts};
}

}  // namespace rayform
