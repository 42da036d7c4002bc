#include "rayform/render/pbr_sampling.h"

#include <algorithm>
#include <cmath>

namespace rayform {
namespace {

float mean3(vec3 c) { return (c.x + c.y + c.z) * (1.f / 3.f); }

// The coat's Fresnel at normal incidence: KHR_materials_clearcoat's fixed
// coat of ior 1.5, ((1.5 - 1) / (1.5 + 1))^2 (the value pbr_brdf.cpp uses).
constexpr float coat_f0 = 0.04f;

// What sample_pbr and pbr_pdf share: the frames, alphas and probabilities of
// one (surface, n, v).
struct LobeSetup {
  PbrLobeProbabilities p;
  ShadingFrame frame, coat_frame;
  vec3 v_local, coat_v_local;
  float alpha, coat_alpha;
};

LobeSetup lobe_setup(const PbrSurface& s, vec3 n, vec3 v) {
  LobeSetup L;
  L.p = pbr_lobe_probabilities(s, n, v);
  L.frame = make_shading_frame(n);
  L.v_local = to_local(L.frame, v);
  L.alpha = ggx_alpha(s.roughness);
  if (L.p.coat > 0.f) {
    L.coat_frame = make_shading_frame(s.clearcoat_normal);
    L.coat_v_local = to_local(L.coat_frame, v);
    L.coat_alpha = ggx_alpha(s.clearcoat_roughness);
  }
  return L;
}

// The mixture pdf of the reflection lobes at l (n.l > 0 checked by the caller).
float mixture_pdf(const LobeSetup& L, vec3 l) {
  float pdf = 0.f;
  const vec3 l_local = to_local(L.frame, l);
  if (L.p.diffuse > 0.f) pdf += L.p.diffuse * cosine_hemisphere_pdf(l_local.z);
  if (L.p.specular > 0.f) pdf += L.p.specular * ggx_reflection_pdf(L.v_local, l_local, L.alpha);
  if (L.p.coat > 0.f) pdf += L.p.coat * ggx_reflection_pdf(L.coat_v_local, to_local(L.coat_frame, l), L.coat_alpha);
  return pdf;
}

}  // namespace

float smith_g1(float n_dot_v, float alpha) {
  const float nv = std::abs(n_dot_v), alpha2 = alpha * alpha;
  // 2 nv / (nv + sqrt(alpha^2 + (1 - alpha^2) nv^2)): 1 / (1 + Lambda) times nv / nv.
  return 2.f * nv / (nv + std::sqrt(alpha2 + (1.f - alpha2) * nv * nv));
}

vec3 sample_ggx_vndf(vec3 v_local, float alpha, vec2 u) {
  // Stretch v to the configuration of alpha = 1, where the visible normals
  // are the points of the unit sphere's cap {c.z >= -v.z} translated by v
  // (Dupuy and Benyoub 2023, listing 3): c uniform on the cap, h = c + v.
  const vec3 v_std = glm::normalize(vec3(alpha * v_local.x, alpha * v_local.y, v_local.z));
  const float phi = 2.f * pi * u.x;
  const float z = (1.f - u.y) * (1.f + v_std.z) - v_std.z;
  const float sin_theta = std::sqrt(std::clamp(1.f - z * z, 0.f, 1.f));
  const vec3 h_std = vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), z) + v_std;
  // Unstretch the normal (normals transform by the inverse transpose).
  return glm::normalize(vec3(alpha * h_std.x, alpha * h_std.y, std::max(0.f, h_std.z)));
}

float ggx_vndf_pdf(vec3 v_local, vec3 h_local, float alpha) {
  if (v_local.z <= 0.f || h_local.z <= 0.f) return 0.f;
  const float v_dot_h = glm::dot(v_local, h_local);
  if (v_dot_h <= 0.f) return 0.f;
  return smith_g1(v_local.z, alpha) * v_dot_h * ggx_distribution(h_local.z, alpha) / v_local.z;
}

