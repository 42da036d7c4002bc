// read_gltf_scene: one GltfReader (gltf_reader_internal.h) per file, and
// its walk (read) in order; the asset version and extensions the file
// requires checked, those it uses reported, rayform's own extras applied last.
#include "rayform/importers/gltf/gltf_reader.h"

#include "rayform/importers/gltf/gltf_extras.h"
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <algorithm>
#include <filesystem>

namespace rayform {

namespace gltf_detail {
namespace fs = std::filesystem;

namespace {

// Extensions a file may require: those whose data this reader uses (fully or
// approximately), and the ones it knows and ignores, whose files still draw
// (the material layers iridescence, anisotropy, dispersion and
// diffuse_transmission, drawn without that layer; variants, each primitive
// with its default material), reported as ignored. Any other in extensionsRequired is an error;
// any other in extensionsUsed is ignored and said so.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> s = {"KHR_texture_transform",
                                          "KHR_lights_punctual",
                                          "KHR_materials_emissive_strength",
                                          "KHR_draco_mesh_compression",
                                          "EXT_meshopt_compression",
                                          "KHR_mesh_quantization",
                                          "EXT_texture_webp",
                                          "KHR_texture_basisu",
                                          "EXT_mesh_gpu_instancing",
                                          "KHR_materials_ior",
                                          "KHR_materials_specular",
                                          "KHR_materials_unlit",
                                          "KHR_materials_transmission",
                                          "KHR_materials_clearcoat",
                                          "KHR_materials_pbrSpecularGlossiness",
                                          "KHR_materials_sheen",
                                          "KHR_materials_volume",
                                          "KHR_materials_iridescence",
                                          "KHR_materials_anisotropy",
                                          "KHR_materials_dispersion",
                                          "KHR_materials_variants",
                                          "KHR_materials_diffuse_transmission"};
  return s;
}

}  // namespace

Scene GltfReader::read(std::vector<ExtensionUse>* extensions) {
  load();
  check_asset();
  scene_.source_path = path_;
  extras_primitives_.resize(model_.meshes.size());
  materials_.assign(model_.materials.size(), invalid);
  textures_.assign(model_.textures.size(), {-2, -2});
  nodes_.assign(model_.nodes.size(), invalid);
  on_path_.assign(model_.nodes.size(), 0);

  // Every material in file order, so that Scene material i is glTF material i
  // (the default material, if some primitive needs it, comes after them).
  for (size_t i = 0; i < model_.materials.size(); ++i) material(int(i), idx("materials", long(i)));

  Node root;
  root.kind = Node::Kind::group;
  root.name = fs::path(path_).stem().string();
  const std::vector<std::pair<int, std::string>> roots = root_nodes();
  check_node_trees(roots);
  for (const auto& [node, ref] : roots) root.children.push_back(convert_node(node, ref, mat4(1.f)));
  // Skinned meshes, posed in world space (see convert_node).
  root.children.insert(root.children.end(), world_space_shapes_.begin(), world_space_shapes_.end());
  scene_.nodes.push_back(std::move(root));
  scene_.root = int(scene_.nodes.size()) - 1;

  if (!model_.animations.empty()) warn("animations are ignored: the scene is read in its static pose");
  apply_rayform_extras();
  report_extensions();
  if (extensions) *extensions = std::move(extensions_);
  return std::move(scene_);
}

void GltfReader::check_asset() {
  const std::string& v = model_.asset.version;
  if (v.rfind("2.", 0) != 0) fail("asset.version is '" + v + "': only glTF 2.0 is supported");
  if (!model_.asset.minVersion.empty() && model_.asset.minVersion != "2.0")
    fail("asset.minVersion is '" + model_.asset.minVersion + "': only glTF 2.0 is supported");
  for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
    const std::string& ext = model_.extensionsRequired[i];
    if (!supported_extensions().count(ext))
      fail(idx("extensionsRequired", long(i)) + ": extension '" + ext +
           "' is required by the file but not supported (rayform info lists what a file uses; docs/assets.md "
           "what is supported)");
  }
}

// The extensions the file names, with how they were used: those recorded
// while reading keep their entry; the rest of the supported ones were read
// as they are; unsupported ones are ignored. One warning lists what was
// approximated or ignored.
void GltfReader::report_extensions() {
  using Support = ExtensionUse::Support;
  if (std::count(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_materials_variants"))
    use_extension("KHR_materials_variants", Support::ignored,
                  "each primitive is drawn with its default material; the variants' materials are not used");
  for (const std::string& ext : model_.extensionsUsed) {
    bool seen =
        std::any_of(extensions_.begin(), extensions_.end(), [&](const ExtensionUse& u) { return u.name == ext; });
    if (seen) continue;
    if (supported_extensions().count(ext)) extensions_.push_back({ext, Support::read, ""});
    else extensions_.push_back({ext, Support::ignored, "not supported"});
  }
  std::string approximated, ignored;
  for (const ExtensionUse& u : extensions_) {
    std::string& list = u.support == Support::approximated ? approximated : ignored;
    if (u.support == Support::read) continue;
    list += (list.empty() ? "" : "; ") + u.name + (u.detail.empty() ? "" : " (" + u.detail + ")");
  }
  if (!approximated.empty()) warn("extensions approximated: " + approximated);
  if (!ignored.empty()) warn("extensions ignored: " + ignored);
}

void GltfReader::use_extension(const std::string& name, ExtensionUse::Support support, const std::string& detail) {
  for (ExtensionUse& u : extensions_)
    if (u.name == name) return;
  extensions_.push_back({name, support, detail});
}

// rayform's own extras, written by the writer (gltf_writer.h): what glTF cannot say (analytic spheres and planes, Phong
// values, the course camera, ...) travels in "rayform" extras; apply_gltf_rayform_extras (gltf_extras.h) checks each
// against the file's data and restores it.
void GltfReader::apply_rayform_extras() {
  GltfSceneMapping map;
  map.scene = options_.scene >= 0 ? options_.scene : std::max(model_.defaultScene, 0);
  map.mesh_primitives = extras_primitives_;
  map.materials = materials_;
  map.texture = [this](int ti) { return texture_for_extras(ti); };
  std::vector<std::string> extras_warnings;
  apply_gltf_rayform_extras(model_, map, scene_, &extras_warnings);
  for (const std::string& w : extras_warnings) warn(w);
}

}  // namespace gltf_detail

Scene read_gltf_scene(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings,
                      std::vector<ExtensionUse>* extensions) {
  return gltf_detail::GltfReader(path, options, warnings).read(extensions);
}

}  // namespace rayform
