// rank_work_share.h over MPI: the exchange gathers every rank's byte count
// (MPI_Iallgather), then broadcasts each rank's bytes from it in turn
// (MPI_Ibcast, in pieces of at most 1 GiB: MPI counts are int). Waits without
// spinning: a rank that finished its part early must not take a core from
// one still working on its own.
#include "rank_work_share.h"

#include "mpi_wait.h"
#include "ranks.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>

namespace rayform::cli {
namespace {

constexpr uint64_t piece_bytes = uint64_t(1) << 30;

std::vector<std::vector<std::byte>> allgather_bytes(std::vector<std::byte> mine) {
  const Ranks& r = ranks();
  std::vector<uint64_t> sizes(size_t(r.size), 0);
  const uint64_t my_size = mine.size();
  MPI_Request request;
  MPI_Iallgather(&my_size, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD, &request);
  wait_without_spinning(&request);
  std::vector<std::vector<std::byte>> all(size_t(r.size));
  all[size_t(r.rank)] = std::move(mine);
  for (int k = 0; k < r.size; ++k) {
    std::vector<std::byte>& bytes = all[size_t(k)];
    if (k != r.rank) bytes.resize(sizes[size_t(k)]);
    for (uint64_t done = 0; done < sizes[size_t(k)]; done += piece_bytes) {
      const int count = int(std::min(piece_bytes, sizes[size_t(k)] - done));
      MPI_Ibcast(bytes.data() + done, count, MPI_BYTE, k, MPI_COMM_WORLD, &request);
      wait_without_spinning(&request);
    }
  }
  return all;
}

}  // namespace

WorkShare rank_work_share() {
  const Ranks& r = ranks();
  WorkShare share;
  share.part = r.rank;
  share.parts = r.size;
  if (r.distributed()) share.exchange = allgather_bytes;
  return share;
}

}  // namespace rayform::cli
