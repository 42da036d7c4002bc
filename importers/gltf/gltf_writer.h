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
//   quads around the scene (shape_tessellation.h: plane_quad), standalone triangles
//   as one-triangle meshes, each keeping its analytic form in the primitive's
//   extras;
// - Phong materials as metallic-roughness (gltf_material.h: phong_to_pbr), the Phong
//   values in the material's extras; textures as PNG or JPEG images with
//   samplers and KHR_texture_transform;
// - cameras and KHR_lights_punctual lights on nodes of their own, with what
//   glTF cannot say (the course's stretched aspect, a raw up vector, a point
//   light without falloff) in their extras; the background in the scene's extras.
//
// Every rayform extra lives under the key "rayform" of an object's extras, so
// that other tools keep them; gltf_extras.h reads them back.
#pragma once

#include "rayform/scene/scene.h"
#include "rayform/importers/scene_writer.h"

#include <string>
#include <vector>

namespace rayform {

struct GltfWriteOptions {
  bool binary = false;  // .glb: one file, buffers and images in its binary chunk
  bool embed = false;   // .gltf: buffers and images as data URIs (no .bin, no image files)
  int sphere_segments = 64;
  bool shape_extras = true;  // analytic spheres/planes/triangles in primitive extras
  std::string side_folder;   // side files there (SaveOptions::side_folder)
};

// Writes `scene` to `path`. Messages (what glTF cannot hold, what was
// approximated) are appended to `messages`. Throws rayform::Error naming the file.
SaveResult write_gltf_scene(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
                            std::vector<std::string>* messages);

}  // namespace rayform
