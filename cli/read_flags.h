// The flags of every command that reads a scene: --limit NAME=VALUE
// (repeatable; scene/limits.h) and --confine (referenced_files.h).
#pragma once

#include "scene_io.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace rayform::cli {

struct ReadFlags {
  std::vector<std::string> limits;  // "NAME=VALUE"
  bool confine = false;
};

void add_read_flags(CLI::App& command, ReadFlags& flags);

// Sets options.limits and options.access; throws UsageError for a bad --limit.
void apply_read_flags(const ReadFlags& flags, LoadOptions& options);

}  // namespace rayform::cli
