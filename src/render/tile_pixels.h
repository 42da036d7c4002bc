// The pixels of some tiles of a RenderResult as one block of bytes, and back:
// how a render spread over processes brings its tiles to one result. Every
// buffer the result holds (colour, depth, normals, albedo, coverage) goes,
// tile by tile in the order given, each tile's rows of each buffer in turn,
// bytes as they are in memory (the processes share one machine's format).
#pragma once

#include "rayform/render/render.h"

#include <cstddef>
#include <span>
#include <vector>

namespace rayform {

// How many bytes pack_tile_pixels writes for `tiles` of `result`.
size_t tile_pixel_bytes(const RenderResult& result, const TileGrid& grid, std::span<const int> tiles);

// The pixels of `tiles` (indices into `grid`, the grid `result` was
// rendered with). Throws rayform::Error for a tile outside the grid.
std::vector<unsigned char> pack_tile_pixels(const RenderResult& result, const TileGrid& grid,
                                            std::span<const int> tiles);

// Writes the pixels packed from `tiles` into the same tiles of `result`,
// which must hold the same buffers as the packed one (the same options).
// Throws rayform::Error when the size of `bytes` does not fit, or a tile is
// outside the grid.
void unpack_tile_pixels(RenderResult& result, const TileGrid& grid, std::span<const int> tiles,
                        std::span<const unsigned char> bytes);

}  // namespace rayform
