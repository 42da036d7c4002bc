// work_counter.h: a counter in an MPI window on rank 0 (mpi_plugin_abi.h)
// when distributed, otherwise a local atomic.
#include "rayform/distributed/work_counter.h"

#include "rayform/distributed/mpi_plugin.h"
#include "rayform/distributed/ranks.h"

#include <atomic>

namespace rayform::distributed {

struct WorkCounter::Impl {
  std::atomic<long long> local{0};  // not distributed
  void* shared = nullptr;           // the plugin's counter
};

WorkCounter::WorkCounter() : impl_(std::make_unique<Impl>()) {
  if (ranks().distributed()) impl_->shared = mpi()->counter_create();
}

WorkCounter::~WorkCounter() {
  if (impl_->shared) mpi()->counter_destroy(impl_->shared);
}

long long WorkCounter::next() { return impl_->shared ? mpi()->counter_next(impl_->shared) : impl_->local++; }

}  // namespace rayform::distributed
