// A counter shared by every rank of an MPI job: each next() returns a number
// no other call on any rank returns, 0, 1, 2, ... in the order the calls
// reach it. It hands out work dynamically: a rank (or thread) that finishes
// early takes more. Under MPI it is one integer in an RMA window on rank 0,
// advanced with MPI_Fetch_and_op (mpi_plugin_module.cpp); otherwise a local atomic.
#pragma once

#include <memory>

namespace rayform::distributed {

class WorkCounter {
 public:
  // Collective: every rank constructs and destroys it, in the same order
  // as any other collective operation (ranks.h).
  WorkCounter();
  ~WorkCounter();
  WorkCounter(const WorkCounter&) = delete;
  WorkCounter& operator=(const WorkCounter&) = delete;

  // Thread-safe (calls from one rank's threads are serialised).
  long long next();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rayform::distributed
