// The material mapping between glTF's physically based materials and the
// Scene's Phong material, both directions, and KHR_texture_transform's uv
// transform in the Scene's flipped uv convention. Textures themselves are the
// reader's and writer's business; this file maps factors.
//
// Reading (metallic-roughness to Phong, a documented approximation: the
// renderer has no environment to reflect):
//   K  = baseColorFactor x baseColorTexture texel: the diffuse colour, also
//        for metals, which would otherwise render black;
//   Ks = F0 (1 - roughness)^2, F0 = mix(F0_dielectric, baseColorFactor.rgb,
//        metallic), F0_dielectric = 0.04 (ior 1.5): Schlick's reflectance at
//        normal incidence, faded out on rough surfaces whose (unnormalised)
//        Phong lobe would be a broad glow;
//   n  = (2 / alpha^2 - 2) / 4, alpha = roughness^2, clamped to [1, 1024]:
//        the Blinn-Phong exponent of a microfacet lobe of width alpha
//        (Walter et al. 2007), divided by 4 because the shader's lobe is
//        (L.R)^n and the angle between L and R is twice that between N and H.
// Extensions that change colour, each onto those terms:
//   KHR_materials_emissive_strength  emission x emissiveStrength;
//   KHR_materials_ior                F0_dielectric = ((ior - 1) / (ior + 1))^2;
//   KHR_materials_specular           F0_dielectric x specularColorFactor
//                                    (clamped to 1) x specularFactor;
//   KHR_materials_unlit              drawn unlit: the surface colour K alone;
//   KHR_materials_transmission       refraction with index ior (1.5 by
//                                    default), weighted by Ks = max(Ks,
//                                    transmission x base) and K x (1 - transmission);
//   KHR_materials_clearcoat          a second lobe folded into the first:
//                                    Ks += clearcoat x 0.04 (1 - clearcoatRoughness)^2,
//                                    n = the sharper of the two exponents;
//   KHR_materials_pbrSpecularGlossiness (the older workflow): K = diffuseFactor,
//                                    F0 = specularFactor, roughness = 1 - glossiness;
// others (sheen, volume, iridescence, anisotropy, dispersion, variants) are
// ignored and said so once. Textures of these extensions are not sampled.
#pragma once

#include "rayform/importers/material_approximation.h"
#include "rayform/scene/scene.h"

#include <string>
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

// The factor part of glTF material `gm` (named `where`, e.g. "materials[2]",
// in errors that start with `file`) as Phong: diffuse, specular, shininess,
// emission, refraction, unlit, alpha cut-off threshold, sidedness. Textures
// are left to the caller. Extensions met are recorded in `extensions`.
void gltf_material_to_phong(const tinygltf::Material& gm, const std::string& file, const std::string& where,
                            Material& m, std::vector<ExtensionUse>& extensions);

// KHR_texture_transform (uv' = T(offset) R(rotation) S(scale) uv in glTF's uv
// space, v pointing down the image) as the Material::uv_transform that gives
// the same texel for the flipped uvs the Scene stores (v_scene = 1 - v_gltf).
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
