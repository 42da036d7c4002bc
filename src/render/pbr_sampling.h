// Importance sampling of the glTF metallic-roughness BRDF (render/pbr_brdf.h)
// for one bounce of a path, and the multiple-importance-sampling weights that
// combine it with light sampling. Free functions over plain data, no
// allocation: the integrator draws the random numbers and traces the rays.
//
// Conventions: directions are unit vectors pointing away from the surface (v
// towards the viewer, l towards the light or the next hit), as in
// pbr_brdf.h. "Local" vectors are in a ShadingFrame's coordinates, the normal
// along +z. Every pdf is per unit solid angle (sr^-1) unless it says
// otherwise; a probability of a discrete choice has no unit.
//
// The GGX lobes are sampled by their distribution of visible normals (VNDF,
// Heitz 2018), with the spherical-cap construction of Dupuy and Benyoub
// (2023, "Sound and Complete Visible Normal Sampling for the GGX
// Distribution"): it draws exactly the same normals as Heitz's two-disk
// construction, in fewer operations. The GGX D(h) and Smith G1 are those of
// pbr_brdf.h (alpha = ggx_alpha(roughness), clamped below by min_ggx_alpha).
#pragma once

#include "rayform/math/math.h"
#include "rayform/render/pbr_brdf.h"

#include <cmath>

