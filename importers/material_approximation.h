// Approximations between the Scene's two material models (scene.h), for the
// writers of formats that hold only one of them: the course's Phong model
// from metallic-roughness values (course and OBJ writers), and
// metallic-roughness values from Phong (glTF writer). The renderer shades
// each model as it is; nothing here is used for pictures.
//
// Metallic-roughness to Phong:
//   K  = base colour (also for metals, which would otherwise render black);
//   Ks = F0 (1 - roughness)^2, F0 = mix(F0_dielectric, base, metallic),
//        F0_dielectric = 0.04 (ior 1.5): Schlick's reflectance at normal
//        incidence, faded out on rough surfaces whose (unnormalised) Phong
//        lobe would be a broad glow;
//   n  = (2 / alpha^2 - 2) / 4, alpha = roughness^2, clamped to [1, 1024]:
//        the Blinn-Phong exponent of a microfacet lobe of width alpha
//        (Walter et al. 2007), divided by 4 because the Phong lobe is
//        (L.R)^n and the angle between L and R is twice that between N and H.
#pragma once

#include "rayform/scene/scene.h"

#include <string>
#include <vector>

namespace rayform {

// Reflectance at normal incidence of a dielectric of index 1.5, glTF's default.
inline constexpr float gltf_dielectric_f0 = 0.04f;

// The Phong terms (m.specular, m.shininess) of metallic-roughness values.
void pbr_to_phong(vec3 base, float metallic, float roughness, vec3 f0_dielectric, Material& m);

// Phong (diffuse K, specular Ks, shininess n) as glTF metallic-roughness, the
// inverse of pbr_to_phong with F0_dielectric = 0.04:
//   base      = K (clamped to [0, 1]);
//   roughness = (2 n + 1)^(-1/4) (n = 0 or Ks = 0: 1, a matte surface);
//   metallic  = (mean(F0) - 0.04) / (mean(base) - 0.04) clamped to [0, 1],
//               F0 = Ks / (1 - roughness)^2 (0 when base is no brighter than 0.04).
// pbr_to_phong gives back K exactly and (Ks, n) exactly wherever they lie in
// its range (Ks = mix(0.04, K, m) (1 - r)^2 for some m in [0, 1], 1 <= n <= 1024).
struct PbrValues {
  vec4 base{1.f};
  float metallic = 0.f, roughness = 1.f;
};
PbrValues phong_to_pbr(vec3 diffuse, vec3 specular, float shininess);

// The Phong material that stands for a metallic-roughness one (Model::
// metallic_roughness) in formats that hold only Phong; a Phong material is
// returned as it is. Kept: the name, sidedness and unlit; diffuse K = base
// colour with the base colour texture (uv set 0 only) and its transform,
// modulating; Ks and n from pbr_to_phong with F0_dielectric =
// ((ior - 1) / (ior + 1))^2 x min(specular_color, 1) x specular (ior 0: 1);
// clearcoat folded in (Ks += clearcoat x 0.04 (1 - clearcoat_roughness)^2,
// n the sharper exponent); transmission as refraction of index `ior`
// (Ks = max(Ks, transmission x base), K x (1 - transmission)); emission =
// emissive x emissive_strength; MASK as the cut-off alpha_cutoff / base alpha
// (a base alpha of 0: every texel a hole). What is lost:
// pbr_fields_lost_in_phong.
Material phong_approximation(const Material& m);

// What phong_approximation cannot hold of a metallic-roughness material, each
// named for messages ("normal texture", "sheen", ...), in PbrMaterial's order;
// empty for a Phong material.
std::vector<std::string> pbr_fields_lost_in_phong(const Material& m);

}  // namespace rayform
