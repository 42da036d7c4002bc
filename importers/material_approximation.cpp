#include "rayform/importers/material_approximation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace rayform {

namespace {

// The range of Phong exponents the mapping produces.
constexpr float min_shininess = 1.f, max_shininess = 1024.f;

float shininess_of_roughness(float roughness) {
  const float alpha2 = roughness * roughness * roughness * roughness;
  const float n = alpha2 > 0.f ? (2.f / alpha2 - 2.f) / 4.f : max_shininess;
  return std::clamp(n, min_shininess, max_shininess);
}

}  // namespace

void pbr_to_phong(vec3 base, float metallic, float roughness, vec3 f0_dielectric, Material& m) {
  metallic = std::clamp(metallic, 0.f, 1.f);
  roughness = std::clamp(roughness, 0.f, 1.f);
  const vec3 f0 = glm::mix(f0_dielectric, base, metallic);
  const float smooth = 1.f - roughness;
  m.specular = f0 * smooth * smooth;
  m.shininess = shininess_of_roughness(roughness);
}

PbrValues phong_to_pbr(vec3 diffuse, vec3 specular, float shininess) {
  PbrValues p;
  const vec3 base = glm::clamp(diffuse, vec3(0.f), vec3(1.f));
  p.base = vec4(base, 1.f);
  if (specular == vec3(0.f) || !(shininess > 0.f)) {
    p.metallic = 0.f;
    p.roughness = 1.f;
    return p;
  }
  const float n = std::clamp(shininess, min_shininess, max_shininess);
  p.roughness = float(std::pow(2.0 * double(n) + 1.0, -0.25));
  const float smooth = 1.f - p.roughness;
  const vec3 f0 = glm::max(specular, vec3(0.f)) / (smooth * smooth);
  const float mb = (base.r + base.g + base.b) / 3.f, mf = (f0.r + f0.g + f0.b) / 3.f;
  p.metallic =
      mb > gltf_dielectric_f0 ? std::clamp((mf - gltf_dielectric_f0) / (mb - gltf_dielectric_f0), 0.f, 1.f) : 0.f;
  return p;
}

Material phong_approximation(const Material& m) {
  if (m.model != Material::Model::metallic_roughness) return m;
  const PbrMaterial& p = m.pbr;
  Material out;
  out.name = m.name;
  out.double_sided = m.double_sided;
  out.two_sided_lighting = m.two_sided_lighting;
  out.unlit = m.unlit;
  out.texture_modulates = true;
  const vec3 base = vec3(p.base_color);
  out.diffuse = base;
  if (p.base_color_texture.used() && p.base_color_texture.texcoord == 0) {
    out.diffuse_texture = p.base_color_texture.texture;
    out.uv_transform = p.base_color_texture.transform;
  }
  const float f = p.ior == 0.f ? 1.f : (p.ior - 1.f) / (p.ior + 1.f);
  const vec3 f0_dielectric = glm::min(vec3(f * f) * p.specular_color, vec3(1.f)) * p.specular;
  pbr_to_phong(base, p.metallic, p.roughness, f0_dielectric, out);
  if (p.clearcoat > 0.f) {
    const float smooth = 1.f - std::clamp(p.clearcoat_roughness, 0.f, 1.f);
    out.specular += vec3(p.clearcoat * gltf_dielectric_f0 * smooth * smooth);
    out.shininess = std::max(out.shininess, shininess_of_roughness(p.clearcoat_roughness));
  }
  if (p.transmission > 0.f) {
    out.refraction_index = p.ior >= 1.f ? p.ior : PbrMaterial{}.ior;
    out.specular = glm::max(out.specular, p.transmission * glm::clamp(base, vec3(0.f), vec3(1.f)));
    out.diffuse *= 1.f - p.transmission;
  }
  out.emission = p.emissive * p.emissive_strength;
  if (p.alpha_mode == PbrMaterial::AlphaMode::mask) {
    // The shader compares the texel's alpha with alpha_cutoff; glTF compares
    // base alpha x texel alpha with alpha_cutoff.
    const float cutoff_above_any_alpha = 2.f;
    out.alpha_cutoff = p.base_color.a > 0.f ? p.alpha_cutoff / p.base_color.a : cutoff_above_any_alpha;
  }
  return out;
}

std::vector<std::string> pbr_fields_lost_in_phong(const Material& m) {
  std::vector<std::string> lost;
  if (m.model != Material::Model::metallic_roughness) return lost;
  const PbrMaterial& p = m.pbr;
  const PbrMaterial defaults;
  if (p.base_color_texture.used() && p.base_color_texture.texcoord != 0)
    lost.push_back("base colour texture on the second uv set");
  if (p.metallic_roughness_texture.used()) lost.push_back("metallic-roughness texture");
  if (p.normal_texture.used()) lost.push_back("normal texture");
  if (p.occlusion_texture.used()) lost.push_back("occlusion texture");
  if (p.emissive_texture.used()) lost.push_back("emissive texture");
  if (p.alpha_mode == PbrMaterial::AlphaMode::blend) lost.push_back("alpha blending");
  if (p.specular_texture.used() || p.specular_color_texture.used()) lost.push_back("specular textures");
  if (p.transmission_texture.used()) lost.push_back("transmission texture");
  if (p.thickness != defaults.thickness || p.thickness_texture.used() ||
      p.attenuation_color != defaults.attenuation_color || p.attenuation_distance != defaults.attenuation_distance)
    lost.push_back("volume");
  if (p.clearcoat_texture.used() || p.clearcoat_roughness_texture.used() || p.clearcoat_normal_texture.used())
    lost.push_back("clearcoat textures");
  if (p.sheen_color != defaults.sheen_color || p.sheen_color_texture.used() || p.sheen_roughness_texture.used())
    lost.push_back("sheen");
  return lost;
}

}  // namespace rayform
