// ranks.h over MPI (built when RAYFORM_MPI is on).
#include "ranks.h"

#include "mpi_wait.h"

#include <mpi.h>

#include <cstdlib>
#include <iostream>

namespace rayform::cli {
namespace {

Ranks the_ranks;

// Whether a launcher that gives MPI its ranks started this process: OpenMPI's
// mpirun, a PMIx launcher (srun --mpi=pmix), a PMI-1/2 one.
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

void finalize() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  barrier_without_spinning();  // MPI_Finalize waits for every rank, polling
  MPI_Finalize();
}

}  // namespace

bool built_with_mpi() { return true; }

Ranks start_ranks(int* argc, char*** argv) {
  if (!launched_by_mpirun()) return the_ranks;
  // Tiles are handed out from the worker threads, one MPI call at a time.
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  std::atexit(finalize);
  if (provided < MPI_THREAD_SERIALIZED)
    abort_ranks(
        "rayform: error: this MPI library cannot be called from more than one thread "
        "(MPI_THREAD_SERIALIZED): rayform needs it");
  MPI_Comm_rank(MPI_COMM_WORLD, &the_ranks.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &the_ranks.size);
  return the_ranks;
}

const Ranks& ranks() { return the_ranks; }

std::vector<bool> gather_flags(bool flag) {
  if (!the_ranks.distributed()) return {flag};
  const int mine = flag ? 1 : 0;
  std::vector<int> all(size_t(the_ranks.size));
  MPI_Request request;  // the others may still be loading
  MPI_Iallgather(&mine, 1, MPI_INT, all.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  wait_without_spinning(&request);
  return std::vector<bool>(all.begin(), all.end());
}

long long sum_over_ranks(long long value) {
  if (!the_ranks.distributed()) return value;
  long long sum = 0;
  MPI_Request request;  // the others may still be rendering
  MPI_Iallreduce(&value, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD, &request);
  wait_without_spinning(&request);
  return sum;
}

std::vector<std::string> gather_text(const std::string& text) {
  if (!the_ranks.distributed()) return {text};
  const int n = int(text.size());
  std::vector<int> sizes(the_ranks.root() ? size_t(the_ranks.size) : 0);
  MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(sizes.size());
  int total = 0;
  for (size_t r = 0; r < sizes.size(); ++r) {
    offsets[r] = total;
    total += sizes[r];
  }
  std::string all(size_t(total), '\0');
  MPI_Gatherv(text.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  for (size_t r = 0; r < sizes.size(); ++r) texts.push_back(all.substr(size_t(offsets[r]), size_t(sizes[r])));
  return texts;
}

void abort_ranks(const std::string& message) {
  std::cerr << message << std::endl;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

}  // namespace rayform::cli
