// The glTF writer, one per file written (write_gltf_scene), shared by the
// writer's parts; internal to importers/gltf/, never installed. Its members
// are defined one concept per file:
//   gltf_writer.cpp               the walk (write) in order, and the messages on what was approximated
//   gltf_write_values.cpp         JSON values: floats by their shortest text, rayform extras
//   gltf_write_geometry.cpp       buffers, accessors, shapes as meshes and primitives
//   gltf_write_nodes.cpp          the node tree, matrices that one glTF node cannot hold split in two
//   gltf_write_materials.cpp      materials, textures, images, samplers
//   gltf_write_cameras_lights.cpp cameras, KHR_lights_punctual lights, the background
//   gltf_write_output.cpp         the files: tinygltf's write, each file checked and synced, then committed
#pragma once

#include "rayform/geometry/bounds.h"
#include "rayform/importers/gltf/gltf_writer.h"
#include "rayform/importers/writer_context.h"
#include "rayform/scene/scene.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace rayform::gltf_detail {

using Value = tinygltf::Value;

// ---- gltf_write_values.cpp ------------------------------------------------------

// The float as the double of its shortest decimal text (0.9f -> 0.9), so that
// the JSON reads well and still gives back the same float.
double nice(float f);

Value num(float f);
Value vec_value(vec3 v);

std::vector<double> nice_vector(std::initializer_list<float> fs);

// extras = { "rayform": obj }
Value rayform_extras(Value::Object obj);

// Bits of the uv sets a glTF material's textures use.
inline constexpr int uv_set_0 = 1, uv_set_1 = 2;

// ---- the writer -----------------------------------------------------------------

// One primitive to write: a shape with its material (and, for planes, the
// object-to-world matrix that places the quad).
struct PrimitiveRef {
  ShapeKind kind;
  int shape;
  int material;
  mat4 world{1.f};
  bool operator<(const PrimitiveRef& o) const {
    return std::tie(kind, shape, material) < std::tie(o.kind, o.shape, o.material);
  }
};

class GltfWriter {
 public:
  GltfWriter(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
             std::vector<std::string>* messages);

  SaveResult write();

 private:
  // ---- gltf_writer.cpp ----------------------------------------------------------
  void report();

  // ---- gltf_write_geometry.cpp --------------------------------------------------
  struct Geometry {
    int position = -1, normal = -1, uv = -1, uv1 = -1, tangent = -1, color = -1, indices = -1;
    size_t triangles = 0;
  };
  int add_view(const void* data, size_t bytes, int target);
  int add_accessor(int view, int component, size_t count, int type, std::vector<double> min = {},
                   std::vector<double> max = {});
  int add_vec3s(const std::vector<vec3>& v, bool bounds);
  Geometry mesh_geometry(const Mesh& m, int only_material);
  tinygltf::Primitive primitive(const Geometry& g, int material);
  int gltf_material(int m) const;
  std::vector<tinygltf::Primitive> shape_primitives(const PrimitiveRef& r);
  int add_mesh(const std::vector<PrimitiveRef>& refs, const std::string& name);

  // ---- gltf_write_nodes.cpp -----------------------------------------------------
  int add_node(tinygltf::Node n);
  int set_matrix(tinygltf::Node& n, const mat4& m);
  std::vector<int> root_nodes(const mat4& world);
  int write_node(int index, const mat4& parent_world);

  // ---- gltf_write_materials.cpp -------------------------------------------------
  int add_sampler(const Texture& t);
  int add_texture(int ti);
  void find_data_textures();
  tinygltf::Material make_material(int mi, bool textured);
  tinygltf::Material make_pbr_material(int mi, bool textured);
  Value texture_transform(const UvTransform& t);
  Value::Object texture_object(const TextureSlot& slot, bool textured, int* uv_sets);
  void add_material(int mi);
  int untextured(int gi);
  void use_extension(const std::string& e);

  // ---- gltf_write_cameras_lights.cpp --------------------------------------------
  std::string unique_name(const std::string& wanted, std::set<std::string>& used);
  int add_camera(int ci);
  int add_light(int li);
  Value scene_extras();

  // ---- gltf_write_output.cpp ----------------------------------------------------
  void check_written(const std::string& file, uint64_t bytes, bool json) const;
  // The URI of the side file `file` (OutputFiles::side_reference, percent-encoded).
  std::string side_uri(const std::string& file) const;
  SaveResult save();

  const Scene& scene_;
  GltfWriteOptions options_;
  WriterContext context_;  // the output's path and names, its files, the messages
  tinygltf::Model model_;
  std::vector<uint8_t> buffer_;
  Bounds3 extent_;
  vec3 extent_center_{0.f};
  float extent_radius_ = 1.f;
  std::vector<uint8_t> on_path_;
  std::map<std::vector<PrimitiveRef>, int> meshes_;
  std::map<int, Geometry> sphere_geometry_;
  std::map<std::pair<int, int>, Geometry> mesh_geometry_;
  std::map<std::string, Geometry> stored_;  // by content
  std::map<int, int> untextured_;           // glTF material -> its copy without texture
  // Per glTF material, in order (make_material pushes it): the uv sets its
  // textures use (uv_set_0 | uv_set_1).
  std::vector<int> uv_sets_needed_;
  // Scene textures that only data slots of metallic-roughness materials use
  // (metallic-roughness, normal, occlusion, ...): glTF reads those linear.
  std::set<int> data_textures_;
  int untextured_uses_ = 0;
  std::map<int, int> textures_;
  std::map<std::tuple<int, int, int>, int> samplers_;
  std::set<std::string> used_files_, camera_names_, light_names_;
  std::set<std::string> clamped_, raw_textures_, converted_;
  size_t zero_normals_ = 0;
  int spheres_ = 0, planes_ = 0, split_meshes_ = 0, sheared_ = 0, bump_maps_ = 0, refractive_ = 0;
  int stretched_ = 0, raw_up_ = 0, no_falloff_ = 0;
  float plane_half_ = 0.f;
};

}  // namespace rayform::gltf_detail
