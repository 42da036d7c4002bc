// The glTF reader, one per file read (read_gltf_scene), shared by the
// reader's parts; internal to importers/gltf/, never installed. Its members
// are defined one concept per file:
//   gltf_reader.cpp               the walk (read): asset version, extensions, rayform extras
//   gltf_read_file.cpp            the file through tinygltf, its failures explained
//   gltf_read_nodes.cpp           scene roots, the node graph's checks, node transforms, instancing
//   gltf_read_cameras_lights.cpp  cameras and KHR_lights_punctual lights
//   gltf_read_materials.cpp       materials, textures, samplers
//   gltf_read_meshes.cpp          meshes and primitives: Draco, morph targets, skins, triangles
#pragma once

#include "rayform/importers/gltf/gltf_accessors.h"
#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/importers/gltf/gltf_messages.h"
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/base/error.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace rayform::gltf_detail {

inline std::string idx(const char* array, long i) { return gltf_path(array, i); }

struct Primitive {
  int mesh = invalid;      // Scene mesh
  int material = invalid;  // Scene material
};

class GltfReader {
 public:
  GltfReader(const std::string& path, const GltfReadOptions& options, std::vector<std::string>* warnings)
      : path_(path),
        options_(options),
        warnings_(warnings),
        accessors_(model_, path, options.limits.unbacked_elements) {}

  Scene read(std::vector<ExtensionUse>* extensions);

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + what); }

  void warn(const std::string& w) {
    std::string full = path_ + ": " + w;
    if (warnings_ && seen_warnings_.insert(full).second) warnings_->push_back(full);
  }

  // ---- gltf_reader.cpp ----------------------------------------------------------
  void check_asset();
  void report_extensions();
  void use_extension(const std::string& name, ExtensionUse::Support support = ExtensionUse::Support::read,
                     const std::string& detail = "");
  void apply_rayform_extras();

  // ---- gltf_read_file.cpp -------------------------------------------------------
  void load();
  [[noreturn]] void diagnose_load_failure(const std::vector<unsigned char>& bytes, const GltfContainer& container,
                                          bool glb, const std::string& err);

  // ---- gltf_read_nodes.cpp ------------------------------------------------------
  std::vector<std::pair<int, std::string>> root_nodes();
  void check_no_cycle(const std::vector<std::pair<int, std::string>>& roots);
  void check_node_trees(const std::vector<std::pair<int, std::string>>& roots);
  mat4 node_matrix(const tinygltf::Node& n, const std::string& where);
  int add_node(Node n);
  int convert_node(int i, const std::string& ref, const mat4& parent_world, int depth = 2);
  std::vector<mat4> instance_matrices(const tinygltf::Value& e, const std::string& ew);
  mat4 node_world(int i);

  // ---- gltf_read_cameras_lights.cpp ---------------------------------------------
  void place_camera(int c, const std::string& where, const mat4& world);
  void place_light(int li, const std::string& where, const mat4& world);

  // ---- gltf_read_materials.cpp --------------------------------------------------
  TextureSlot texture_slot(const tinygltf::TextureInfo& info, bool srgb, const std::string& where);
  tinygltf::TextureInfo texture_info(const tinygltf::Value& v, const std::string& where);
  void read_texture_slots(const tinygltf::Material& gm, const std::string& mw, PbrMaterial& pbr);
  int texture(int ti, bool srgb, const std::string& where);
  int texture_for_extras(int ti);
  int texture_source(const tinygltf::Texture& t, const std::string& tw);
  Texture::Wrap wrap(int mode, const std::string& where);
  int material(int gi, const std::string& where);

  // ---- gltf_read_meshes.cpp -----------------------------------------------------
  struct DracoPrimitive;
  std::unique_ptr<DracoPrimitive> decode_draco_primitive(const tinygltf::Primitive& prim, const std::string& where);
  GltfAccessors::Floats attribute(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& name,
                                  const std::string& where, std::initializer_list<int> types, uint32_t formats);
  std::vector<mat4> skin_joint_matrices(int skinned_node);
  const std::vector<int>& mesh_shapes(int mi, const std::vector<float>& weights, int skinned_node);
  void count_mesh_copy(int mi);
  Primitive convert_primitive(const tinygltf::Primitive& prim, const std::string& where, const std::string& name,
                              const std::vector<float>& weights, const std::vector<mat4>* joints);
  void read_tangents(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& where,
                     Mesh& mesh);
  void apply_morph_targets(const tinygltf::Primitive& prim, const std::string& where, const std::vector<float>& weights,
                           Mesh& mesh);
  void apply_skin(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& where,
                  const std::vector<mat4>& joints, Mesh& mesh);
  std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, int mode, const std::string& where);

  std::string path_;
  GltfReadOptions options_;
  std::vector<std::string>* warnings_;
  std::set<std::string> seen_warnings_;
  tinygltf::Model model_;
  GltfAccessors accessors_;  // reads model_'s accessors
  Scene scene_;
  // Shape nodes per (glTF mesh, skinned node or invalid, morph weights).
  using MeshKey = std::tuple<int, int, std::vector<float>>;
  std::map<MeshKey, std::vector<int>> mesh_shapes_;
  std::vector<std::vector<int>> extras_primitives_;  // per glTF mesh: its first conversion's Scene meshes
  std::vector<int> world_space_shapes_;              // shape nodes of skinned meshes (posed in world space)
  std::vector<int> parents_;                         // per glTF node: its first parent (node_world)
  std::set<int> ktx2_images_;                        // images that are KTX2 (not decoded)
  std::vector<ExtensionUse> extensions_;
  std::vector<int> materials_;  // per glTF material: Scene material
  // Per glTF texture, its Scene textures: [0] read as linear data, [1] as
  // sRGB-encoded colour (a texture used both ways becomes two); -2: not yet
  // converted.
  std::vector<std::array<int, 2>> textures_;
  std::vector<int> nodes_;  // per glTF node: Scene node
  // Built so far, checked against options_.limits before each copy is built:
  // EXT_mesh_gpu_instancing instances, and the vertices and triangles of
  // every Scene mesh (a glTF mesh is copied per morph weights and skin).
  uint64_t instances_ = 0, vertices_ = 0, triangles_ = 0;
  std::vector<uint8_t> on_path_;
  int default_material_ = invalid;
};

}  // namespace rayform::gltf_detail
