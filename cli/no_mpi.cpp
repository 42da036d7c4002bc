// ranks.h, work_counter.h, tile_gather.h and rank_work_share.h for a rayform built without MPI
// (RAYFORM_MPI off): always rank 0 of 1, every operation local.
#include "rank_work_share.h"
#include "ranks.h"
#include "tile_gather.h"
#include "work_counter.h"

#include <atomic>
#include <cstdlib>
#include <iostream>

namespace rayform::cli {

bool built_with_mpi() { return false; }
Ranks start_ranks(int*, char***) { return ranks(); }
const Ranks& ranks() {
  static const Ranks one;
  return one;
}
std::vector<bool> gather_flags(bool flag) { return {flag}; }
long long sum_over_ranks(long long value) { return value; }
std::vector<std::string> gather_text(const std::string& text) { return {text}; }
void abort_ranks(const std::string& message) {
  std::cerr << message << std::endl;
  std::exit(1);
}

struct WorkCounter::Impl {
  std::atomic<long long> value{0};
};
WorkCounter::WorkCounter() : impl_(std::make_unique<Impl>()) {}
WorkCounter::~WorkCounter() = default;
long long WorkCounter::next() { return impl_->value++; }

void gather_tiles(RenderResult&, const TileGrid&, const std::vector<int>&) {}

WorkShare rank_work_share() { return {}; }

}  // namespace rayform::cli
