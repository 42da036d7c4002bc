// librayform_mpi.so: mpi_plugin_abi.h over MPI's C API. The program opens it
// (mpi_plugin.cpp) only when mpirun or another MPI launcher started it, so a
// rayform run on its own does not load libmpi and its libraries (about 2 ms
// of every start).
#include "rayform/distributed/mpi_plugin_abi.h"
#include "rayform/distributed/mpi_wait.h"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <utility>
#include <vector>

#include <dirent.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

namespace {

constexpr uint64_t piece_bytes = uint64_t(1) << 30;  // MPI counts are int

// MPI's launcher link: the PMIx client of OpenMPI 4 talks to mpirun over a
// loopback TCP socket without TCP_NODELAY. Its fences (MPI_Init's, and the one
// in MPI_Finalize) send a few small messages in a row, and Nagle holds the
// last one until mpirun's delayed ACK comes, 40 ms later (strace: the
// finalize fence's message reached mpirun 37-45 ms after it was written).
// Sets TCP_NODELAY on the TCP sockets the process holds once MPI is up: it
// changes only when small writes leave, never what is sent.
void send_small_writes_at_once() {
  DIR* fds = opendir("/proc/self/fd");
  if (!fds) return;
  const int listing = dirfd(fds);
  while (const dirent* e = readdir(fds)) {
    char* end = nullptr;
    const long fd = std::strtol(e->d_name, &end, 10);
    if (end == e->d_name || *end != '\0' || fd == listing) continue;
    int type = 0, domain = 0;
    socklen_t len = sizeof type;
    if (getsockopt(int(fd), SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_STREAM) continue;
    len = sizeof domain;
    if (getsockopt(int(fd), SOL_SOCKET, SO_DOMAIN, &domain, &len) != 0 || (domain != AF_INET && domain != AF_INET6))
      continue;
    const int on = 1;
    (void)setsockopt(int(fd), IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  }
  closedir(fds);
}

struct Counter {
  MPI_Win window = MPI_WIN_NULL;
  long long* value = nullptr;  // rank 0's counter
  std::mutex mutex;            // one MPI call at a time (MPI_THREAD_SERIALIZED)
};

// Collective: a counter at 0. One long long in a window on rank 0, which
// every rank holds a shared lock on (passive target) and advances with
// MPI_Fetch_and_op. On one node OpenMPI's shared-memory window (osc/sm) makes
// that an atomic add in shared memory.
Counter* make_counter() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  auto* c = new Counter;
  MPI_Win_allocate(rank == 0 ? MPI_Aint(sizeof(long long)) : 0, sizeof(long long), MPI_INFO_NULL, MPI_COMM_WORLD,
                   &c->value, &c->window);
  if (rank == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, c->window);
    *c->value = 0;
    MPI_Win_unlock(0, c->window);
  }
  rayform::distributed::barrier_without_spinning();  // the counter is 0 before anyone takes a number
  MPI_Win_lock_all(MPI_MODE_NOCHECK, c->window);
  return c;
}

// Collective.
void free_counter(Counter* c) {
  rayform::distributed::barrier_without_spinning();  // others may be busy with their last tile or render
  MPI_Win_unlock_all(c->window);
  MPI_Win_free(&c->window);  // collective: every rank has taken its last number
  delete c;
}

// The first counter, made by start: a spread frame's tiles and a batch's
// files each take one, and the first MPI_Win_allocate took 0.4 to 25 ms here (OpenMPI
// sets up its one-sided layer on the first window). Every rank takes it for
// the same counter, the first one made after start, so creation stays
// collective in effect; finish frees it if no one took it.
Counter* spare_counter = nullptr;

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int rayform_mpi_version(void) { return RAYFORM_MPI_PLUGIN_VERSION; }

__attribute__((visibility("default"))) int rayform_mpi_start(int* rank, int* size, char* error, int error_size) {
  // Tiles are handed out from the worker threads, one MPI call at a time.
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  send_small_writes_at_once();
  if (provided < MPI_THREAD_SERIALIZED) {
    std::snprintf(error, size_t(error_size),
                  "this MPI library cannot be called from more than one thread (MPI_THREAD_SERIALIZED): rayform "
                  "needs it");
    return 0;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  if (*size > 1) spare_counter = make_counter();
  return 1;
}

__attribute__((visibility("default"))) void rayform_mpi_finish(void) {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  if (spare_counter) free_counter(std::exchange(spare_counter, nullptr));
  rayform::distributed::barrier_without_spinning();  // MPI_Finalize waits for every rank, polling
  MPI_Finalize();
}

__attribute__((visibility("default"))) void rayform_mpi_abort(void) { MPI_Abort(MPI_COMM_WORLD, 1); }

__attribute__((visibility("default"))) void rayform_mpi_allgather(const void* mine, void* all, uint64_t bytes_each) {
  MPI_Request request;  // the others may still be loading
  MPI_Iallgather(mine, int(bytes_each), MPI_BYTE, all, int(bytes_each), MPI_BYTE, MPI_COMM_WORLD, &request);
  rayform::distributed::wait_without_spinning(&request);
}

__attribute__((visibility("default"))) long long rayform_mpi_sum(long long value) {
  long long sum = 0;
  MPI_Request request;  // the others may still be rendering
  MPI_Iallreduce(&value, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD, &request);
  rayform::distributed::wait_without_spinning(&request);
  return sum;
}

__attribute__((visibility("default"))) void rayform_mpi_allgather_parts(void* const* parts, const uint64_t* sizes) {
  // One broadcast from each rank (in pieces MPI's int counts can hold), all
  // started before any is waited for: a rank sends its part while it receives
  // the others', where broadcasts in turn would leave one side idle.
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  std::vector<MPI_Request> requests;
  for (int k = 0; k < ranks; ++k)
    for (uint64_t done = 0; done < sizes[k]; done += piece_bytes) {
      requests.emplace_back();
      MPI_Ibcast(static_cast<char*>(parts[k]) + done, int(std::min(piece_bytes, sizes[k] - done)), MPI_BYTE, k,
                 MPI_COMM_WORLD, &requests.back());
    }
  rayform::distributed::wait_without_spinning(requests.data(), int(requests.size()));
}

__attribute__((visibility("default"))) void rayform_mpi_send(const void* data, uint64_t bytes, int to, int tag) {
  for (uint64_t done = 0; done == 0 || done < bytes; done += piece_bytes) {
    MPI_Request request;  // the receiver may still be rendering
    MPI_Isend(static_cast<const char*>(data) + done, int(std::min(piece_bytes, bytes - done)), MPI_BYTE, to, tag,
              MPI_COMM_WORLD, &request);
    rayform::distributed::wait_without_spinning(&request);
  }
}

__attribute__((visibility("default"))) void rayform_mpi_receive(void* data, uint64_t bytes, int from, int tag) {
  for (uint64_t done = 0; done == 0 || done < bytes; done += piece_bytes) {
    MPI_Request request;  // the sender may still be rendering
    MPI_Irecv(static_cast<char*>(data) + done, int(std::min(piece_bytes, bytes - done)), MPI_BYTE, from, tag,
              MPI_COMM_WORLD, &request);
    rayform::distributed::wait_without_spinning(&request);
  }
}

__attribute__((visibility("default"))) void* rayform_mpi_counter_create(void) {
  if (spare_counter) return std::exchange(spare_counter, nullptr);
  return make_counter();
}

__attribute__((visibility("default"))) long long rayform_mpi_counter_next(void* counter) {
  auto* c = static_cast<Counter*>(counter);
  std::lock_guard lock(c->mutex);
  const long long one = 1;
  long long got = 0;
  MPI_Fetch_and_op(&one, &got, MPI_LONG_LONG, 0, 0, MPI_SUM, c->window);
  MPI_Win_flush(0, c->window);
  return got;
}

__attribute__((visibility("default"))) void rayform_mpi_counter_destroy(void* counter) {
  free_counter(static_cast<Counter*>(counter));
}

}  // extern "C"