float ggx_reflection_pdf(vec3 v_local, vec3 l_local, float alpha) {
  if (v_local.z <= 0.f) return 0.f;
  const vec3 sum = v_local + l_local;
  const float length2 = glm::dot(sum, sum);
  if (!(length2 > 0.f)) return 0.f;  // l = -v: no facet reflects -v to itself
  const vec3 h = sum / std::sqrt(length2);
  const float v_dot_h = glm::dot(v_local, h);  // > 0: h halves v and l
  return ggx_vndf_pdf(v_local, h, alpha) / (4.f * v_dot_h);
}

vec3 refract_through(vec3 v_local, vec3 h_local, float eta) {
  const float cos_i = glm::dot(v_local, h_local);
  if (cos_i <= 0.f) return vec3(0.f);
  const float inv_eta = 1.f / eta;  // n_v / n_l
  const float sin2_t = inv_eta * inv_eta * std::max(0.f, 1.f - cos_i * cos_i);
  if (sin2_t >= 1.f) return vec3(0.f);  // total internal reflection
  const float cos_t = std::sqrt(1.f - sin2_t);
  return glm::normalize(-inv_eta * v_local + (inv_eta * cos_i - cos_t) * h_local);
}

float ggx_refraction_pdf(vec3 v_local, vec3 l_local, float alpha, float eta) {
  if (v_local.z <= 0.f || l_local.z >= 0.f) return 0.f;
  vec3 h = v_local + eta * l_local;
  const float length2 = glm::dot(h, h);
  if (!(length2 > 0.f)) return 0.f;
  h /= std::sqrt(length2);
  if (h.z < 0.f) h = -h;
  const float v_dot_h = glm::dot(v_local, h), l_dot_h = glm::dot(l_local, h);
  if (v_dot_h <= 0.f || l_dot_h >= 0.f) return 0.f;
  const float denominator = v_dot_h + eta * l_dot_h;
  return ggx_vndf_pdf(v_local, h, alpha) * eta * eta * -l_dot_h / (denominator * denominator);
}

vec3 sample_cosine_hemisphere(vec2 u) {
  // Shirley and Chiu's concentric map of [0, 1)^2 to the unit disk, lifted
  // to the hemisphere (z = sqrt(1 - r^2)).
  const vec2 o = 2.f * u - 1.f;
  vec2 disk(0.f);
  if (o.x != 0.f || o.y != 0.f) {
    float r, theta;
    if (std::abs(o.x) > std::abs(o.y)) {
      r = o.x;
      theta = 0.25f * pi * (o.y / o.x);
    } else {
      r = o.y;
      theta = 0.5f * pi - 0.25f * pi * (o.x / o.y);
    }
    disk = r * vec2(std::cos(theta), std::sin(theta));
  }
  return vec3(disk, std::sqrt(std::max(0.f, 1.f - glm::dot(disk, disk))));
}

PbrLobeProbabilities pbr_lobe_probabilities(const PbrSurface& s, vec3 n, vec3 v) {
  PbrLobeProbabilities p;
  const float n_dot_v = glm::dot(n, v);
  if (n_dot_v <= 0.f) return p;
  const float coat_n_dot_v = glm::dot(s.clearcoat_normal, v);

  float coat_weight = 0.f;  // clearcoat Fc: the share the coat reflects
  if (s.clearcoat > 0.f) {
    coat_weight = s.clearcoat * fresnel_schlick(vec3(coat_f0), vec3(1.f), std::abs(coat_n_dot_v)).x;
    if (coat_n_dot_v > 0.f) {
      const vec2 ab = ggx_split_sum(coat_n_dot_v, s.clearcoat_roughness);
      p.coat = coat_weight * (ab.x + ab.y);
    }
  }
  const float sheen_e = max_component(s.sheen_color) > 0.f ? sheen_directional_albedo(n_dot_v, s.sheen_roughness) : 0.f;
  const float below = (1.f - coat_weight) * std::clamp(1.f - max_component(s.sheen_color) * sheen_e, 0.f, 1.f);

  const vec3 f0 = dielectric_f0(s);
  const vec2 ab = ggx_split_sum(n_dot_v, s.roughness);
  const vec3 specular = glm::mix(f0 * ab.x + vec3(s.specular * ab.y), s.base * ab.x + vec3(ab.y), s.metallic);
  p.specular = mean3(specular) * below;

  const float fresnel_v = max_component(fresnel_schlick(f0, vec3(s.specular), n_dot_v));
  const vec3 diffuse = (1.f - s.metallic) * (1.f - s.transmission) * (1.f - fresnel_v) * s.base;
  p.diffuse = mean3(diffuse) * below + mean3(s.sheen_color) * sheen_e * (1.f - coat_weight);

  p.transmission = mean3(pbr_transmission_weight(s, n_dot_v, coat_n_dot_v));

  const float total = p.diffuse + p.specular + p.coat + p.transmission;
  if (!(total > 0.f)) return PbrLobeProbabilities{};
  p.diffuse /= total;
  p.specular /= total;
  p.coat /= total;
  p.transmission /= total;
  return p;
}

