// ranks.h over librayform_mpi.so (mpi_plugin.h), opened only when an MPI
// launcher started this process; otherwise rank 0 of 1 and every operation
// is local.
#include "rayform/distributed/ranks.h"

#include "rayform/distributed/mpi_launcher.h"
#include "rayform/distributed/mpi_plugin.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <thread>
#include <utility>

namespace rayform::distributed {
namespace {

Ranks the_ranks;
const MpiPlugin* plugin = nullptr;  // opened when an MPI launcher started this process

// MPI starts on a thread of its own, so that the program goes on meanwhile:
// MPI_Init takes 20 to 30 ms here, about half of it waiting for mpirun and
// the other ranks, and what comes first (the command line, opening the scene
// file, a large OBJ's scan) needs no MPI. That thread is MPI's main thread
// (the one that called MPI_Init): it calls MPI_Finalize too, at exit. Every
// other use of MPI (mpi()) waits until it is up. MPI_THREAD_SERIALIZED lets
// any thread call MPI once it is, one call at a time.
struct MpiThread {
  std::mutex mutex;
  std::condition_variable changed;
  bool up = false;      // start has returned
  bool ok = false;      // and MPI is usable
  bool finish = false;  // the program is exiting
  std::string failure;
  Ranks ranks;  // as MPI gives them
  std::thread thread;
};
MpiThread* mpi_thread = nullptr;  // never freed: it ends at exit
std::atomic<bool> mpi_up{false};

void run_mpi_thread(MpiThread* t) {
  Ranks r;
  char error[256] = {0};
  const bool ok = plugin->start(&r.rank, &r.size, error, int(sizeof error));
  {
    std::lock_guard lock(t->mutex);
    t->up = true;
    t->ok = ok;
    t->failure = error;
    t->ranks = r;
  }
  t->changed.notify_all();
  std::unique_lock lock(t->mutex);
  t->changed.wait(lock, [t] { return t->finish; });
  if (ok) plugin->finish();
}

// At exit (registered before the thread starts, so it runs after whatever
// the program registers later): MPI_Finalize on MPI's thread.
void finish_mpi() {
  {
    std::lock_guard lock(mpi_thread->mutex);
    mpi_thread->finish = true;
  }
  mpi_thread->changed.notify_all();
  mpi_thread->thread.join();
}

// This process's rank and the job's size as the launcher gives them, before
// MPI is up (OpenMPI's mpirun; Hydra and other PMI launchers); false when the
// environment does not say (a PMIx launcher such as srun gives the rank only).
bool ranks_from_environment(Ranks* r) {
  auto number = [](const char* name, int* value) {
    const char* text = std::getenv(name);
    if (!text) return false;
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < 0 || v > INT32_MAX) return false;
    *value = int(v);
    return true;
  };
  for (const auto& [rank, size] : {std::pair{"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"}, {"PMI_RANK", "PMI_SIZE"}})
    if (number(rank, &r->rank) && number(size, &r->size) && r->rank < r->size) return true;
  return false;
}

// The line a rank that cannot use MPI prints before it stops.
void say_mpi_unusable(const std::string& why) {
  std::cerr << "rayform: error: started by an MPI launcher, but MPI cannot be used: " + why + "\n";
}

// Waits until MPI is up; a rank where it could not start stops the job.
// `take_ranks`: the_ranks are MPI's (the environment did not give them);
// otherwise they must agree with MPI's.
void wait_for_mpi(bool take_ranks) {
  std::unique_lock lock(mpi_thread->mutex);
  mpi_thread->changed.wait(lock, [] { return mpi_thread->up; });
  const bool ok = mpi_thread->ok;
  const std::string failure = mpi_thread->failure;
  const Ranks mpi_ranks = mpi_thread->ranks;
  lock.unlock();
  if (!ok) {
    say_mpi_unusable(failure);
    plugin->abort();  // MPI is initialised (MPI_Init itself ends the job when it fails)
    std::exit(1);
  }
  if (take_ranks) the_ranks = mpi_ranks;
  if (mpi_ranks.rank != the_ranks.rank || mpi_ranks.size != the_ranks.size) {
    std::cerr << "rayform: error: MPI says rank " + std::to_string(mpi_ranks.rank) + " of " +
                     std::to_string(mpi_ranks.size) + ", the launcher's environment rank " +
                     std::to_string(the_ranks.rank) + " of " + std::to_string(the_ranks.size) + "\n";
    plugin->abort();
    std::exit(1);
  }
  mpi_up.store(true, std::memory_order_release);
}

}  // namespace

const MpiPlugin* mpi() {
  if (!mpi_thread) return nullptr;
  if (!mpi_up.load(std::memory_order_acquire)) wait_for_mpi(/*take_ranks*/ false);
  return plugin;
}

Ranks start_ranks() {
  if (!built_with_mpi() || !launched_by_mpi_launcher()) return the_ranks;
  std::string failure;
  plugin = open_mpi_plugin(&failure);
  if (!plugin) {
    say_mpi_unusable(failure);
    std::exit(1);
  }
  mpi_thread = new MpiThread;
  std::atexit(finish_mpi);
  mpi_thread->thread = std::thread(run_mpi_thread, mpi_thread);
  if (!ranks_from_environment(&the_ranks)) wait_for_mpi(/*take_ranks*/ true);  // only MPI can tell
  return the_ranks;
}

const Ranks& ranks() { return the_ranks; }

std::vector<bool> gather_flags(bool flag) {
  const std::vector<long long> all = gather_numbers(flag ? 1 : 0);
  return std::vector<bool>(all.begin(), all.end());
}

std::vector<long long> gather_numbers(long long value) {
  if (!the_ranks.distributed()) return {value};
  std::vector<long long> all(size_t(the_ranks.size));
  mpi()->allgather(&value, all.data(), sizeof value);
  return all;
}

long long sum_over_ranks(long long value) {
  if (!the_ranks.distributed()) return value;
  return mpi()->sum(value);
}

std::vector<std::string> gather_text(const std::string& text) {
  if (!the_ranks.distributed()) return {text};
  constexpr int tag_text = 4;  // tile_gather.cpp uses 1 to 3
  const uint64_t mine = text.size();
  std::vector<uint64_t> sizes(size_t(the_ranks.size));
  mpi()->allgather(&mine, sizes.data(), sizeof mine);
  if (!the_ranks.root()) {
    mpi()->send(text.data(), mine, 0, tag_text);
    return {};
  }
  std::vector<std::string> texts(sizes.size());
  texts[0] = text;
  for (size_t r = 1; r < sizes.size(); ++r) {
    texts[r].resize(sizes[r]);
    mpi()->receive(texts[r].data(), sizes[r], int(r), tag_text);
  }
  return texts;
}

void abort_ranks(const std::string& message) {
  std::cerr << message << std::endl;
  if (const MpiPlugin* m = mpi()) m->abort();
  std::exit(1);
}

}  // namespace rayform::distributed
