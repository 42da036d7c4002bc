// glTF 2.0 (.gltf with external or data-URI resources, .glb) as a Scene,
// through tinygltf (a thin adapter; every index and byte range is checked here,
// not trusted).
//
// What the Scene gets:
// - the node tree of one scene (the default one) as transform nodes (matrix
//   or T*R*S), under a root group named after the file; one shape node per
//   mesh primitive; a glTF mesh used by several nodes is shared (instanced);
// - primitives in TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN (points and lines
//   are skipped with a warning), indexed by u8/u16/u32 or not at all;
//   byteStride, sparse accessors and normalised integer uvs/colours read;
//   no NORMAL: Mesh::normals stays empty, so the renderer shades with face
//   normals (the flat normals the specification asks for);
// - TEXCOORD_n (the one the base colour texture uses) with v flipped to the
//   renderer's convention (v = 1 is the top row: v_scene = 1 - v_gltf);
//   COLOR_0 as vertex colours;
// - materials: see the comment on the metallic/roughness conversion in
//   gltf_reader.cpp; base colour textures from tinygltf's decoded RGBA8
//   pixels (sRGB, modulating, standard lookup, sampler wrap and filter);
//   KHR_texture_transform; alphaMode MASK; doubleSided; emissive;
// - cameras and KHR_lights_punctual lights placed by their nodes' world
//   transforms.
// Errors: rayform::Error "file: element: what", e.g.
// "box.gltf: meshes[2].primitives[0].indices: index 40 is out of range (the primitive has 24 vertices)".
#pragma once

#include "scene/scene.h"

#include <string>
#include <vector>

namespace rayform {

struct GltfReadOptions {
  int scene = -1;  // index into the file's scenes; -1: its default scene (or scene 0)
};

// Reads a .gltf or .glb file (the content decides, not the extension).
// Warnings, if wanted, are appended to `warnings`.
Scene read_gltf_scene(const std::string& path, const GltfReadOptions& options = {},
                      std::vector<std::string>* warnings = nullptr);

// KHR_texture_transform (uv' = T(offset) R(rotation) S(scale) uv in glTF's uv
// space, v pointing down the image) as the Material::uv_transform that gives
// the same texel for the flipped uvs the Scene stores (v_scene = 1 - v_gltf).
// With F(u, v) = (u, 1 - v) the stored transform is F o M o F: the scale is
// kept, the rotation changes sign and the offset becomes
// (o.x + sin(r) s.y, 1 - o.y - cos(r) s.y).
UvTransform gltf_uv_transform_to_scene(vec2 offset, float rotation, vec2 scale);

}  // namespace rayform
