// Whether a launcher that gives MPI its ranks started this process: OpenMPI's
// mpirun, a PMIx launcher (srun --mpi=pmix), a PMI-1/2 one. Only then does
// rayform open its MPI plugin (ranks.h); the progress line also looks at it
// (progress.h).
#pragma once

#include <cstdlib>

namespace rayform::distributed {

inline bool launched_by_mpi_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace rayform::distributed
