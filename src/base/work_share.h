// A job's work shared among cooperating processes (the MPI ranks of the
// command-line program), for the stages each of them would otherwise repeat
// whole before a frame spread over them can start: parsing a large OBJ text,
// building a large mesh's BVH. Each process does the items of its part and an
// exchange gives every process the results of every part, so that all of them
// end with the same data a process alone makes. How the bytes travel is the
// caller's business: src/ and importers/ know nothing of MPI.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace rayform {

struct WorkShare {
  int part = 0;   // this process's part, 0 <= part < parts
  int parts = 1;  // how many processes share the work; 1: none
  // Collective: every part calls it the same number of times, in the same
  // order, with the bytes of its own results; returns the bytes of every
  // part in part order (result[part] is `mine`). Throws what the transport
  // throws (the job cannot go on).
  std::function<std::vector<std::vector<std::byte>>(std::vector<std::byte> mine)> exchange;

  bool shared() const { return parts > 1 && exchange != nullptr; }
};

}  // namespace rayform
