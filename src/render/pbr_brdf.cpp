#include "rayform/render/pbr_brdf.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rayform {
namespace {

// (1 - cos)^5, cos clamped to [0, 1].
float schlick_weight(float cos_theta) {
  float m = std::clamp(1.f - cos_theta, 0.f, 1.f);
  float m2 = m * m;
  return m2 * m2 * m;
}

// The coat's Fresnel at normal incidence: a dielectric of ior 1.5.
constexpr float coat_f0 = 0.04f;

// Conty Estevez and Kulla's fit of the sheen's Lambda, ln Lambda(x) for
// x = cos theta <= 1/2: a / (1 + b x^c) + d x + e, the coefficients
// interpolated between their fits at alpha = 0 and alpha = 1 by (1 - alpha)^2
// (the values KHR_materials_sheen gives).
float sheen_lambda_exponent(float x, float alpha) {
  float t = (1.f - alpha) * (1.f - alpha);
  auto fit = [t](float at_alpha_1, float at_alpha_0) { return at_alpha_1 + (at_alpha_0 - at_alpha_1) * t; };
  float a = fit(21.5473f, 25.3245f), b = fit(3.82987f, 3.32435f), c = fit(0.19823f, 0.16801f);
  float d = fit(-1.97760f, -1.27393f), e = fit(-4.32054f, -4.85967f);
  return a / (1.f + b * std::pow(x, c)) + d * x + e;
}

float sheen_lambda(float cos_theta, float alpha) {
  float x = std::abs(cos_theta);
  if (x < 0.5f) return std::exp(sheen_lambda_exponent(x, alpha));
  return std::exp(2.f * sheen_lambda_exponent(0.5f, alpha) - sheen_lambda_exponent(1.f - x, alpha));
}

// A function of (n.v, roughness) tabulated on a 32 x 32 grid: n.v at the
// cell centres (i + 1/2) / 32 (the end cells are flat beyond them: n.v = 0
// itself is where the sheen's visibility is infinite), roughness at j / 31
// (0 and 1 included), read bilinearly.
constexpr int table_size = 32;

float table_n_dot_v(int i) { return (float(i) + 0.5f) / float(table_size); }
float table_roughness(int j) { return float(j) / float(table_size - 1); }

struct Table2D {
  std::array<float, table_size * table_size> values{};  // [i * table_size + j]: n.v row i, roughness column j
  float& at(int i, int j) { return values[size_t(i) * table_size + size_t(j)]; }
  float at(int i, int j) const { return values[size_t(i) * table_size + size_t(j)]; }
  float lookup(float n_dot_v, float roughness) const {
    float x = std::clamp(n_dot_v * float(table_size) - 0.5f, 0.f, float(table_size - 1));
    float y = std::clamp(roughness, 0.f, 1.f) * float(table_size - 1);
    int i = std::min(int(x), table_size - 2), j = std::min(int(y), table_size - 2);
    float tx = x - float(i), ty = y - float(j);
    float top = at(i, j) + (at(i, j + 1) - at(i, j)) * ty;
    float bottom = at(i + 1, j) + (at(i + 1, j + 1) - at(i + 1, j)) * ty;
    return top + (bottom - top) * tx;
  }
};

// The view direction in the table's frame (n = +z) at n.v = n_dot_v.
vec3 table_view(float n_dot_v) { return vec3(std::sqrt(std::max(0.f, 1.f - n_dot_v * n_dot_v)), 0.f, n_dot_v); }

struct SplitSumTables {
  Table2D a, b;
};

// A and B of ggx_split_sum, integrated over the half vector h distributed as
// D(h) (n.h) (pdf of l = D (n.h) / (4 v.h)) on a stratified 64 x 32 grid of
// midpoints (the azimuth over [0, pi]: the integrand is symmetric about the
// plane of n and v). Each point weighs f cos / pdf = 4 V (n.l) (v.h) / (n.h)
// times 1 - (1 - v.h)^5 (A) or (1 - v.h)^5 (B).
SplitSumTables integrate_split_sum() {
  constexpr int polar_steps = 64, azimuth_steps = 32;
  std::array<float, azimuth_steps> cos_phi{}, sin_phi{};
  for (int q = 0; q < azimuth_steps; ++q) {
    cos_phi[size_t(q)] = std::cos(pi * (float(q) + 0.5f) / float(azimuth_steps));
    sin_phi[size_t(q)] = std::sin(pi * (float(q) + 0.5f) / float(azimuth_steps));
  }
  SplitSumTables t;
  for (int i = 0; i < table_size; ++i) {
    float n_dot_v = table_n_dot_v(i);
    vec3 v = table_view(n_dot_v);
    for (int j = 0; j < table_size; ++j) {
      float alpha = ggx_alpha(table_roughness(j));
      float alpha2 = alpha * alpha;
      double sum_a = 0, sum_b = 0;
      for (int p = 0; p < polar_steps; ++p) {
        float xi = (float(p) + 0.5f) / float(polar_steps);
        float cos2 = (1.f - xi) / (1.f + (alpha2 - 1.f) * xi);
        float cos_h = std::sqrt(cos2), sin_h = std::sqrt(std::max(0.f, 1.f - cos2));
        for (int q = 0; q < azimuth_steps; ++q) {
          vec3 h(sin_h * cos_phi[size_t(q)], sin_h * sin_phi[size_t(q)], cos_h);
          float v_dot_h = glm::dot(v, h);
          if (v_dot_h <= 0.f) continue;
          float n_dot_l = 2.f * v_dot_h * cos_h - n_dot_v;  // l = 2 (v.h) h - v
          if (n_dot_l <= 0.f) continue;
          float weight = 4.f * smith_visibility(n_dot_l, n_dot_v, alpha) * n_dot_l * v_dot_h / cos_h;
          float s = schlick_weight(v_dot_h);
          sum_a += double(weight * (1.f - s));
          sum_b += double(weight * s);
        }
      }
      double count = double(polar_steps) * azimuth_steps;
      t.a.at(i, j) = float(sum_a / count);
      t.b.at(i, j) = float(sum_b / count);
    }
  }
  return t;
}

const SplitSumTables& split_sum_tables() {
  static const SplitSumTables tables = integrate_split_sum();  // thread-safe initialisation
  return tables;
}

// E_sheen over the hemisphere of l on a 64 x 32 midpoint grid in (theta_l,
// phi_l), the azimuth over [0, pi] (symmetric about the plane of n and v):
// sum of D V (n.l) sin(theta_l) dtheta dphi, doubled. Lambda(n.v) and
// Lambda(n.l) are computed once per table entry and grid row.
Table2D integrate_sheen_albedo() {
  constexpr int polar_steps = 64, azimuth_steps = 32;
  const float d_theta = 0.5f * pi / float(polar_steps), d_phi = pi / float(azimuth_steps);
  std::array<float, azimuth_steps> cos_phi{}, sin_phi{};
  for (int q = 0; q < azimuth_steps; ++q) {
    cos_phi[size_t(q)] = std::cos((float(q) + 0.5f) * d_phi);
    sin_phi[size_t(q)] = std::sin((float(q) + 0.5f) * d_phi);
  }
  Table2D t;
  for (int i = 0; i < table_size; ++i) {
    float n_dot_v = table_n_dot_v(i);
    vec3 v = table_view(n_dot_v);
    for (int j = 0; j < table_size; ++j) {
      float alpha = sheen_alpha(table_roughness(j));
      float lambda_v = sheen_lambda(n_dot_v, alpha);
      double sum = 0;
      for (int p = 0; p < polar_steps; ++p) {
        float theta = (float(p) + 0.5f) * d_theta;
        float n_dot_l = std::cos(theta), sin_l = std::sin(theta);
        float visibility = 1.f / ((1.f + lambda_v + sheen_lambda(n_dot_l, alpha)) * 4.f * n_dot_v * n_dot_l);
        double row = 0;
        for (int q = 0; q < azimuth_steps; ++q) {
          vec3 l(sin_l * cos_phi[size_t(q)], sin_l * sin_phi[size_t(q)], n_dot_l);
          row += double(charlie_distribution(glm::normalize(v + l).z, alpha));
        }
        sum += row * double(visibility * n_dot_l * sin_l);
      }
      t.at(i, j) = float(2.0 * sum * double(d_theta) * double(d_phi));
    }
  }
  return t;
}

const Table2D& sheen_albedo_table() {
  static const Table2D table = integrate_sheen_albedo();  // thread-safe initialisation
  return table;
}

// The sheen's scaling of the layers below it seen at n.v (1 - max_component(sheen) E).
float sheen_scaling(const PbrSurface& s, float n_dot_x) {
  return std::clamp(1.f - max_component(s.sheen_color) * sheen_directional_albedo(n_dot_x, s.sheen_roughness), 0.f,
                    1.f);
}

bool has_sheen(const PbrSurface& s) { return max_component(s.sheen_color) > 0.f; }

// Fc at |n_c.v| (the extension's fresnel_coat takes abs(VdotNc)).
float coat_fresnel(float coat_n_dot_v) { return coat_f0 + (1.f - coat_f0) * schlick_weight(std::abs(coat_n_dot_v)); }

}  // namespace

