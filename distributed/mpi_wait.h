// Waiting for another rank without spinning a core (for the mpi_*.cpp files
// only). OpenMPI's blocking calls poll in a loop: a rank that has finished
// its share and waits for a slower one would take a core from it whenever
// ranks share cores (more ranks than cores, or a machine shared with other
// work). Where a wait can be long (others still loading or rendering), the
// call is started non-blocking and tested with short sleeps between.
#pragma once

#include <mpi.h>

#include <chrono>
#include <thread>

namespace rayform::distributed {

// MPI_Waitall without polling: tests every 50 us for the first 5 ms, then every 0.5 ms.
inline void wait_without_spinning(MPI_Request* requests, int count = 1) {
  for (int n = 0;; ++n) {
    int done = 0;
    MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(n < 100 ? 50 : 500));
  }
}

// MPI_Barrier on MPI_COMM_WORLD, waiting as above.
inline void barrier_without_spinning() {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait_without_spinning(&request);
}

}  // namespace rayform::distributed
