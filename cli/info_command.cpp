#include "commands.h"
#include "messages.h"
#include "rayform/distributed/ranks.h"
#include "read_flags.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/text_format.h"

#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace rayform::cli {
namespace {

const char* support_name(ExtensionUse::Support s) {
  return s == ExtensionUse::Support::read           ? "read"
         : s == ExtensionUse::Support::approximated ? "approximated"
                                                    : "ignored";
}

const char* format_name(SceneFormat f) {
  return f == SceneFormat::course_txt ? "course" : f == SceneFormat::obj ? "obj" : "gltf";
}

// A float as the shortest decimal that reads back as it (0.3, not 0.30000001192092896).
double json_number(float v) { return std::stod(format_float(v)); }

// What the text prints, for programs (README.md, "rayform info --json").
nlohmann::json info_json(const std::string& path, const LoadedScene& loaded, const SceneStats& s) {
  nlohmann::json j;
  j["scene"] = path;
  j["format"] = format_name(loaded.format);
  if (loaded.format == SceneFormat::course_txt) j["dialect"] = std::string(course_dialect_name(loaded.dialect));
  j["nodes"] = s.nodes;
  j["instances"] = s.instances;
  j["spheres"] = s.spheres;
  j["planes"] = s.planes;
  j["triangles"] = {{"standalone", s.triangles},
                    {"in_meshes", s.mesh_triangles},
                    {"meshes", s.meshes},
                    {"unique_in_meshes", s.unique_mesh_triangles}};
  j["materials"] = s.materials;
  j["textures"] = s.textures;
  j["lights"] = s.lights;
  j["cameras"] = s.cameras;
  if (s.bounds.empty()) j["bounds"] = nullptr;
  else
    j["bounds"] = {{"min", {json_number(s.bounds.lo.x), json_number(s.bounds.lo.y), json_number(s.bounds.lo.z)}},
                   {"max", {json_number(s.bounds.hi.x), json_number(s.bounds.hi.y), json_number(s.bounds.hi.z)}},
                   {"planes_excluded", s.planes > 0}};
  j["extensions"] = nlohmann::json::array();
  for (const ExtensionUse& e : loaded.extensions)
    j["extensions"].push_back({{"name", e.name}, {"support", support_name(e.support)}, {"detail", e.detail}});
  j["warnings"] = loaded.warnings;
  return j;
}

}  // namespace

void add_info_command(CLI::App& app) {
  struct Args {
    std::string scene, dialect;
    ReadFlags read;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* info = app.add_subcommand("info", "Print counts and bounds of a scene, and the glTF extensions it uses");
  info->add_option("scene", a->scene, "Scene file")->required();
  info->add_option("--dialect", a->dialect, "Course dialect: 2012, 2019 or a5 (default: detected)")
      ->check(CLI::IsMember({"2012", "2019", "a5"}));
  info->add_flag("--json", a->json, "Print the same as one JSON object on stdout, the warnings in it too");
  add_read_flags(*info, a->read);
  info->callback([a] {
    if (!distributed::ranks().root()) return;  // under mpirun, one report (rank 0's), not one per rank
    LoadOptions lo{dialect_from_string(a->dialect)};
    apply_read_flags(a->read, lo);
    LoadedScene loaded = load_scene(a->scene, lo);
    for (const std::string& w : loaded.warnings) warn(w);
    const SceneStats stats = scene_stats(loaded.scene, lo.limits.instances);
    if (a->json) {
      // Invalid UTF-8 in names (a path, a glTF extension) is replaced, not refused.
      std::cout << info_json(a->scene, loaded, stats).dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                << "\n";
      return;
    }
    std::cout << "scene:       " << a->scene << "\n";
    if (loaded.format == SceneFormat::course_txt)
      std::cout << "format:      course .txt, dialect " << course_dialect_name(loaded.dialect) << "\n";
    std::cout << format_scene_stats(stats);
    if (!loaded.extensions.empty()) {
      std::cout << "extensions:\n";
      for (const ExtensionUse& e : loaded.extensions)
        std::cout << "  " << e.name << ": " << support_name(e.support)
                  << (e.detail.empty() ? "" : " (" + e.detail + ")") << "\n";
    }
  });
}

}  // namespace rayform::cli
