// write_gltf_scene: one GltfWriter (gltf_writer_internal.h) per file, and its walk
// (write) in order: materials, the node tree, cameras, lights, the scene's
// extras; then the messages on what glTF could not hold as it was, and the
// files.
#include "rayform/importers/gltf/gltf_writer.h"

#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/importers/shape_tessellation.h"
#include "rayform/importers/text_format.h"

#include <algorithm>

namespace rayform {

namespace gltf_detail {

GltfWriter::GltfWriter(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
                       std::vector<std::string>* messages)
    : scene_(scene), options_(options), context_(scene, path, options.side_folder, messages) {
  extent_ = scene_extent(scene);
  if (!extent_.empty()) {
    extent_center_ = extent_.center();
    extent_radius_ = std::max(0.5f * glm::length(extent_.extent()), 1.f);
  }
}

SaveResult GltfWriter::write() {
  model_.asset.version = "2.0";
  model_.asset.generator = "rayform convert";
  find_data_textures();
  for (size_t i = 0; i < scene_.materials.size(); ++i) add_material(int(i));

  tinygltf::Scene gs;
  gs.name = scene_.nodes[size_t(scene_.root)].name;
  on_path_.assign(scene_.nodes.size(), 0);
  for (int n : root_nodes(mat4(1.f))) gs.nodes.push_back(n);
  for (size_t i = 0; i < scene_.cameras.size(); ++i) gs.nodes.push_back(add_camera(int(i)));
  for (size_t i = 0; i < scene_.lights.size(); ++i) gs.nodes.push_back(add_light(int(i)));
  gs.extras = scene_extras();
  model_.scenes.push_back(std::move(gs));
  model_.defaultScene = 0;
  report();
  return save();
}

void GltfWriter::report() {
  if (spheres_)
    context_.note(std::to_string(spheres_) + " sphere(s) tessellated (" + std::to_string(options_.sphere_segments) +
                  " segments, " +
                  std::to_string(tessellate_sphere(Sphere{}, options_.sphere_segments).triangle_count()) +
                  " triangles each)" +
                  (options_.shape_extras ? "; the exact sphere is kept in the primitive's extras"
                                         : "; no extras (--tessellate-only)"));
  if (planes_)
    context_.note(std::to_string(planes_) + " plane(s) written as square quads of half-size " +
                  format_float(plane_half_) + " around the scene" +
                  (options_.shape_extras ? "; the exact plane is kept in the primitive's extras" : ""));
  if (untextured_uses_)
    context_.note(std::to_string(untextured_uses_) +
                  " textured material(s) also used by shapes without uvs: those use an "
                  "untextured copy (glTF requires TEXCOORD_0 with a texture)");
  if (split_meshes_)
    context_.note(std::to_string(split_meshes_) +
                  " mesh(es) with several materials written as one primitive per material");
  if (sheared_)
    context_.note(
        std::to_string(sheared_) +
        " transform(s) with a shear, which one glTF node cannot hold, written as two nodes (scale x rotation, "
        "rotation)");
  if (zero_normals_)
    context_.note(std::to_string(zero_normals_) +
                  " zero-length vertex normal(s) written as (0, 0, 1) (glTF requires unit normals)");
  if (std::any_of(scene_.materials.begin(), scene_.materials.end(),
                  [](const Material& m) { return m.model == Material::Model::phong; }))
    context_.note(
        "Phong materials converted to metallic-roughness (docs/convert.md); the exact Phong values are kept in the "
        "material extras");
  context_.note_names("materials", clamped_, ": diffuse colour outside [0, 1] clamped in baseColorFactor");
  context_.note_names(
      "textures", raw_textures_,
      ": course textures (raw texels, texel centres on whole numbers) are kept as they are, the course's reading "
      "in "
      "the texture extras; other viewers read them as sRGB with the usual texel centres");
  context_.note_names("textures", converted_, " converted to PNG (glTF holds PNG and JPEG)");
  if (bump_maps_)
    context_.note(
        std::to_string(bump_maps_) +
        " bump map(s) kept as textures named in the material extras only (glTF has height maps only as normal maps)");
  if (refractive_)
    context_.note(std::to_string(refractive_) + " refraction index(es) kept in the material extras only");
  if (stretched_)
    context_.note(
        "camera: the course stretches its view to the image (no aspect correction); glTF cameras keep the aspect, "
        "which is the same picture for square images; the course camera is kept in the camera extras");
  if (raw_up_)
    context_.note("camera: the 2019 dialect's raw (not orthogonal) up vector is kept in the camera extras only");
  if (no_falloff_)
    context_.note(
        std::to_string(no_falloff_) +
        " point light(s) without falloff (course): glTF lights fall off with the distance squared; the intensity is "
        "set to match at the centre of the scene, the exact light in the light extras");
  const Background& b = scene_.background;
  if (b.color != Background{}.color || b.ambient != vec3(0.f) || b.cube_map[0] != invalid)
    context_.note("background colour, ambient light and cube map have no glTF equivalent: kept in the scene's extras");
}

}  // namespace gltf_detail

SaveResult write_gltf_scene(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
                            std::vector<std::string>* messages) {
  require_scene_root(scene, path);
  return gltf_detail::GltfWriter(scene, path, options, messages).write();
}

}  // namespace rayform
