// tile_gather.h over MPI (built when RAYFORM_MPI is on).
#include "tile_gather.h"

#include "ranks.h"

#include "rayform/render/tile_pixels.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>

namespace rayform::cli {
namespace {

constexpr int tag_sizes = 1, tag_tiles = 2, tag_pixels = 3;
constexpr size_t piece = size_t(1) << 30;  // MPI counts are int: at most 1 GiB a message

void send_bytes(const void* data, size_t n, int tag) {
  const char* p = static_cast<const char*>(data);
  for (size_t done = 0; done < n; done += piece)
    MPI_Send(p + done, int(std::min(piece, n - done)), MPI_BYTE, 0, tag, MPI_COMM_WORLD);
}

void receive_bytes(void* data, size_t n, int from, int tag) {
  char* p = static_cast<char*>(data);
  for (size_t done = 0; done < n; done += piece)
    MPI_Recv(p + done, int(std::min(piece, n - done)), MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

}  // namespace

void gather_tiles(RenderResult& result, const TileGrid& grid, const std::vector<int>& mine) {
  const Ranks& r = ranks();
  if (!r.distributed()) return;
  if (!r.root()) {
    const std::vector<unsigned char> pixels = pack_tile_pixels(result, grid, mine);
    const uint64_t sizes[2] = {mine.size(), pixels.size()};
    MPI_Send(sizes, 2, MPI_UINT64_T, 0, tag_sizes, MPI_COMM_WORLD);
    send_bytes(mine.data(), mine.size() * sizeof(int), tag_tiles);
    send_bytes(pixels.data(), pixels.size(), tag_pixels);
    return;
  }
  for (int from = 1; from < r.size; ++from) {
    uint64_t sizes[2] = {0, 0};
    MPI_Recv(sizes, 2, MPI_UINT64_T, from, tag_sizes, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::vector<int> tiles(sizes[0]);
    std::vector<unsigned char> pixels(sizes[1]);
    receive_bytes(tiles.data(), tiles.size() * sizeof(int), from, tag_tiles);
    receive_bytes(pixels.data(), pixels.size(), from, tag_pixels);
    unpack_tile_pixels(result, grid, tiles, pixels);  // checks that the sizes agree
  }
}

}  // namespace rayform::cli
