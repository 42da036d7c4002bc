#include "rayform/distributed/mpi_plugin.h"

#include "rayform/base/plugin_library.h"

#include <dlfcn.h>

namespace rayform::distributed {

const MpiPlugin* open_mpi_plugin(std::string* failure) {
  static MpiPlugin plugin;
  if (plugin.start) return &plugin;
  void* h = open_plugin("librayform_mpi.so", "RAYFORM_MPI_PLUGIN", failure);
  if (!h) return nullptr;
  auto version = reinterpret_cast<rayform_mpi_version_fn>(dlsym(h, "rayform_mpi_version"));
  if (!version || version() != RAYFORM_MPI_PLUGIN_VERSION) {
    *failure = "librayform_mpi.so is not the version this rayform was built with";
    return nullptr;
  }
  MpiPlugin p;
  p.start = reinterpret_cast<rayform_mpi_start_fn>(dlsym(h, "rayform_mpi_start"));
  p.finish = reinterpret_cast<rayform_mpi_finish_fn>(dlsym(h, "rayform_mpi_finish"));
  p.abort = reinterpret_cast<rayform_mpi_abort_fn>(dlsym(h, "rayform_mpi_abort"));
  p.allgather = reinterpret_cast<rayform_mpi_allgather_fn>(dlsym(h, "rayform_mpi_allgather"));
  p.sum = reinterpret_cast<rayform_mpi_sum_fn>(dlsym(h, "rayform_mpi_sum"));
  p.allgather_parts = reinterpret_cast<rayform_mpi_allgather_parts_fn>(dlsym(h, "rayform_mpi_allgather_parts"));
  p.send = reinterpret_cast<rayform_mpi_send_fn>(dlsym(h, "rayform_mpi_send"));
  p.receive = reinterpret_cast<rayform_mpi_receive_fn>(dlsym(h, "rayform_mpi_receive"));
  p.counter_create = reinterpret_cast<rayform_mpi_counter_create_fn>(dlsym(h, "rayform_mpi_counter_create"));
  p.counter_next = reinterpret_cast<rayform_mpi_counter_next_fn>(dlsym(h, "rayform_mpi_counter_next"));
  p.counter_destroy = reinterpret_cast<rayform_mpi_counter_destroy_fn>(dlsym(h, "rayform_mpi_counter_destroy"));
  if (!p.start || !p.finish || !p.abort || !p.allgather || !p.sum || !p.allgather_parts || !p.send || !p.receive ||
      !p.counter_create || !p.counter_next || !p.counter_destroy) {
    *failure = "librayform_mpi.so lacks some of the rayform_mpi_* functions";
    return nullptr;
  }
  plugin = p;
  return &plugin;
}

}  // namespace rayform::distributed
