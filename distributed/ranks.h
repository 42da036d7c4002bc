// This process's place in an MPI job, and the few operations across ranks
// that the distributed drivers (distributed_frame.h, render_batch.h) need.
// MPI is started only when the process was launched by mpirun (or srun with
// PMIx), through the MPI plugin (mpi_plugin.h): a rayform started on its own,
// or built without MPI (RAYFORM_MPI off), is rank 0 of 1, loads no MPI
// library, and every operation here is local. The interface has no MPI type:
// only the plugin includes <mpi.h>.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace rayform::distributed {

struct Ranks {
  int rank = 0, size = 1;
  bool root() const { return rank == 0; }
  bool distributed() const { return size > 1; }
};

// Whether this rayform was built with MPI (built_with_mpi.cpp: compiled into
// each program, false in the fuzz entries).
bool built_with_mpi();

// Starts MPI when launched by mpirun (once, first thing in main), on a thread
// of its own: the ranks come from the launcher's environment at once, and the
// first operation below waits for MPI. MPI is finalised at exit. Returns ranks().
Ranks start_ranks();
const Ranks& ranks();

// Collective (every rank calls them, in the same order):
// Each rank's flag, by rank, on every rank.
std::vector<bool> gather_flags(bool flag);
// Each rank's number, by rank, on every rank.
std::vector<long long> gather_numbers(long long value);
// The sum of every rank's `value`, on every rank.
long long sum_over_ranks(long long value);
// Every rank's text, by rank, at rank 0 (elsewhere empty).
std::vector<std::string> gather_text(const std::string& text);

// A failure another rank reports: main exits with status 1, printing nothing
// (so that N ranks failing alike print one message, rank 0's).
struct ReportedElsewhere : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Prints `message` on stderr and ends every rank of the job with exit
// status 1 (MPI_Abort; exit(1) when not distributed).
[[noreturn]] void abort_ranks(const std::string& message);

}  // namespace rayform::distributed