float ggx_alpha(float roughness) { return std::max(roughness * roughness, min_ggx_alpha); }

float ggx_distribution(float n_dot_h, float alpha) {
  if (n_dot_h <= 0.f) return 0.f;
  float alpha2 = alpha * alpha;
  float d = n_dot_h * n_dot_h * (alpha2 - 1.f) + 1.f;
  return alpha2 / (pi * d * d);
}

float smith_visibility(float n_dot_l, float n_dot_v, float alpha) {
  float alpha2 = alpha * alpha;
  float nl = std::abs(n_dot_l), nv = std::abs(n_dot_v);
  float ggx_v = nl * std::sqrt(nv * nv * (1.f - alpha2) + alpha2);
  float ggx_l = nv * std::sqrt(nl * nl * (1.f - alpha2) + alpha2);
  float sum = ggx_v + ggx_l;
  return sum > 0.f ? 0.5f / sum : 0.f;
}

vec3 fresnel_schlick(vec3 f0, vec3 f90, float cos_theta) { return f0 + (f90 - f0) * schlick_weight(cos_theta); }

vec3 dielectric_f0(const PbrSurface& s) {
  float r = (s.ior - 1.f) / (s.ior + 1.f);
  return glm::min(r * r * s.specular_color, vec3(1.f)) * s.specular;
}

