// Phong shading as the course defines it, for every format:
//   colour = ambient * K + sum over lights [ max(0, L.N) Lc * K + s Lc * Ks ]
//   R = d - 2 (d.N) N (mirror of the view ray), s = (L.R)^shininess if L.R > 0
// K is the diffuse colour, or the texture colour where the material has a
// texture and the hit has uvs (course: the texel replaces the colour; assets:
// it multiplies it), times the vertex colour. No clamping here.
#pragma once

#include "rayform/render/scene_intersect.h"

namespace rayform {

// Direction to a light and its colour arriving at point p (before shading).
struct LightSample {
  vec3 to_light;   // unit vector from p towards the light
  vec3 color;      // incident colour (after falloff / spot cone)
  float distance;  // to the light; infinity for directional lights
};

// sample_light of a point or spot light.
inline LightSample sample_local_light(const PreparedLight& pl, vec3 p) {
  const Light& l = pl.light;
  LightSample s;
  vec3 d = l.position - p;
  float dist2 = glm::dot(d, d);
  s.distance = std::sqrt(dist2);
  s.to_light = s.distance > 0.f ? d / s.distance : vec3(0.f, 0.f, 1.f);
  s.color = l.color;
  if (l.falloff > 0.f) s.color /= l.attenuation_constant + l.falloff * dist2;
  if (l.range > 0.f) {  // glTF KHR_lights_punctual smooth range window
    float r = s.distance / l.range;
    float window = std::clamp(1.f - r * r * r * r, 0.f, 1.f);
    s.color *= window * window;
  }
  if (l.kind == Light::Kind::spot) {
    const float cos_outer = pl.cos_outer, cos_inner = pl.cos_inner;
    float cd = glm::dot(-s.to_light, pl.axis);
    float k = cos_inner > cos_outer ? std::clamp((cd - cos_outer) / (cos_inner - cos_outer), 0.f, 1.f)
                                    : (cd >= cos_outer ? 1.f : 0.f);
    s.color *= k * k;
  }
  return s;
}

// The light arriving at p (directional lights inline, the others by call).
[[gnu::always_inline]] inline LightSample sample_light(const PreparedLight& pl, vec3 p) {
  if (pl.light.kind == Light::Kind::directional) return {pl.to_light, pl.light.color, infinity};
  return sample_local_light(pl, p);
}

// Surface colour K (diffuse colour or texel) of a hit, with its alpha.
inline vec4 surface_albedo(const PreparedScene& p, const Material& m, const SurfacePoint& sp) {
  vec4 k(m.diffuse, 1.f);
  if (m.diffuse_texture >= 0 && sp.has_uv) {
    vec2 uv = sp.uv;
    if (!m.uv_transform.is_identity()) uv = m.uv_transform.apply(uv);
    vec4 texel = sample_texture(p.textures[m.diffuse_texture], uv);
    k = m.texture_modulates ? k * texel : texel;
  }
  return vec4(vec3(k) * sp.color, k.a);
}

// Diffuse term of one light.
inline vec3 diffuse_light(vec3 k, vec3 n, const LightSample& ls) {
  return std::max(0.f, glm::dot(ls.to_light, n)) * ls.color * k;
}

// Phong terms of one light (diffuse + specular), for view direction d (unit);
// no highlight for a material without one (Material::specular_highlight).
inline vec3 phong_light(const Material& m, vec3 k, vec3 n, vec3 d, const LightSample& ls) {
  vec3 c = diffuse_light(k, n, ls);
  if (m.specular_highlight && m.specular != vec3(0.f)) {
    vec3 r = d - 2.f * glm::dot(d, n) * n;
    float lr = glm::dot(ls.to_light, r);
    if (lr > 0.f) c += std::pow(lr, m.shininess) * ls.color * m.specular;
  }
  return c;
}

}  // namespace rayform
