// The C interface between the command-line program and librayform_mpi.so
// (mpi_plugin_module.cpp), the only code that calls MPI. Plain C types, so
// the plugin needs nothing of rayform. Every function but start, abort and
// counter_next is collective or point-to-point as its comment says; waits
// for other ranks do not spin a core (mpi_wait.h). Byte counts are 64-bit:
// the plugin splits transfers into pieces MPI's int counts can hold. MPI's
// thread level is MPI_THREAD_SERIALIZED: any thread may call, one at a time.
#pragma once

#include <cstdint>

extern "C" {
// Version of this interface; rayform_mpi_version() must return it.
#define RAYFORM_MPI_PLUGIN_VERSION 2
typedef int (*rayform_mpi_version_fn)(void);
// Collective: MPI_Init_thread(MPI_THREAD_SERIALIZED), and the window of the
// first counter (below), made now so that its cost falls where the caller
// waits for MPI anyway. 1 with *rank and *size set, or 0 with the reason in
// `error`. The thread that calls it is MPI's main thread: it must be the one
// that calls finish.
typedef int (*rayform_mpi_start_fn)(int* rank, int* size, char* error, int error_size);
// Collective, on the thread that called start, once no other MPI call is
// under way: waits for every rank without spinning, then MPI_Finalize.
typedef void (*rayform_mpi_finish_fn)(void);
// MPI_Abort of every rank with status 1.
typedef void (*rayform_mpi_abort_fn)(void);
// Collective: every rank's `bytes_each` bytes at `mine`, by rank, into `all`.
typedef void (*rayform_mpi_allgather_fn)(const void* mine, void* all, uint64_t bytes_each);
// Collective: the sum of every rank's value.
typedef long long (*rayform_mpi_sum_fn)(long long value);
// Collective: each rank k's `sizes[k]` bytes at its `parts[k]` into every
// rank's `parts[k]` (parts[rank] is sent, the others received), all the
// transfers under way at once. Every rank passes the same sizes.
typedef void (*rayform_mpi_allgather_parts_fn)(void* const* parts, const uint64_t* sizes);
// Point to point on tag `tag`: the receiver names the same byte count.
typedef void (*rayform_mpi_send_fn)(const void* data, uint64_t bytes, int to, int tag);
typedef void (*rayform_mpi_receive_fn)(void* data, uint64_t bytes, int from, int tag);
// A counter on rank 0 that every rank advances (work_counter.h). Create and
// destroy are collective; next is thread-safe and returns 0, 1, 2, ... over
// all ranks.
typedef void* (*rayform_mpi_counter_create_fn)(void);
typedef long long (*rayform_mpi_counter_next_fn)(void* counter);
typedef void (*rayform_mpi_counter_destroy_fn)(void* counter);
}
