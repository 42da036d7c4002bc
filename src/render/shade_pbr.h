// A glTF metallic-roughness material (Scene PbrMaterial) at a hit: its
// textures sampled and applied to the factors (texel channels as the
// specification assigns them), its normal texture applied to the shading
// normal, and its emission and occlusion. The BRDF itself is pbr_brdf.h;
// the light transport is the integrator's (whitted_integrator.h).
#pragma once

#include "rayform/render/pbr_brdf.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/scene_intersect.h"

namespace rayform {

// The texel of a material's texture slot at a hit: 1 where the slot has no
// texture, the texture was not decoded, or the hit lacks the slot's uv set.
inline vec4 slot_texel(const PreparedScene& p, const TextureSlot& slot, const SurfacePoint& sp) {
  if (!slot.used()) return vec4(1.f);
  const bool has_uv = slot.texcoord == 0 ? sp.has_uv : slot.texcoord == 1 && sp.has_uv1;
  const TextureImage& t = p.textures[size_t(slot.texture)];
  if (!has_uv || t.empty()) return vec4(1.f);
  vec2 uv = slot.texcoord == 0 ? sp.uv : sp.uv1;
  if (!slot.transform.is_identity()) uv = slot.transform.apply(uv);
  return sample_texture(t, uv);
}

// Base colour and alpha: factor x texel x vertex colour (glTF COLOR_0).
inline vec4 pbr_base_color(const PreparedScene& p, const PbrMaterial& m, const SurfacePoint& sp) {
  const vec4 c = m.base_color * slot_texel(p, m.base_color_texture, sp);
  return vec4(vec3(c) * sp.color, c.a);
}

// Shading normal n (unit, on the side the tangent frame was made for)
// perturbed by a tangent-space normal texture: texel (x, y, z) = rgb * 2 - 1,
// x and y scaled by `scale`, in the frame (T, B, n), T the hit's tangent
// made orthogonal to n and B = w cross(n, T) (glTF). n itself where the
// slot has no texture or the hit no tangent.
inline vec3 mapped_normal(const PreparedScene& p, const TextureSlot& slot, float scale, const SurfacePoint& sp,
                          vec3 n) {
  if (!slot.used() || !sp.has_tangent) return n;
  vec3 t = vec3(sp.tangent) - glm::dot(vec3(sp.tangent), n) * n;
  const float t_length = glm::length(t);
  if (!(t_length > 0.f) || !std::isfinite(t_length)) return n;
  t /= t_length;
  const vec3 b = (sp.tangent.w < 0.f ? -1.f : 1.f) * glm::cross(n, t);
  vec3 tn = vec3(slot_texel(p, slot, sp)) * 2.f - vec3(1.f);
  tn.x *= scale;
  tn.y *= scale;
  const vec3 mapped = tn.x * t + tn.y * b + tn.z * n;
  const float length = glm::length(mapped);
  return length > 0.f && std::isfinite(length) ? mapped / length : n;
}

// Everything the integrator needs of a pbr material at a hit.
struct PbrPoint {
  PbrSurface surface;
  vec3 normal{0.f, 0.f, 1.f};  // shading normal, unit, facing the viewer where it can
  vec3 emission{0.f};          // emitted radiance
  float occlusion = 1.f;       // the share of indirect light that arrives (occlusion texture)
  bool volume = false;         // thickness > 0: refraction bends, the inside attenuates
};

// The material `m` at hit `sp` seen along unit direction d, with its base
// colour already evaluated (pbr_base_color). The normal texture applies to
// the side the normal faces; `flipped` says sp.normal was reversed to show a
// back face (two-sided lighting), so that the texture is applied in the
// surface's own frame and the result reversed again.
inline PbrPoint pbr_point(const PreparedScene& p, const PbrMaterial& m, const SurfacePoint& sp, vec3 base, vec3 d,
                          bool flipped) {
  PbrPoint out;
  PbrSurface& s = out.surface;
  s.base = base;
  const vec4 mr = slot_texel(p, m.metallic_roughness_texture, sp);
  s.metallic = std::clamp(m.metallic * mr.b, 0.f, 1.f);
  s.roughness = std::clamp(m.roughness * mr.g, 0.f, 1.f);
  s.ior = m.ior;
  s.specular = m.specular * slot_texel(p, m.specular_texture, sp).a;
  s.specular_color = m.specular_color * vec3(slot_texel(p, m.specular_color_texture, sp));
  s.transmission = m.transmission * slot_texel(p, m.transmission_texture, sp).r;
  s.clearcoat = m.clearcoat * slot_texel(p, m.clearcoat_texture, sp).r;
  s.clearcoat_roughness = m.clearcoat_roughness * slot_texel(p, m.clearcoat_roughness_texture, sp).g;
  const vec4 sheen = slot_texel(p, m.sheen_color_texture, sp);
  s.sheen_color = m.sheen_color * vec3(sheen);
  s.sheen_roughness = m.sheen_roughness * slot_texel(p, m.sheen_roughness_texture, sp).a;

  const vec3 own = flipped ? -sp.normal : sp.normal;  // the normal of the surface's own side
  const float side = flipped ? -1.f : 1.f;
  vec3 n = side * mapped_normal(p, m.normal_texture, m.normal_scale, sp, own);
  // A normal texture may tilt the normal away from the viewer, and an
  // interpolated normal faces away near silhouettes: the interpolated
  // normal, then the geometric normal (turned towards the viewer) are used
  // where they do.
  if (glm::dot(n, d) >= 0.f) n = sp.normal;
  if (glm::dot(n, d) >= 0.f) n = glm::dot(sp.geometric_normal, d) < 0.f ? sp.geometric_normal : -sp.geometric_normal;
  out.normal = n;
  s.clearcoat_normal =
      s.clearcoat > 0.f ? side * mapped_normal(p, m.clearcoat_normal_texture, m.clearcoat_normal_scale, sp, own) : n;
  if (glm::dot(s.clearcoat_normal, d) >= 0.f) s.clearcoat_normal = n;

  out.emission = m.emissive * m.emissive_strength;
  if (out.emission != vec3(0.f)) out.emission *= vec3(slot_texel(p, m.emissive_texture, sp));
  out.occlusion = 1.f + m.occlusion_strength * (slot_texel(p, m.occlusion_texture, sp).r - 1.f);
  out.volume = m.thickness > 0.f && s.transmission > 0.f;
  return out;
}

// The fraction of light a volume's inside lets through along a path of
// `distance` world units (Beer-Lambert, KHR_materials_volume).
inline vec3 volume_transmittance(const PbrMaterial& m, float distance) {
  if (!std::isfinite(m.attenuation_distance) || m.attenuation_distance <= 0.f) return vec3(1.f);
  const float k = distance / m.attenuation_distance;
  return glm::pow(glm::max(m.attenuation_color, vec3(0.f)), vec3(k));
}

}  // namespace rayform
