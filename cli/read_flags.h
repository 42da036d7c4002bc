// The flags of every command that reads a scene: --limit NAME=VALUE
// (repeatable; scene/limits.h), --confine (referenced_files.h) and
// -q/--quiet (messages.h).
#pragma once

#include "rayform/importers/scene_io.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace rayform::cli {

struct ReadFlags {
  std::vector<std::string> limits;  // "NAME=VALUE"
  bool confine = false;
  bool quiet = false;
};

void add_read_flags(CLI::App& command, ReadFlags& flags);

// Sets options.limits and options.access, and the quiet state (messages.h);
// throws UsageError for a bad --limit.
void apply_read_flags(const ReadFlags& flags, LoadOptions& options);

}  // namespace rayform::cli
