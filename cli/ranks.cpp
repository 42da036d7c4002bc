// ranks.h over librayform_mpi.so (mpi_plugin.h), opened only when an MPI
// launcher started this process; otherwise rank 0 of 1 and every operation
// is local.
#include "ranks.h"

#include "mpi_launcher.h"
#include "mpi_plugin.h"

#include <cstdint>
#include <cstdlib>
#include <iostream>

namespace rayform::cli {
namespace {

Ranks the_ranks;
const MpiPlugin* started = nullptr;

}  // namespace

const MpiPlugin* mpi() { return started; }

Ranks start_ranks(int* argc, char*** argv) {
  if (!built_with_mpi() || !launched_by_mpi_launcher()) return the_ranks;
  std::string failure;
  const MpiPlugin* plugin = open_mpi_plugin(&failure);
  if (!plugin) abort_ranks("rayform: error: started by mpirun, but MPI cannot be used: " + failure);
  char error[256] = {0};
  if (!plugin->start(argc, argv, &the_ranks.rank, &the_ranks.size, error, int(sizeof error))) {
    started = plugin;  // MPI is initialised: abort_ranks ends every rank
    abort_ranks(std::string("rayform: error: ") + error);
  }
  started = plugin;
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
  started->allgather(&value, all.data(), sizeof value);
  return all;
}

long long sum_over_ranks(long long value) {
  if (!the_ranks.distributed()) return value;
  return started->sum(value);
}

std::vector<std::string> gather_text(const std::string& text) {
  if (!the_ranks.distributed()) return {text};
  constexpr int tag_text = 4;  // tile_gather.cpp uses 1 to 3
  const uint64_t mine = text.size();
  std::vector<uint64_t> sizes(size_t(the_ranks.size));
  started->allgather(&mine, sizes.data(), sizeof mine);
  if (!the_ranks.root()) {
    started->send(text.data(), mine, 0, tag_text);
    return {};
  }
  std::vector<std::string> texts(sizes.size());
  texts[0] = text;
  for (size_t r = 1; r < sizes.size(); ++r) {
    texts[r].resize(sizes[r]);
    started->receive(texts[r].data(), sizes[r], int(r), tag_text);
  }
  return texts;
}

void abort_ranks(const std::string& message) {
  std::cerr << message << std::endl;
  if (started) started->abort();
  std::exit(1);
}

}  // namespace rayform::cli
