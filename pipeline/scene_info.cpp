#include "rayform/pipeline/scene_info.h"

#include "rayform/importers/course_txt/course_dialect.h"
#include "rayform/importers/text_format.h"

#include <nlohmann/json.hpp>

namespace rayform {
namespace {

const char* format_name(SceneFormat f) {
  return f == SceneFormat::course_txt ? "course" : f == SceneFormat::obj ? "obj" : "gltf";
}

// A float as the shortest decimal that reads back as it (0.3, not 0.30000001192092896).
double json_number(float v) { return std::stod(format_float(v)); }

}  // namespace

const char* extension_support_name(ExtensionUse::Support s) {
  return s == ExtensionUse::Support::read           ? "read"
         : s == ExtensionUse::Support::approximated ? "approximated"
                                                    : "ignored";
}

std::string scene_info_json(const std::string& path, const LoadedScene& loaded, const SceneStats& s) {
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
    j["extensions"].push_back({{"name", e.name}, {"support", extension_support_name(e.support)}, {"detail", e.detail}});
  j["warnings"] = loaded.warnings;
  // Invalid UTF-8 in names (a path, a glTF extension) is replaced, not refused.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace rayform
