// The glTF metallic-roughness BRDF (glTF 2.0 specification, Appendix B) and
// the layers of the KHR material extensions (ior, specular, transmission,
// clearcoat, sheen), as free functions. Directions are unit vectors in one
// frame: n the shading normal, v towards the viewer, l towards the light.
// The integrator (whitted_integrator.h, shade_pbr.h) evaluates a material's
// textures into a PbrSurface and calls these.
//
// The layers, from the bottom up (f is the BRDF; every Fresnel term is
// Schlick's):
// - dielectric: F_d = Schlick(dielectric_f0, specular, |v.h|),
//   f_dielectric = F_d D V + (1 - max_component(F_d)) (1 - transmission) base / pi
//   (KHR_materials_specular's fresnel_mix: the diffuse keeps what the
//   strongest channel of the specular leaves; the transmitted share of the
//   diffuse base is not reflected);
// - metal: f_metal = Schlick(base, 1, |v.h|) D V;
// - f_base = mix(f_dielectric, f_metal, metallic);
// - sheen (KHR_materials_sheen): f = sheen_color D_charlie V_charlie +
//   f_base min(1 - max_component(sheen_color) E_sheen(n.v), 1 - max_component(sheen_color)
//   E_sheen(n.l)), E_sheen the sheen lobe's directional albedo (the
//   extension's albedo scaling, symmetric in v and l);
// - clearcoat (KHR_materials_clearcoat): with Fc = Schlick(0.04, 1, n_c.v)
//   and the coat's own normal n_c and roughness, f cos = (f cos)_below (1 -
//   clearcoat Fc) + clearcoat Fc D_c V_c (n_c.l) (the extension's
//   fresnel_coat: the coat's lobe carries Fc at n_c.v, not at v.h).
// Energy: the model is Appendix B's single-scattering one. Rough lobes lose
// the energy that would scatter more than once between microfacets, and a
// smooth dielectric seen at grazing angles reflects more than it receives
// (over the hemisphere, the diffuse's weight 1 - F_d(v.h) and the lobe's
// F_d do not add up to 1); tests/unit/pbr_brdf_test.cpp measures both.
// Reciprocity: everything but the clearcoat is reciprocal (f(v, l) =
// f(l, v)); the clearcoat's Fresnel weight depends on v alone, as the
// extension defines it.
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
// alpha = max(roughness^2, min_ggx_alpha).
float ggx_alpha(float roughness);
// GGX / Trowbridge-Reitz: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)
// for n.h > 0, else 0.
float ggx_distribution(float n_dot_h, float alpha);
// Height-correlated Smith visibility V = G / (4 |n.l| |n.v|) (Heitz 2014).
float smith_visibility(float n_dot_l, float n_dot_v, float alpha);
// Schlick: f0 + (f90 - f0) (1 - cos)^5, cos clamped to [0, 1].
vec3 fresnel_schlick(vec3 f0, vec3 f90, float cos_theta);
// The dielectric Fresnel of a surface at normal incidence, F0 =
// min(((ior - 1) / (ior + 1))^2 specular_color, 1) specular, and its F90 = specular.
// ior 0 gives ((0 - 1) / (0 + 1))^2 = 1: a reflector whose F0 is
// specular_color specular (KHR_materials_specular's conversion of
// specular-glossiness materials).
vec3 dielectric_f0(const PbrSurface& s);

// The sheen lobe (KHR_materials_sheen): alpha = max(sheen_roughness^2,
// min_sheen_alpha); the "Charlie" distribution of Conty Estevez and Kulla
// (2017), D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi), and
// their visibility V = 1 / ((1 + Lambda(n.v) + Lambda(n.l)) 4 n.v n.l) with
// the fitted Lambda the extension gives (reciprocal, unlike Ashikhmin's).
inline constexpr float min_sheen_alpha = 1e-3f;
float sheen_alpha(float sheen_roughness);
float charlie_distribution(float n_dot_h, float alpha);
float charlie_visibility(float n_dot_l, float n_dot_v, float alpha);
// E_sheen: the directional albedo of the sheen lobe (sheen colour 1) seen
// at n.v = n_dot_v, from a 32 x 32 table over (n.v, sheen roughness) in
// [0, 1]^2 integrated numerically once, at the first call (thread-safe),
// read bilinearly.
float sheen_directional_albedo(float n_dot_v, float sheen_roughness);

// The split-sum terms of the GGX lobe with Schlick's Fresnel: its directional
// albedo seen at n.v = n_dot_v is F0 A + F90 B with (A, B) = the result
// (x = A, y = B). From a 32 x 32 table over (n.v, perceptual roughness) in
// [0, 1]^2 integrated numerically once, at the first call (thread-safe),
// read bilinearly.
vec2 ggx_split_sum(float n_dot_v, float roughness);

// f(v, l) max(0, n.l): the light reflected towards v of unit irradiance
// arriving from l, summed over the material's layers (diffuse, specular,
// metal, sheen, clearcoat). The diffuse base's transmitted share is not in
// it (the integrator traces it as a refraction ray). 0 when l or v lies
// below the surface.
vec3 pbr_reflection(const PbrSurface& s, vec3 n, vec3 v, vec3 l);

// The directional albedo of the specular layers seen from v at n.v =
// n_dot_v (its absolute value used): the integral over l of their f cos,
// the weight of one mirror-direction ray that stands in for the specular
// reflection of the surroundings (1 sample, deterministic). It is
// mix(F0_d A + F90_d B, base A + B, metallic) (1 - max_component(sheen_color)
// E_sheen(n.v)) (1 - clearcoat Fc) + clearcoat Fc (A_c + B_c) with the
// split-sum terms above; the sheen lobe (broad, grazing, like the diffuse)
// is not in it. The coat is taken as seen at coat_n_dot_v = n_c.v, which
// the two-argument form takes equal to n_dot_v.
vec3 pbr_specular_albedo(const PbrSurface& s, float n_dot_v);
vec3 pbr_specular_albedo(const PbrSurface& s, float n_dot_v, float coat_n_dot_v);

// The weight of one refraction ray through a transmissive surface seen at
// n.v = n_dot_v (its absolute value used): transmission (1 - metallic) base
// (1 - F_dielectric), under the coat's (1 - clearcoat F_coat). F_dielectric
// is max3 of Schlick's dielectric Fresnel at n.v (as in the diffuse's
// weight above), and the sheen's albedo scaling at n.v applies as to the
// rest of the base. The coat is taken as seen at coat_n_dot_v, equal to
// n_dot_v in the two-argument form.
vec3 pbr_transmission_weight(const PbrSurface& s, float n_dot_v);
vec3 pbr_transmission_weight(const PbrSurface& s, float n_dot_v, float coat_n_dot_v);

}  // namespace rayform
