// work_counter.h over MPI (built when RAYFORM_MPI is on): one long long in a
// window on rank 0, which every rank holds a shared lock on (passive target)
// and advances with MPI_Fetch_and_op. On one node OpenMPI's shared-memory
// window (osc/sm) makes that an atomic add in shared memory.
#include "work_counter.h"

#include "mpi_wait.h"
#include "ranks.h"

#include <mpi.h>

#include <atomic>
#include <mutex>

namespace rayform::cli {

struct WorkCounter::Impl {
  std::atomic<long long> local{0};  // not distributed
  MPI_Win window = MPI_WIN_NULL;
  long long* value = nullptr;  // rank 0's counter
  std::mutex mutex;            // one MPI call at a time (MPI_THREAD_SERIALIZED)
};

WorkCounter::WorkCounter() : impl_(std::make_unique<Impl>()) {
  const Ranks& r = ranks();
  if (!r.distributed()) return;
  MPI_Win_allocate(r.root() ? MPI_Aint(sizeof(long long)) : 0, sizeof(long long), MPI_INFO_NULL, MPI_COMM_WORLD,
                   &impl_->value, &impl_->window);
  if (r.root()) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, impl_->window);
    *impl_->value = 0;
    MPI_Win_unlock(0, impl_->window);
  }
  barrier_without_spinning();  // the counter is 0 before anyone takes a number
  MPI_Win_lock_all(MPI_MODE_NOCHECK, impl_->window);
}

WorkCounter::~WorkCounter() {
  if (impl_->window == MPI_WIN_NULL) return;
  barrier_without_spinning();  // others may be busy with their last tile or render
  MPI_Win_unlock_all(impl_->window);
  MPI_Win_free(&impl_->window);  // collective: every rank has taken its last number
}

long long WorkCounter::next() {
  if (impl_->window == MPI_WIN_NULL) return impl_->local++;
  std::lock_guard lock(impl_->mutex);
  const long long one = 1;
  long long got = 0;
  MPI_Fetch_and_op(&one, &got, MPI_LONG_LONG, 0, 0, MPI_SUM, impl_->window);
  MPI_Win_flush(0, impl_->window);
  return got;
}

}  // namespace rayform::cli