float sheen_alpha(float sheen_roughness) { return std::max(sheen_roughness * sheen_roughness, min_sheen_alpha); }

float charlie_distribution(float n_dot_h, float alpha) {
  float sin2 = std::max(0.f, 1.f - n_dot_h * n_dot_h);
  float inv_alpha = 1.f / alpha;
  return (2.f + inv_alpha) * std::pow(sin2, 0.5f * inv_alpha) / (2.f * pi);
}

float charlie_visibility(float n_dot_l, float n_dot_v, float alpha) {
  float nl = std::abs(n_dot_l), nv = std::abs(n_dot_v);
  float denominator = (1.f + sheen_lambda(nv, alpha) + sheen_lambda(nl, alpha)) * 4.f * nv * nl;
  return denominator > 0.f ? 1.f / denominator : 0.f;
}

float sheen_directional_albedo(float n_dot_v, float sheen_roughness) {
  return sheen_albedo_table().lookup(n_dot_v, sheen_roughness);
}

vec2 ggx_split_sum(float n_dot_v, float roughness) {
  const SplitSumTables& t = split_sum_tables();
  return vec2(t.a.lookup(n_dot_v, roughness), t.b.lookup(n_dot_v, roughness));
}

vec3 pbr_reflection(const PbrSurface& s, vec3 n, vec3 v, vec3 l) {
  float n_dot_l = glm::dot(n, l), n_dot_v = glm::dot(n, v);
  if (n_dot_l <= 0.f || n_dot_v <= 0.f) return vec3(0.f);
  vec3 h = glm::normalize(v + l);
  float n_dot_h = glm::dot(n, h);
  float v_dot_h = std::abs(glm::dot(v, h));

  float alpha = ggx_alpha(s.roughness);
  float specular_lobe = ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
  vec3 f_dielectric_fresnel = fresnel_schlick(dielectric_f0(s), vec3(s.specular), v_dot_h);
  vec3 f_dielectric = f_dielectric_fresnel * specular_lobe +
                      (1.f - max_component(f_dielectric_fresnel)) * (1.f - s.transmission) * s.base / pi;
  vec3 f_metal = fresnel_schlick(s.base, vec3(1.f), v_dot_h) * specular_lobe;
  vec3 f = glm::mix(f_dielectric, f_metal, s.metallic);

  if (has_sheen(s)) {
    float sheen_a = sheen_alpha(s.sheen_roughness);
    float sheen_lobe = charlie_distribution(n_dot_h, sheen_a) * charlie_visibility(n_dot_l, n_dot_v, sheen_a);
    f = s.sheen_color * sheen_lobe + f * std::min(sheen_scaling(s, n_dot_v), sheen_scaling(s, n_dot_l));
  }
  vec3 reflected = f * n_dot_l;

  if (s.clearcoat > 0.f) {
    vec3 nc = s.clearcoat_normal;
    float coat_n_dot_v = glm::dot(nc, v), coat_n_dot_l = glm::dot(nc, l);
    float coat_weight = s.clearcoat * coat_fresnel(coat_n_dot_v);
    float coat = 0.f;
    if (coat_n_dot_v > 0.f && coat_n_dot_l > 0.f) {
      float coat_alpha = ggx_alpha(s.clearcoat_roughness);
      coat = ggx_distribution(glm::dot(nc, h), coat_alpha) * smith_visibility(coat_n_dot_l, coat_n_dot_v, coat_alpha) *
             coat_n_dot_l;
    }
    reflected = reflected * (1.f - coat_weight) + vec3(coat_weight * coat);
  }
  return reflected;
}

