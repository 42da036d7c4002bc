// The flags of every command that reads a scene: --limit NAME=VALUE
// (repeatable; base/limits.h), --confine (referenced_files.h) and
// -q/--quiet (messages.h), which may also come before the subcommand
// (`rayform -q render ...`).
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
  // The program's -q/--quiet (add_quiet_before_command), when it has one.
  const CLI::Option* quiet_before_command = nullptr;
};

// Adds -q/--quiet to the program itself, for before the subcommand; call it
// before adding the subcommands.
void add_quiet_before_command(CLI::App& app);

void add_read_flags(CLI::App& command, ReadFlags& flags);

// Sets options.limits and options.access, and the quiet state (messages.h);
// throws UsageError for a bad --limit.
void apply_read_flags(const ReadFlags& flags, LoadOptions& options);

// Whether -q/--quiet was given, before or after the subcommand.
bool quiet_requested(const ReadFlags& flags);

}  // namespace rayform::cli