namespace rayform {

// An orthonormal basis (t, b, n), right-handed (cross(t, b) = n), built from
// a unit normal n without a branch on its direction (Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited"). Continuous everywhere but
// across n.z = 0 where the sign of n.z flips (the basis is still orthonormal
// there).
struct ShadingFrame {
  vec3 t, b, n;
};
inline ShadingFrame make_shading_frame(vec3 n) {
  const float sign = std::copysign(1.f, n.z);
  const float a = -1.f / (sign + n.z);
  const float c = n.x * n.y * a;
  return {vec3(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x), vec3(c, sign + n.y * n.y * a, -n.y), n};
}
// w in the frame's coordinates (x along t, y along b, z along n).
inline vec3 to_local(const ShadingFrame& f, vec3 w) {
  return vec3(glm::dot(w, f.t), glm::dot(w, f.b), glm::dot(w, f.n));
}
// A local vector back in the frame's space.
inline vec3 to_world(const ShadingFrame& f, vec3 w) { return w.x * f.t + w.y * f.b + w.z * f.n; }

// Smith's masking G1(v) = 1 / (1 + Lambda(v)) of the GGX distribution, with
// Lambda(v) = (sqrt(1 + alpha^2 tan^2 theta_v) - 1) / 2: the one-direction
// factor of pbr_brdf.h's height-correlated smith_visibility (G2 = 1 / (1 +
// Lambda(v) + Lambda(l))). |n_dot_v| is used; 0 at n.v = 0.
float smith_g1(float n_dot_v, float alpha);

// A microfacet normal h (local, h.z > 0) drawn from the GGX distribution of
// normals visible from v_local (v_local.z > 0): pdf ggx_vndf_pdf. u in [0, 1)^2.
vec3 sample_ggx_vndf(vec3 v_local, float alpha, vec2 u);
// The density of sample_ggx_vndf's h: G1(v) max(0, v.h) D(h) / (n.v), per
// unit solid angle of h. 0 when v_local.z <= 0 or h_local.z <= 0.
float ggx_vndf_pdf(vec3 v_local, vec3 h_local, float alpha);
// The density of l = reflect(-v, h) = 2 (v.h) h - v for h from
// sample_ggx_vndf: ggx_vndf_pdf(v, h) / (4 |v.h|) with h = normalize(v + l),
// per unit solid angle of l. Defined for l on either side of the surface
// (a sampled l may fall below the horizon); 0 when v_local.z <= 0.
float ggx_reflection_pdf(vec3 v_local, vec3 l_local, float alpha);

// Refraction through a microfacet. eta = (index of refraction on l's side) /
// (index on v's side), e.g. 1.5 entering glass from air, 1 / 1.5 leaving it.
// The direction of -v refracted by the facet h (Snell's law, v.h > 0), or
// vec3(0) at total internal reflection (or v.h <= 0).
vec3 refract_through(vec3 v_local, vec3 h_local, float eta);
// The density of l = refract_through(v, h, eta) for h from sample_ggx_vndf,
// per unit solid angle of l: ggx_vndf_pdf(v, h) |dw_h / dw_l| with the
// generalised half vector h = +-normalize(v + eta l) (on the side of +z) and
// the Jacobian eta^2 |l.h| / (v.h + eta l.h)^2 (Walter et al. 2007, eq. 17).
// 0 unless v_local.z > 0, l_local.z < 0, v.h > 0 and l.h < 0.
float ggx_refraction_pdf(vec3 v_local, vec3 l_local, float alpha, float eta);

// Cosine-weighted directions on the local hemisphere (Malley's method on a
// concentric disk, Shirley and Chiu 1997): pdf cos(theta) / pi.
vec3 sample_cosine_hemisphere(vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.f ? cos_theta / pi : 0.f; }

// The probabilities with which sample_pbr picks its lobes for a view v at a
// point of normal n (they sum to 1, or are all 0 when nothing is reflected
// or transmitted towards v). Each is proportional to an approximate albedo of
// its lobe, the mean over RGB of:
// - diffuse: the dielectric's diffuse base (1 - metallic) (1 - transmission)
//   base (1 - max_component(F_d(n.v))) plus the sheen's sheen_color E_sheen(n.v) (the
//   sheen lobe, broad and grazing, is drawn with the diffuse's cosine
//   distribution), both under the sheen scaling and the coat's (1 - clearcoat Fc);
// - specular: the GGX lobe's split-sum albedo, mix(F0_d A + F90_d B, base A +
//   B, metallic), under the same;
// - coat: clearcoat Fc (A_c + B_c) with Fc and the split-sum terms at n_c.v;
// - transmission: pbr_transmission_weight.
// Approximate is enough: the estimator is unbiased for any probabilities
// that are positive where the BRDF is.
struct PbrLobeProbabilities {
  float diffuse = 0.f, specular = 0.f, coat = 0.f, transmission = 0.f;
};
PbrLobeProbabilities pbr_lobe_probabilities(const PbrSurface& s, vec3 n, vec3 v);

// One direction for the next ray from a surface point.
struct BrdfSample {
  vec3 direction{0.f};  // unit, away from the surface
  // The factor the radiance arriving from `direction` is multiplied by: f
  // cos / pdf for a reflection, pbr_transmission_weight / probability for
  // the transmission. 0 together with pdf 0 when there is no sample.
  vec3 weight{0.f};
  // Reflection: the mixture pdf over the reflection lobes, per unit solid
  // angle (= pbr_pdf(direction)). Transmission: the probability of choosing
  // it (a discrete choice, no unit: the transmission is a delta lobe). 0: no
  // sample (the view or the sampled direction is below the surface, or the
  // material reflects and transmits nothing): end the path.
  float pdf = 0.f;
  bool specular_transmission = false;
  bool diffuse = false;  // drawn from the diffuse lobe (light transport without diffuse interreflection ends there)
};

// Samples one bounce of the whole material with 3 random numbers u3 in
// [0, 1)^3: u3.x picks a lobe (pbr_lobe_probabilities), u3.y and u3.z
// sample it:
// - diffuse (and sheen): cosine-weighted about n;
// - specular: GGX VNDF about n with alpha = ggx_alpha(roughness), l =
//   reflect(-v, h);
// - coat (clearcoat > 0): GGX VNDF about clearcoat_normal with
//   ggx_alpha(clearcoat_roughness);
// - transmission: the thin-walled glTF transmission as one delta lobe:
//   direction -v, specular_transmission = true, weight
//   pbr_transmission_weight(s, n.v, n_c.v) / P(transmission). For a volume
//   (KHR_materials_volume) the integrator bends the ray itself, as it does
//   today; the rough refraction lobe (ggx_refraction_pdf) is not sampled here.
// A reflected direction's weight is pbr_reflection(s, n, v, l) / pbr_pdf(s,
// n, v, l): the pdf of the mixture over all the lobes that could have made
// l (one-sample MIS over lobes with the balance heuristic), so that the mean
// weight is the directional albedo, exactly (unbiased). Directions that fall
// below the surface (n.l <= 0) are no sample (pdf 0). n.v <= 0 (the viewer
// below the shading normal): no sample; the integrator flips n for two-sided
// materials before calling.
BrdfSample sample_pbr(const PbrSurface& s, vec3 n, vec3 v, vec3 u3);

// The pdf per unit solid angle with which sample_pbr returns the reflected
// direction l (for MIS with light sampling): sum over the reflection lobes of
// P(lobe) pdf_lobe(l). 0 when n.l <= 0 or n.v <= 0. Over the hemisphere it
// integrates to 1 - P(transmission) - P(a sample below the surface).
float pbr_pdf(const PbrSurface& s, vec3 n, vec3 v, vec3 l);

// Multiple importance sampling (Veach 1997, ch. 9) of one sample drawn by
// strategy a, where strategy b could have drawn it too: the weight of the
// sample, given both strategies' pdfs (each already multiplied by its sample
// count when the counts differ). power_heuristic(a, b) + power_heuristic(b,
// a) = 1, and likewise for balance_heuristic, for pdfs >= 0 not both 0 and
// not both infinite. Both give 0 when pdf_a = 0 or pdf_b is infinite, and 1
// when pdf_a is infinite (a delta lobe, which b cannot draw) or pdf_b = 0.
// The balance heuristic: pdf_a / (pdf_a + pdf_b).
float balance_heuristic(float pdf_a, float pdf_b);
// The power heuristic with exponent beta = 2: pdf_a^2 / (pdf_a^2 + pdf_b^2)
// (Veach's recommendation: lower variance than the balance heuristic where
// one strategy is much better).
float power_heuristic(float pdf_a, float pdf_b);

}  // namespace rayform
