// rayform's own extras in glTF files: what glTF cannot say (analytic spheres
// and planes, Phong values, the course camera, the background, ...) travels
// under the key "rayform" of an object's extras, written by the writer
// (gltf_writer.h). The reader calls apply_gltf_rayform_extras after building
// its Scene.
#pragma once

#include "rayform/scene/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace rayform {

// How the reader mapped the file's objects to the Scene it built.
struct GltfSceneMapping {
  int scene = 0;                                  // the glTF scene that was read
  std::vector<std::vector<int>> mesh_primitives;  // per glTF mesh, per primitive: Scene mesh;
                                                  // empty when some primitive was skipped
  std::vector<int> materials;                     // per glTF material: Scene material
  std::function<int(int)> texture;                // glTF texture index -> Scene texture (or invalid)
};

// Applies the "rayform" extras of a file rayform wrote: analytic shapes
// replace their tessellations, Phong materials (a "phong" extra) replace the
// metallic-roughness ones read,
// cameras, lights, textures and the background get back what glTF could not
// say. Each extra is checked against the standard data it annotates (a sphere's
// vertices must still lie on it, a material's PBR values must be the ones
// written, a camera must still sit where its node puts it); an extra that no
// longer matches, e.g. after the file was edited elsewhere, is ignored with a
// warning. Files without rayform extras are left as read.
void apply_gltf_rayform_extras(const tinygltf::Model& model, const GltfSceneMapping& mapping, Scene& scene,
                               std::vector<std::string>* warnings);

}  // namespace rayform
