// glTF 2.0 (.gltf with external or data-URI resources, .glb) as a Scene,
// through tinygltf (a thin adapter; every index and byte range is checked here,
// not trusted).
//
// What the Scene gets:
// - the node tree of one scene (the default one) as transform nodes (matrix
//   or T*R*S), under a root group named after the file; one shape node per
//   mesh primitive; a glTF mesh used by several nodes is shared (one Scene
//   mesh, so one BVH), and EXT_mesh_gpu_instancing instances are transform
//   nodes over those same shape nodes, never copies;
// - primitives in TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN (points and lines
//   are skipped with a warning), indexed by u8/u16/u32 or not at all;
//   byteStride, sparse accessors, normalised and (KHR_mesh_quantization)
//   integer attributes, KHR_draco_mesh_compression and
//   EXT_meshopt_compression (gltf_accessors.h, gltf_compression.h);
//   no NORMAL: Mesh::normals stays empty, so the renderer shades with face
//   normals (the flat normals the specification asks for);
// - morph targets at the node's (else the mesh's) default weights; skinned
//   meshes in the pose their joints' node transforms give, in world space
//   (linear blend skinning; the skinned node's own transform is ignored, as
//   the specification says); animations are not played;
// - TEXCOORD_0 as Mesh::uvs and TEXCOORD_1 as Mesh::uvs1, v flipped to the
//   renderer's convention (v = 1 is the top row: v_scene = 1 - v_gltf);
//   TANGENT as Mesh::tangents; COLOR_0 as vertex colours;
// - materials: gltf_material.h (metallic-roughness and KHR_materials_* kept
//   as Material::pbr, the file's meaning); every texture reference as a
//   TextureSlot with its texCoord and KHR_texture_transform; textures as RGBA8
//   pixels decoded by gltf_images.h (PNG, JPEG, WebP through the core's
//   image_decode.h; standard lookup, sampler wrap and filter), sRGB for the
//   colour textures and linear for the others (a texture used both ways is
//   two Scene textures), KTX2 only through a PNG/JPEG fallback source;
// - KHR_materials_variants: each primitive's default material (the variants
//   are reported ignored);
// - cameras and KHR_lights_punctual lights placed by their nodes' world
//   transforms, a light's colour = colour x intensity / pi (scene.h's units).
// Errors: rayform::Error "file: element: what", e.g.
// "box.gltf: meshes[2].primitives[0].indices: index 40 is out of range (the primitive has 24 vertices)".
#pragma once

#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/image/image_decode.h"
#include "rayform/importers/referenced_files.h"
#include "rayform/base/limits.h"
#include "rayform/scene/scene.h"

#include <string>
#include <vector>

namespace rayform {

struct GltfReadOptions {
  int scene = -1;       // index into the file's scenes; -1: its default scene (or scene 0)
  Limits limits{};      // json_depth, unbacked_elements; vertices, triangles, instances before copies
  FileAccess access{};  // buffers and images the file names
};

// Reads a .gltf or .glb file (the content decides, not the extension).
// Warnings, if wanted, are appended to `warnings`; the extensions the file
// names, with how each was used, to `extensions`.
Scene read_gltf_scene(const std::string& path, const GltfReadOptions& options = {},
                      std::vector<std::string>* warnings = nullptr, std::vector<ExtensionUse>* extensions = nullptr);

}  // namespace rayform
