#include "rayform/render/tile_pixels.h"

#include "rayform/base/error.h"

#include <cstring>
#include <string>

namespace rayform {
namespace {

// One buffer of a result: its first byte and the bytes of one pixel.
struct BufferView {
  unsigned char* data;
  size_t pixel_bytes;
};

// The buffers `r` holds, in the order they are packed.
std::vector<BufferView> buffers(const RenderResult& r) {
  std::vector<BufferView> p;
  auto add = [&](const void* data, size_t bytes) {
    p.push_back({static_cast<unsigned char*>(const_cast<void*>(data)), bytes});
  };
  if (!r.color.pixels.empty()) add(r.color.pixels.data(), 3 * sizeof(float));
  if (!r.color8.pixels.empty()) add(r.color8.pixels.data(), 3);
  if (!r.depth.empty()) add(r.depth.data(), sizeof(float));
  if (!r.normals.empty()) add(r.normals.data(), sizeof(vec3));
  if (!r.albedo.pixels.empty()) add(r.albedo.pixels.data(), 3 * sizeof(float));
  if (!r.albedo8.pixels.empty()) add(r.albedo8.pixels.data(), 3);
  if (!r.coverage.empty()) add(r.coverage.data(), sizeof(float));
  return p;
}

TileRect checked_rect(const TileGrid& grid, int tile) {
  if (tile < 0 || tile >= grid.count())
    throw Error("tile pixels: tile " + std::to_string(tile) + " is outside the image's " +
                std::to_string(grid.count()) + " tiles");
  return grid.rect(tile);
}

// Calls copy(pixel offset in the plane's buffer, bytes) for every row of
// every tile of every plane, in the packed order.
template <class Copy>
void each_row(const std::vector<BufferView>& ps, const TileGrid& grid, std::span<const int> tiles, Copy copy) {
  for (int tile : tiles) {
    const TileRect r = checked_rect(grid, tile);
    for (const BufferView& p : ps)
      for (int y = r.y0; y < r.y1; ++y)
        copy(p.data + (size_t(y) * size_t(grid.width) + size_t(r.x0)) * p.pixel_bytes,
             size_t(r.x1 - r.x0) * p.pixel_bytes);
  }
}

}  // namespace

size_t tile_pixel_bytes(const RenderResult& result, const TileGrid& grid, std::span<const int> tiles) {
  size_t per_pixel = 0;
  for (const BufferView& p : buffers(result)) per_pixel += p.pixel_bytes;
  size_t pixels = 0;
  for (int tile : tiles) {
    const TileRect r = checked_rect(grid, tile);
    pixels += size_t(r.x1 - r.x0) * size_t(r.y1 - r.y0);
  }
  return pixels * per_pixel;
}

std::vector<unsigned char> pack_tile_pixels(const RenderResult& result, const TileGrid& grid,
                                            std::span<const int> tiles) {
  std::vector<unsigned char> bytes(tile_pixel_bytes(result, grid, tiles));
  unsigned char* out = bytes.data();
  each_row(buffers(result), grid, tiles, [&](const unsigned char* row, size_t n) {
    std::memcpy(out, row, n);
    out += n;
  });
  return bytes;
}

void unpack_tile_pixels(RenderResult& result, const TileGrid& grid, std::span<const int> tiles,
                        std::span<const unsigned char> bytes) {
  const size_t expected = tile_pixel_bytes(result, grid, tiles);
  if (bytes.size() != expected)
    throw Error("tile pixels: " + std::to_string(bytes.size()) + " bytes for " + std::to_string(tiles.size()) +
                " tiles that hold " + std::to_string(expected));
  const unsigned char* in = bytes.data();
  each_row(buffers(result), grid, tiles, [&](unsigned char* row, size_t n) {
    std::memcpy(row, in, n);
    in += n;
  });
}

}  // namespace rayform
