// tile_gather.h over MPI (built when RAYFORM_MPI is on). Each rank r > 0
// sends its tiles in pieces of about 16 MiB of pixels: a header (tile count,
// byte count), the tile indices, the packed pixels; a header with no tiles
// ends its stream. Rank 0 takes the ranks in turn and unpacks each piece as
// it arrives. Small pieces reuse one buffer on either side: no copy of a
// whole share, whose first touch of fresh pages cost more than the transfer
// (an 8K frame with every AOV in float is 1.46 GB).
#include "tile_gather.h"

#include "mpi_wait.h"
#include "ranks.h"

#include "rayform/render/tile_pixels.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <span>

namespace rayform::cli {
namespace {

constexpr int tag_header = 1, tag_tiles = 2, tag_pixels = 3;
constexpr size_t piece_bytes = size_t(16) << 20;

}  // namespace

void gather_tiles(RenderResult& result, const TileGrid& grid, const std::vector<int>& mine) {
  const Ranks& r = ranks();
  if (!r.distributed()) return;
  std::vector<unsigned char> pixels;
  if (!r.root()) {
    for (size_t first = 0;;) {
      // The next tiles up to about piece_bytes (at least one tile).
      size_t end = first, bytes = 0;
      while (end < mine.size() && (end == first || bytes < piece_bytes))
        bytes += tile_pixel_bytes(result, grid, std::span<const int>(&mine[end++], 1));
      const std::span<const int> tiles(mine.data() + first, end - first);
      const uint64_t header[2] = {tiles.size(), bytes};
      if (!tiles.empty()) pixels = pack_tile_pixels(result, grid, tiles);
      // Rank 0 may still be rendering: wait for it without spinning.
      MPI_Request requests[3];
      MPI_Isend(header, 2, MPI_UINT64_T, 0, tag_header, MPI_COMM_WORLD, &requests[0]);
      if (tiles.empty()) return wait_without_spinning(requests, 1);
      MPI_Isend(tiles.data(), int(tiles.size()), MPI_INT, 0, tag_tiles, MPI_COMM_WORLD, &requests[1]);
      MPI_Isend(pixels.data(), int(pixels.size()), MPI_BYTE, 0, tag_pixels, MPI_COMM_WORLD, &requests[2]);
      wait_without_spinning(requests, 3);
      first = end;
    }
  }
  std::vector<int> tiles;
  for (int from = 1; from < r.size; ++from) {
    for (;;) {
      uint64_t header[2] = {0, 0};
      MPI_Request request;  // rank `from` may still be rendering; the tiles and pixels follow at once
      MPI_Irecv(header, 2, MPI_UINT64_T, from, tag_header, MPI_COMM_WORLD, &request);
      wait_without_spinning(&request);
      if (header[0] == 0) break;
      tiles.resize(header[0]);
      pixels.resize(header[1]);
      MPI_Recv(tiles.data(), int(tiles.size()), MPI_INT, from, tag_tiles, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Recv(pixels.data(), int(pixels.size()), MPI_BYTE, from, tag_pixels, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      unpack_tile_pixels(result, grid, tiles, pixels);  // checks that the sizes agree
    }
  }
}

}  // namespace rayform::cli
