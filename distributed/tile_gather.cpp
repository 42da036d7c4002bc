// tile_gather.h over MPI (mpi_plugin_abi.h). Each rank r > 0 sends its tiles
// in pieces of about 16 MiB of pixels: a header (tile count, byte count), the
// tile indices, the packed pixels; a header with no tiles ends its stream.
// Rank 0 takes the ranks in turn and unpacks each piece as it arrives. Small
// pieces reuse one buffer on either side: no copy of a whole share, whose
// first touch of fresh pages cost more than the transfer (an 8K frame with
// every AOV in float is 1.46 GB).
#include "rayform/distributed/tile_gather.h"

#include "rayform/distributed/mpi_plugin.h"
#include "rayform/distributed/ranks.h"

#include "rayform/render/tile_pixels.h"

#include <cstdint>
#include <span>

namespace rayform::distributed {
namespace {

constexpr int tag_header = 1, tag_tiles = 2, tag_pixels = 3;
constexpr size_t piece_bytes = size_t(16) << 20;

}  // namespace

void gather_tiles(RenderResult& result, const TileGrid& grid, const std::vector<int>& mine) {
  const Ranks& r = ranks();
  if (!r.distributed()) return;
  const MpiPlugin& m = *mpi();
  std::vector<unsigned char> pixels;
  if (!r.root()) {
    for (size_t first = 0;;) {
      // The next tiles up to about piece_bytes (at least one tile).
      size_t end = first, bytes = 0;
      while (end < mine.size() && (end == first || bytes < piece_bytes))
        bytes += tile_pixel_bytes(result, grid, std::span<const int>(&mine[end++], 1));
      const std::span<const int> tiles(mine.data() + first, end - first);
      const uint64_t header[2] = {tiles.size(), bytes};
      m.send(header, sizeof header, 0, tag_header);  // rank 0 may still be rendering
      if (tiles.empty()) return;
      pixels = pack_tile_pixels(result, grid, tiles);
      m.send(tiles.data(), tiles.size_bytes(), 0, tag_tiles);
      m.send(pixels.data(), pixels.size(), 0, tag_pixels);
      first = end;
    }
  }
  std::vector<int> tiles;
  for (int from = 1; from < r.size; ++from) {
    for (;;) {
      uint64_t header[2] = {0, 0};
      m.receive(header, sizeof header, from, tag_header);  // rank `from` may still be rendering
      if (header[0] == 0) break;
      tiles.resize(header[0]);
      pixels.resize(header[1]);
      m.receive(tiles.data(), tiles.size() * sizeof(int), from, tag_tiles);
      m.receive(pixels.data(), pixels.size(), from, tag_pixels);
      unpack_tile_pixels(result, grid, tiles, pixels);  // checks that the sizes agree
    }
  }
}

}  // namespace rayform::distributed
