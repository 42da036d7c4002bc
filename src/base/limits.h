// How much a scene file may make rayform allocate: the limits every reader and
// `prepare` check before they allocate, so that a small hostile file cannot
// claim gigabytes or hours. One owner, one default each; the command line sets
// them with `--limit NAME=VALUE`. The defaults admit anything this kind of
// machine (tens of GB) can render: ~100 bytes per triangle once prepared.
#pragma once

#include <cstdint>
#include <string>

namespace rayform {

// The deepest JSON nesting that may be allowed: tinygltf's parser recurses
// once per level (20 000 levels overflow an 8 MB stack; AddressSanitizer's
// frames are larger still).
inline constexpr uint64_t max_json_depth = 1024;

// The default of Limits::memory: a sixteenth of the machine's physical
// memory (sysconf), at least 256 MiB; 1 GiB when unknown. It grows with the
// files a job reads, up to half of physical memory: memory_budget.h says why.
uint64_t default_memory_limit();
// The machine's physical memory in bytes (sysconf); 0 when unknown.
uint64_t physical_memory_bytes();

struct Limits {
  uint64_t triangles = uint64_t(1) << 27;       // in all meshes of a scene, each mesh counted once
  uint64_t vertices = uint64_t(1) << 27;        // in all meshes of a scene
  uint64_t unbacked_elements = 1 << 24;         // glTF accessor elements without a bufferView (zeros), every read
  uint64_t instances = uint64_t(1) << 26;       // shapes once the node hierarchy is flattened
  uint64_t texture_texels = uint64_t(1) << 28;  // width x height of one texture, read from its header; each
                                                // side at most the square root (16384)
  uint64_t json_depth = 512;                    // nesting of arrays and objects in a glTF's JSON
  uint64_t memory = default_memory_limit();     // bytes one job may hold at once (memory_budget.h)
};

// The names `--limit` accepts, in the order of the struct, separated by ", ".
std::string limit_names();

// Sets the limit `name` (one of limit_names()) to `value` (a positive integer,
// or with a k/M/G suffix for 10^3/10^6/10^9). Returns "" or what is wrong.
std::string set_limit(Limits& limits, const std::string& name, const std::string& value);

// "triangles: 2000000 is more than the limit of 1000000 (raise it with --limit
// triangles=N)"; callers put the file or scene in front.
std::string limit_exceeded(const char* name, uint64_t count, uint64_t limit);

}  // namespace rayform
