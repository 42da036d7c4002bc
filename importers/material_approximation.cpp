#include "rayform/importers/material_approximation.h"

#include <algorithm>
#include <cmath>

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
  p.metallic = mb > gltf_dielectric_f0 ? std::clamp((mf - gltf_dielectric_f0) / (mb - gltf_dielectric_f0), 0.f, 1.f) : 0.f;
  return p;
}

}  // namespace rayform
