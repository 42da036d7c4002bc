// librayform_mpi.so (mpi_plugin_abi.h) as the program sees it: opened by
// start_ranks (ranks.h) when an MPI launcher started this process, so that a
// rayform run on its own never loads MPI.
#pragma once

#include "rayform/distributed/mpi_plugin_abi.h"

#include <string>

namespace rayform::distributed {

struct MpiPlugin {
  rayform_mpi_start_fn start = nullptr;
  rayform_mpi_finish_fn finish = nullptr;
  rayform_mpi_abort_fn abort = nullptr;
  rayform_mpi_allgather_fn allgather = nullptr;
  rayform_mpi_sum_fn sum = nullptr;
  rayform_mpi_allgather_parts_fn allgather_parts = nullptr;
  rayform_mpi_send_fn send = nullptr;
  rayform_mpi_receive_fn receive = nullptr;
  rayform_mpi_counter_create_fn counter_create = nullptr;
  rayform_mpi_counter_next_fn counter_next = nullptr;
  rayform_mpi_counter_destroy_fn counter_destroy = nullptr;
};

// Opens the plugin (base/plugin_library.h; $RAYFORM_MPI_PLUGIN overrides
// where) and checks its version: nullptr with the reason in *failure.
const MpiPlugin* open_mpi_plugin(std::string* failure);

// The plugin, once MPI is up (start_ranks starts it on a thread of its own:
// the first call waits for it); nullptr in a process no MPI launcher started.
const MpiPlugin* mpi();

}  // namespace rayform::distributed
