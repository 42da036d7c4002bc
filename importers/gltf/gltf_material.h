// glTF materials as the Scene's metallic-roughness material (Material::Model::
// metallic_roughness, Material::pbr: the file's meaning, no approximation for
// the core model and the extensions below), and KHR_texture_transform's uv
// transform in the Scene's flipped uv convention. This file reads factors;
// texture references are the reader's business (its texture cache), listed
// here so that every part names them alike (gltf_material_textures).
//
// What a material gets (Material):
//   model = metallic_roughness; pbr from the file:
//     pbrMetallicRoughness        base_color, metallic, roughness
//     normalTexture.scale         normal_scale
//     occlusionTexture.strength   occlusion_strength
//     emissiveFactor              emissive
//     alphaMode, alphaCutoff      alpha_mode (an unknown mode: opaque), alpha_cutoff
//     KHR_materials_emissive_strength, _ior, _specular, _transmission,
//     _volume, _clearcoat, _sheen: their fields, read;
//     KHR_materials_pbrSpecularGlossiness (the older workflow), approximated:
//       base_color = diffuseFactor, metallic = 0, roughness = 1 - glossiness,
//       F0 = specularFactor through KHR_materials_specular's colour
//       (specular_color = specularFactor / 0.04, specular = 1, so that
//       min(0.04 specular_color, 1) specular = specularFactor);
//   double_sided = two_sided_lighting = doubleSided (the specification
//   reverses a back face's normal);
//   unlit = KHR_materials_unlit;
//   of the Phong fields, which the metallic-roughness shader does not read,
//   only diffuse = base colour rgb (and, by the reader, diffuse_texture and
//   uv_transform = the base colour texture's, texture_modulates = true), for
//   code that wants a surface's albedo whatever its model (e.g. the albedo
//   output). Phong's specular, shininess, emission, alpha_cutoff and
//   refraction_index keep their defaults.
// Extensions that change nothing the Scene holds (iridescence, anisotropy,
// dispersion, diffuse_transmission) are recorded as ignored.
#pragma once

// The writer reaches the approximations (phong_to_pbr) through this header.
#include "rayform/importers/material_approximation.h"
#include "rayform/scene/scene.h"

#include <string>
#include <utility>
#include <vector>

namespace tinygltf {
struct Material;
}

namespace rayform {

// How a reader used a format extension the file names.
struct ExtensionUse {
  enum class Support : uint8_t { read, approximated, ignored };
  std::string name;
  Support support = Support::read;
  std::string detail;  // what was approximated or why it was ignored
};

// The material glTF's specification gives primitives without one: base
// colour 1, metallic 1, roughness 1, single-sided.
Material gltf_default_material();

// glTF material `gm` (named `where`, e.g. "materials[2]", in errors that
// start with `file`) as a Scene material, as described above, its texture
// slots empty. Values outside the specification's ranges are errors naming
// their JSON path. Extensions met are recorded in `extensions` (once each).
Material gltf_material_factors(const tinygltf::Material& gm, const std::string& file, const std::string& where,
                               std::vector<ExtensionUse>& extensions);

// A texture reference of a glTF material: where it sits in the material's
// JSON (`extension` empty: a core textureInfo of pbrMetallicRoughness or the
// material itself; else a member of that material extension), the
// PbrMaterial slot it fills and whether its texels are sRGB-encoded colour.
struct GltfMaterialTexture {
  const char* extension;  // "" for the core textures
  const char* key;        // e.g. "baseColorTexture", "clearcoatNormalTexture"
  TextureSlot PbrMaterial::*slot;
  bool srgb;  // base colour, emissive, specular colour, sheen colour (and the
              // specular-glossiness diffuse and specular textures)
};
// Every texture reference this reader keeps, core ones first.
const std::vector<GltfMaterialTexture>& gltf_material_textures();

// Every texture slot of `m` with its glTF name, for checks over all of them.
std::vector<std::pair<const char*, const TextureSlot*>> gltf_named_texture_slots(const PbrMaterial& m);

// KHR_texture_transform (uv' = T(offset) R(rotation) S(scale) uv in glTF's uv
// space, v pointing down the image) as the UvTransform that gives the same
// texel for the flipped uvs the Scene stores (v_scene = 1 - v_gltf).
// With F(u, v) = (u, 1 - v) the stored transform is F o M o F: the scale is
// kept, the rotation changes sign and the offset becomes
// (o.x + sin(r) s.y, 1 - o.y - cos(r) s.y).
UvTransform gltf_uv_transform_to_scene(vec2 offset, float rotation, vec2 scale);

// The inverse: the KHR_texture_transform values of a Scene uv transform.
struct GltfUvTransform {
  vec2 offset{0.f};
  float rotation = 0.f;
  vec2 scale{1.f};
};
GltfUvTransform scene_uv_transform_to_gltf(const UvTransform& t);

}  // namespace rayform
