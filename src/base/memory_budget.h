// The memory one job may hold at once (Limits::memory, `--limit memory=N`):
// a running count of bytes charged before they are allocated, by the
// textures decoded (bytes per texel by format, decoder buffers included), the
// meshes and BVHs prepared, and the output buffers. A charge that would pass
// the limit throws one line naming what and how much, so that several
// textures or meshes, each within its own limit, cannot together claim the
// machine. Each charge is held by a MemoryCharge (copies share it) that the
// owner of the memory keeps: dropping the last copy gives the bytes back, so a
// process that runs jobs one after another charges each only for its own.
//
// The default limit is a sixteenth of physical memory (limits.h), and it
// grows with the files a job reads: by input_expansion bytes for each byte
// read (credit_input), up to half of physical memory. A scene that a small
// file makes claim more is refused in a few milliseconds, while a large
// scene's own files make room for it (a 400 MB OBJ of 10M triangles, its
// BVH 1.7 GB). `--limit memory=N` sets a limit that does not grow.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace rayform {

class MemoryCharge {
 public:
  MemoryCharge() = default;
  uint64_t bytes() const;

 private:
  friend class MemoryBudget;
  struct Held;
  std::shared_ptr<Held> held_;
};

class MemoryBudget {
 public:
  explicit MemoryBudget(uint64_t limit);
  MemoryBudget(const MemoryBudget&) = delete;
  MemoryBudget& operator=(const MemoryBudget&) = delete;

  // Charges `bytes` for `what` ("the 16384x16384 texture 'wood.png'"), or
  // throws rayform::Error "WHAT needs 1.1 GB, more than the 0.9 GB left of
  // the memory limit of 1.5 GB (raise it with --limit memory=N)". Thread-safe.
  MemoryCharge charge(uint64_t bytes, const std::string& what);
  // The message charge would throw, or "" when `bytes` fit now.
  std::string problem(uint64_t bytes, const std::string& what) const;

  // The limit in force: the one set, plus input_expansion times the bytes
  // credited where it grows with input, up to half of physical memory.
  uint64_t limit() const;
  // A limit of `limit` bytes; with `grows_with_input`, as the default does.
  void set_limit(uint64_t limit, bool grows_with_input = false);
  // A file of `bytes` bytes was read (a scene, a mesh, a buffer, an image):
  // room for what it may become. Thread-safe; kept for the process's life.
  void credit_input(uint64_t bytes);
  uint64_t used() const;  // charged and not yet given back

 private:
  friend class MemoryCharge;
  struct State;
  std::shared_ptr<State> state_;  // outlives the budget while charges hold it
};

// Bytes of memory a job may hold for each byte of its input files, where
// the limit grows with input: the Scene, BVH and decoded textures of
// ordinary files need under 8 (an OBJ's 40 bytes of text a triangle become
// about 170 bytes once prepared; a photograph's PNG decodes to 2 to 8 times
// its size), while the bombs this limit stops expand by 1000 and more.
inline constexpr uint64_t input_expansion = 16;

// The budget of the job this process runs: its limit is Limits{}.memory
// until the command line sets it (set_limit).
MemoryBudget& job_memory();

// How a size's number is written from kB on.
enum class SizeDigits {
  significant3,  // three significant digits: "2.15 GB", "512 MB", "64.0 kB"
  one_decimal,   // one decimal: "2.1 GB", "512.0 MB", "64.0 kB"
};
// A size in bytes in decimal units (bytes, kB, MB, ... EB); below 1 kB whole bytes.
std::string memory_size_text(uint64_t bytes, SizeDigits digits = SizeDigits::significant3);

}  // namespace rayform
