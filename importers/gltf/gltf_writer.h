// A Scene as glTF 2.0 (.gltf + .bin + images beside it, or everything embedded,
// or .glb), through tinygltf's writer (TinyGLTF::WriteGltfSceneToFile).
//
// What the file gets (docs/convert.md has the details and the formulas):
// - the node tree: one glTF node per group or transform node (its `local` as
//   `matrix`; a matrix that is not translation x rotation x scale, e.g. a
//   shear, is split into two nodes that are), the shape children with
//   identity matrices gathered as the primitives of one mesh on their parent's
//   node; meshes reused wherever the same shapes and materials recur;
// - triangle meshes with POSITION (with min/max), NORMAL, TEXCOORD_0
//   (v flipped back: v_gltf = 1 - v_scene), COLOR_0; a mesh whose faces use
//   several materials as one primitive per material;
// - spheres as UV spheres (GltfWriteOptions::sphere_segments), planes as large
//   quads around the scene (scene_writer.h: plane_quad), standalone triangles
//   as one-triangle meshes, each keeping its analytic form in the primitive's
//   extras;
// - Phong materials as metallic-roughness (phong_to_pbr below), the Phong
//   values in the material's extras; textures as PNG or JPEG images with
//   samplers and KHR_texture_transform;
// - cameras and KHR_lights_punctual lights on nodes of their own, with what
//   glTF cannot say (the course's stretched aspect, a raw up vector, a point
//   light without falloff) in their extras; the background in the scene's extras.
//
// Every rayform extra lives under the key "rayform" of an object's extras, so
// that other tools keep them; apply_gltf_rayform_extras (below) reads them back.
#pragma once

#include "scene/scene.h"
#include "scene_writer.h"

#include <functional>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace rayform {

struct GltfWriteOptions {
  bool binary = false;  // .glb: one file, buffers and images in its binary chunk
  bool embed = false;   // .gltf: buffers and images as data URIs (no .bin, no image files)
  int sphere_segments = 64;
  bool shape_extras = true;  // analytic spheres/planes/triangles in primitive extras
};

// Writes `scene` to `path`. Messages (what glTF cannot hold, what was
// approximated) are appended to `messages`. Throws rayform::Error naming the file.
SaveResult write_gltf_scene(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
                            std::vector<std::string>* messages);

// Phong (diffuse K, specular Ks, shininess n) as glTF metallic-roughness, the
// inverse of the reader's conversion (gltf_reader.cpp: pbr_to_phong), which is
//   Ks = F0 (1 - roughness)^2, F0 = mix(0.04, base, metallic),
//   n = (2 / roughness^4 - 2) / 4 clamped to [1, 1024]:
//   base      = K (clamped to [0, 1]);
//   roughness = (2 n + 1)^(-1/4) (n = 0 or Ks = 0: 1, a matte surface);
//   metallic  = (mean(F0) - 0.04) / (mean(base) - 0.04) clamped to [0, 1],
//               F0 = Ks / (1 - roughness)^2 (0 when base is no brighter than 0.04).
// The reader gives back K exactly and (Ks, n) exactly wherever they lie in the
// reader's range (Ks = mix(0.04, K, m) (1 - r)^2 for some m in [0, 1], 1 <= n <= 1024).
struct PbrValues {
  vec4 base{1.f};
  float metallic = 0.f, roughness = 1.f;
};
PbrValues phong_to_pbr(vec3 diffuse, vec3 specular, float shininess);

// ---- reading the extras back (called by gltf_reader.cpp) ---------------------------

// How the reader mapped the file's objects to the Scene it built.
struct GltfSceneMapping {
  int scene = 0;                                  // the glTF scene that was read
  std::vector<std::vector<int>> mesh_primitives;  // per glTF mesh, per primitive: Scene mesh;
                                                  // empty when some primitive was skipped
  std::vector<int> materials;                     // per glTF material: Scene material
  std::function<int(int)> texture;                // glTF texture index -> Scene texture (or invalid)
};

// Applies the "rayform" extras of a file this writer wrote: analytic shapes
// replace their tessellations, Phong values replace the converted ones,
// cameras, lights, textures and the background get back what glTF could not
// say. Each extra is checked against the standard data it annotates (a sphere's
// vertices must still lie on it, a material's PBR values must be the ones
// written, a camera must still sit where its node puts it); an extra that no
// longer matches, e.g. after the file was edited elsewhere, is ignored with a
// warning. Files without rayform extras are left as read.
void apply_gltf_rayform_extras(const tinygltf::Model& model, const GltfSceneMapping& mapping, Scene& scene,
                               std::vector<std::string>* warnings);

}  // namespace rayform
