// The subcommands of the modern interface, one file each. Every function adds
// its subcommand to the app with a callback that runs it.
#pragma once

#include "rayform/importers/scene_io.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace rayform::cli {

void add_render_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_convert_command(CLI::App& app);

// "2012"/"2019"/"a5" -> dialect; "" -> detect.
std::optional<CourseDialect> dialect_from_string(const std::string& d);

}  // namespace rayform::cli
