// The glTF metallic-roughness BRDF (glTF 2.0 specification, Appendix B) and
// the layers of the KHR material extensions (ior, specular, transmission,
// clearcoat, sheen), as free functions. Directions are unit vectors in one
// frame: n the shading normal, v towards the viewer, l towards the light.
// The integrator (whitted_integrator.h, shade_pbr.h) evaluates a material's
// textures into a PbrSurface and calls these.
#pragma once

#include "rayform/math/math.h"

namespace rayform {

// A metallic-roughness material evaluated at one point (textures applied).
struct PbrSurface {
  vec3 base{1.f};            // base colour, linear
  float metallic = 1.f;      // 0..1
  float roughness = 1.f;     // perceptual roughness 0..1; alpha = roughness^2
  float ior = 1.5f;          // 0 or >= 1 (KHR_materials_ior)
  float specular = 1.f;      // KHR_materials_specular factor (F90 and F0 scale)
  vec3 specular_color{1.f};  // KHR_materials_specular colour (scales F0)
  float transmission = 0.f;  // KHR_materials_transmission: share of the dielectric diffuse
  float clearcoat = 0.f, clearcoat_roughness = 0.f;
  vec3 clearcoat_normal{0.f, 0.f, 1.f};  // unit; the shading normal unless a coat normal texture
  vec3 sheen_color{0.f};
  float sheen_roughness = 0.f;
};

// The microfacet pieces (alpha = roughness^2, clamped below by
// min_ggx_alpha so that a mirror-smooth surface stays finite).
inline constexpr float min_ggx_alpha = 1e-3f;
// GGX / Trowbridge-Reitz: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
float ggx_distribution(float n_dot_h, float alpha);
// Height-correlated Smith visibility V = G / (4 |n.l| |n.v|) (Heitz 2014).
float smith_visibility(float n_dot_l, float n_dot_v, float alpha);
// Schlick: f0 + (f90 - f0) (1 - cos)^5.
vec3 fresnel_schlick(vec3 f0, vec3 f90, float cos_theta);
// The dielectric Fresnel of a surface at normal incidence, F0 =
// min(((ior - 1) / (ior + 1))^2 specular_color, 1) specular, and its F90 = specular.
vec3 dielectric_f0(const PbrSurface& s);

// f(v, l) max(0, n.l): the light reflected towards v of unit irradiance
// arriving from l, summed over the material's layers (diffuse, specular,
// metal, sheen, clearcoat). The diffuse base's transmitted share is not in
// it (the integrator traces it as a refraction ray). 0 when l or v lies
// below the surface.
vec3 pbr_reflection(const PbrSurface& s, vec3 n, vec3 v, vec3 l);

// The directional albedo of the specular layers seen from v (n.v =
// n_dot_v): the integral over l of their f cos, the weight of one
// mirror-direction ray that stands in for the specular reflection of the
// surroundings (1 sample, deterministic).
vec3 pbr_specular_albedo(const PbrSurface& s, float n_dot_v);

// The weight of one refraction ray through a transmissive surface seen at
// n.v = n_dot_v: transmission (1 - metallic) base (1 - F_dielectric), under
// the coat's (1 - clearcoat F_coat).
vec3 pbr_transmission_weight(const PbrSurface& s, float n_dot_v);

}  // namespace rayform
