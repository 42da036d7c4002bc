// built_with_mpi() (ranks.h), the one part of the command line that
// RAYFORM_WITH_MPI changes, in a file of its own: each program compiles it
// (cli/CMakeLists.txt: rayform with RAYFORM_WITH_MPI when RAYFORM_MPI is on;
// tests/fuzz without, so the fuzz entries stay one process), while the render
// path is compiled once, into the library rayform_cli_parts.
#include "rayform/distributed/ranks.h"

namespace rayform::distributed {

bool built_with_mpi() {
#ifdef RAYFORM_WITH_MPI
  return true;
#else
  return false;
#endif
}

}  // namespace rayform::distributed