BrdfSample sample_pbr(const PbrSurface& s, vec3 n, vec3 v, vec3 u3) {
  BrdfSample out;
  const LobeSetup L = lobe_setup(s, n, v);
  const PbrLobeProbabilities& p = L.p;
  float u = u3.x;
  const vec2 uv(u3.y, u3.z);

  if (u < p.transmission) {
    out.direction = -v;
    out.weight = pbr_transmission_weight(s, glm::dot(n, v), glm::dot(s.clearcoat_normal, v)) / p.transmission;
    out.pdf = p.transmission;
    out.specular_transmission = true;
    return out;
  }
  u -= p.transmission;
  // The lobe u falls in; past the end (rounding) the last lobe drawn with
  // a positive probability.
  enum class Lobe { diffuse, specular, coat } lobe;
  if (u < p.diffuse) lobe = Lobe::diffuse;
  else if (u < p.diffuse + p.specular) lobe = Lobe::specular;
  else if (p.coat > 0.f) lobe = Lobe::coat;
  else if (p.specular > 0.f) lobe = Lobe::specular;
  else if (p.diffuse > 0.f) lobe = Lobe::diffuse;
  else return out;  // nothing reflected: no sample

  vec3 l;
  if (lobe == Lobe::diffuse) {
    l = to_world(L.frame, sample_cosine_hemisphere(uv));
  } else {
    const bool coat = lobe == Lobe::coat;
    const vec3 h = to_world(coat ? L.coat_frame : L.frame,
                            sample_ggx_vndf(coat ? L.coat_v_local : L.v_local, coat ? L.coat_alpha : L.alpha, uv));
    l = 2.f * glm::dot(v, h) * h - v;  // reflect(-v, h)
  }
  l = glm::normalize(l);
  out.direction = l;
  out.diffuse = lobe == Lobe::diffuse;
  if (glm::dot(n, l) <= 0.f) return out;  // below the surface: no sample
  out.pdf = mixture_pdf(L, l);
  if (!(out.pdf > 0.f)) {
    out.pdf = 0.f;
    return out;
  }
  out.weight = pbr_reflection(s, n, v, l) / out.pdf;
  return out;
}

float pbr_pdf(const PbrSurface& s, vec3 n, vec3 v, vec3 l) {
  if (glm::dot(n, l) <= 0.f || glm::dot(n, v) <= 0.f) return 0.f;
  return mixture_pdf(lobe_setup(s, n, v), l);
}

float balance_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.f)) return 0.f;
  if (std::isinf(pdf_a)) return 1.f;
  if (std::isinf(pdf_b)) return 0.f;
  // Scaled by the larger pdf so that the sum does not overflow.
  const float m = std::max(pdf_a, pdf_b);
  return (pdf_a / m) / (pdf_a / m + pdf_b / m);
}

float power_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.f)) return 0.f;
  if (std::isinf(pdf_a)) return 1.f;
  if (std::isinf(pdf_b)) return 0.f;
  // Scaled by the larger pdf so that the squares neither overflow nor underflow.
  const float m = std::max(pdf_a, pdf_b);
  const float a = pdf_a / m, b = pdf_b / m;
  return a * a / (a * a + b * b);
}

}  // namespace rayform
