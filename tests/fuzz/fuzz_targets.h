// The fuzz targets' entry functions, shared by the libFuzzer binaries
// (fuzz_main.cpp, one binary per target) and the regression replay runner
// (replay_main.cpp, an ordinary test binary). Every entry writes the fuzz
// bytes into a private temporary folder, calls the public reader of its
// format and reports a clean error or success; anything else (a crash, an
// exception that is not rayform's, a sanitizer report) escapes on purpose.
// Input formats: docs/fuzzing.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rayform::fuzz {

struct FuzzLimits {
  size_t max_input_bytes = size_t(1) << 20;  // larger inputs are skipped (not read)
};

// The texture limit the entries decode with: 2^22 texels (2048 x 2048), below
// rayform's default of 2^28, so that an image the default rightly admits
// (up to 1 GiB decoded) does not pass the fuzzer's and the replay's memory
// bounds. What is tested is that every header is checked, not the default.
inline constexpr uint64_t fuzz_texture_texels = uint64_t(1) << 22;
// Likewise for the counts a glTF may declare without bytes behind them
// (accessors without a bufferView, in all: 48 MB of VEC3 floats) and the
// instances it makes by count: low enough that the fuzzer reaches each limit
// within its memory bound, so that the checks, not the defaults, are tested.
inline constexpr uint64_t fuzz_unbacked_elements = uint64_t(1) << 22;
inline constexpr uint64_t fuzz_instances = uint64_t(1) << 20;

struct FuzzOutcome {
  bool skipped = false;  // over FuzzLimits::max_input_bytes
  bool ok = false;       // false: a clean error (rayform::Error, or a usage error for the CLI)
  std::string message;   // the error's message
  // Files used from outside the scene's folder (confinement checks of the
  // replay; fuzzing ignores them): texture paths, the bait material or mesh.
  std::vector<std::string> outside;
};

using FuzzEntry = FuzzOutcome (*)(const uint8_t* data, size_t size, const FuzzLimits& limits);

struct FuzzTarget {
  const char* name;
  FuzzEntry entry;
  const char* input;  // what the bytes are
};

std::span<const FuzzTarget> fuzz_targets();
const FuzzTarget* find_fuzz_target(std::string_view name);

// Separates the files of one input (targets that read several files).
inline constexpr std::string_view part_separator = "\n%%\n";
std::vector<std::string_view> split_parts(std::string_view input, size_t max_parts);

}  // namespace rayform::fuzz