vec3 pbr_specular_albedo(const PbrSurface& s, float n_dot_v) { return pbr_specular_albedo(s, n_dot_v, n_dot_v); }

vec3 pbr_specular_albedo(const PbrSurface& s, float n_dot_v, float coat_n_dot_v) {
  n_dot_v = std::abs(n_dot_v);
  coat_n_dot_v = std::abs(coat_n_dot_v);
  vec2 ab = ggx_split_sum(n_dot_v, s.roughness);
  vec3 dielectric = dielectric_f0(s) * ab.x + vec3(s.specular * ab.y);
  vec3 metal = s.base * ab.x + vec3(ab.y);
  vec3 albedo = glm::mix(dielectric, metal, s.metallic);
  if (has_sheen(s)) albedo *= sheen_scaling(s, n_dot_v);
  if (s.clearcoat > 0.f) {
    vec2 coat_ab = ggx_split_sum(coat_n_dot_v, s.clearcoat_roughness);
    float coat_weight = s.clearcoat * coat_fresnel(coat_n_dot_v);
    albedo = albedo * (1.f - coat_weight) + vec3(coat_weight * (coat_ab.x + coat_ab.y));
  }
  return albedo;
}

vec3 pbr_transmission_weight(const PbrSurface& s, float n_dot_v) {
  return pbr_transmission_weight(s, n_dot_v, n_dot_v);
}

vec3 pbr_transmission_weight(const PbrSurface& s, float n_dot_v, float coat_n_dot_v) {
  if (s.transmission <= 0.f || s.metallic >= 1.f) return vec3(0.f);
  n_dot_v = std::abs(n_dot_v);
  float reflected = max_component(fresnel_schlick(dielectric_f0(s), vec3(s.specular), n_dot_v));
  vec3 weight = s.transmission * (1.f - s.metallic) * (1.f - reflected) * s.base;
  if (has_sheen(s)) weight *= sheen_scaling(s, n_dot_v);
  if (s.clearcoat > 0.f) weight *= 1.f - s.clearcoat * coat_fresnel(coat_n_dot_v);
  return weight;
}

}  // namespace rayform
