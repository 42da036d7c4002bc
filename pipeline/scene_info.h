// What `rayform info --json` prints of a scene, for programs: one JSON object
// (counts, bounds, glTF extensions, warnings; README.md, "rayform info
// --json"). The command line and the Python module's Scene.info() print
// this one text.
#pragma once

#include "rayform/importers/scene_io.h"
#include "rayform/scene/scene_stats.h"

#include <string>

namespace rayform {

// The name `info` gives an extension's support: "read", "approximated" or "ignored".
const char* extension_support_name(ExtensionUse::Support support);

// The JSON text (indented by 2, invalid UTF-8 in names replaced) of the
// scene read from `path`, with `stats` = scene_stats(loaded.scene, ...).
std::string scene_info_json(const std::string& path, const LoadedScene& loaded, const SceneStats& stats);

}  // namespace rayform
