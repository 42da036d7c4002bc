// rank_work_share.h over MPI (mpi_plugin_abi.h): the exchange gathers every
// rank's byte count, then every rank's bytes from it, the transfers at once. The
// plugin waits without spinning: a rank that finished its part early must not
// take a core from one still working on its own.
#include "rayform/distributed/rank_work_share.h"

#include "rayform/distributed/mpi_plugin.h"
#include "rayform/distributed/ranks.h"

#include <cstdint>

namespace rayform::distributed {
namespace {

std::vector<std::vector<std::byte>> allgather_bytes(std::vector<std::byte> mine) {
  const Ranks& r = ranks();
  const uint64_t my_size = mine.size();
  std::vector<uint64_t> sizes(size_t(r.size), 0);
  mpi()->allgather(&my_size, sizes.data(), sizeof my_size);
  // Every buffer first (each rank zeroes and faults in its own at once), then
  // every transfer at once.
  std::vector<std::vector<std::byte>> all(size_t(r.size));
  std::vector<void*> parts(size_t(r.size));
  all[size_t(r.rank)] = std::move(mine);
  for (int k = 0; k < r.size; ++k) {
    if (k != r.rank) all[size_t(k)].resize(sizes[size_t(k)]);
    parts[size_t(k)] = all[size_t(k)].data();
  }
  mpi()->allgather_parts(parts.data(), sizes.data());
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

}  // namespace rayform::distributed
