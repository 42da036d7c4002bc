// The integrator: the colour seen along a ray, by the course's recursive
// (Whitted) ray tracing with Phong shading (shade_phong.h): the closest hit
// that is not skipped, its lights (with shadow rays when asked), and mirror
// reflection and refraction up to RenderOptions::bounces. One per render
// path: its template switches remove the tests a prepared scene does not need.
#pragma once

#include "rayform/geometry/ray_offset.h"
#include "rayform/math/perlin_noise.h"
#include "rayform/render/cube_map.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/render/shade_phong.h"

#include <algorithm>
#include <cmath>

namespace rayform {

// The index of refraction outside every object (air): camera rays start in
// it, and a ray leaving a refractive object passes into it.
inline constexpr float outside_index = 1.f;

// Compile-time switches of a render path. The generic path has all of them
// on; a specialised path turns off what the prepared scene does not use, so
// its per-ray work skips those tests. Every switch only removes work whose
// contribution is exactly zero for such scenes, so both paths give the same
// image (checked by tests).
template <bool Textures, bool Specular, bool Skips>
struct WhittedIntegrator {
  const PreparedScene& prepared;
  const RenderOptions& options;
  const Scene& scene;
  // Whether shading may start rays at a hit (shadows, reflections, refractions).
  bool spawns_rays = options.shadows || (Specular && options.bounces > 0);
  // What shading needs of a hit point: a start for rays, the point for
  // point and spot lights, or nothing for directional lights alone.
  HitPoint hit_point = spawns_rays ? HitPoint::spawn
                       : prepared.features.noise || std::any_of(prepared.lights.begin(), prepared.lights.end(),
                                                                [](const PreparedLight& l) {
                                                                  return l.light.kind != Light::Kind::directional;
                                                                })
                           ? HitPoint::point
                           : HitPoint::none;
  // Shadow rays ask for the closest hit (some material's back faces cast no
  // shadow, Material::back_faces_cast_shadows) rather than any hit.
  bool closest_shadows = prepared.features.back_face_shadow_gaps;

  vec3 miss(const Ray& ray) const {
    return prepared.features.cube_map ? sample_cube_map(prepared.cube_map, ray.direction) : scene.background.color;
  }

  vec4 albedo(const Material& m, const SurfacePoint& sp) const {
    if constexpr (Textures) return surface_albedo(prepared, m, sp);
    else return vec4(m.diffuse * sp.color, 1.f);
  }

  // Closest hit that is neither a cut-out hole (alpha below the material's
  // cutoff) nor the back face of a single-sided material: those the ray passes.
  bool closest(Ray ray, Hit* hit, SurfacePoint* sp, vec4* k) const {
    return closest_from(ray, intersect_scene(prepared, ray, hit), hit, sp, k);
  }

  // The same, given the ray's first hit (`found`, *hit) from intersect_scene
  // or its eight-ray form.
  bool closest_from(Ray ray, bool found, Hit* hit, SurfacePoint* sp, vec4* k) const {
    for (bool first = true;; first = false) {
      if (!first) found = intersect_scene(prepared, ray, hit);
      if (!found) return false;
      *sp = surface_point(prepared, ray, *hit, hit_point);
      const Material& m = prepared.materials[sp->material];
      if constexpr (Skips) {
        if (!m.double_sided && glm::dot(ray.direction, sp->geometric_normal) > 0.f) {
          ray.tmin = next_float_up(hit->t);
          continue;
        }
      }
      *k = albedo(m, *sp);
      if constexpr (Skips) {
        if (m.alpha_cutoff >= 0.f && k->a < m.alpha_cutoff) {
          ray.tmin = next_float_up(hit->t);
          continue;
        }
      }
      // Two-sided lighting: a back face is shaded as seen from its side.
      if (m.two_sided_lighting && m.refraction_index == 0.f && glm::dot(ray.direction, sp->geometric_normal) > 0.f)
        sp->normal = -sp->normal;
      return true;
    }
  }

  // Whether something blocks the way from the hit point to the light: any
  // surface, or with closest_shadows the closest one unless its material lets
  // back faces pass and it is seen from behind (its normal . the direction to
  // the light >= 0).
  bool blocked(const SurfacePoint& sp, const Light& l, const LightSample& ls) const {
    Ray shadow = l.kind == Light::Kind::directional
                     ? spawn_ray(sp.position, sp.position_error, sp.geometric_normal, ls.to_light)
                     : spawn_ray_to(sp.position, sp.position_error, sp.geometric_normal, l.position);
    return closest_shadows ? blocked_by_closest(shadow, ls) : occluded(prepared, shadow);
  }

  // The closest-hit form of blocked (out of line: the any-hit path above
  // stays as small as it was).
  [[gnu::noinline]] bool blocked_by_closest(const Ray& shadow, const LightSample& ls) const {
    Hit h;
    if (!intersect_scene(prepared, shadow, &h)) return false;
    const SurfacePoint blocker = surface_point(prepared, shadow, h, HitPoint::none);
    return prepared.materials[blocker.material].back_faces_cast_shadows || glm::dot(blocker.normal, ls.to_light) < 0.f;
  }

  // The colour seen along a ray travelling in a medium of index `medium`
  // (camera rays: outside_index), and whether it hit a surface (*hit; for coverage).
  vec3 radiance(const Ray& ray, int depth, bool* hit, float medium = outside_index) const {
    Hit h;
    SurfacePoint sp;
    vec4 k(0.f);
    *hit = closest(ray, &h, &sp, &k);
    if (!*hit) return miss(ray);
    return shade(ray, sp, vec3(k), depth, medium);
  }

  vec3 shade(const Ray& ray, const SurfacePoint& sp, vec3 k, int depth, float medium = outside_index) const {
    const Material& m = prepared.materials[sp.material];
    if (m.unlit) return k;
    // The unit view direction, for highlights and secondary rays only.
    vec3 d(0.f);
    if constexpr (Specular) d = glm::normalize(ray.direction);
    vec3 c = scene.background.ambient * k + m.emission;
    // The colour of the diffuse term: K, or the material's solid noise (the
    // ambient term above keeps K).
    const vec3 kd = m.noise.enabled ? noise_color(m.noise, sp.position) : k;
    for (const PreparedLight& l : prepared.lights) {
      LightSample ls = sample_light(l, sp.position);
      if (options.shadows && blocked(sp, l.light, ls)) continue;
      if constexpr (Specular) c += phong_light(m, kd, sp.normal, d, ls);
      else c += diffuse_light(kd, sp.normal, ls);
    }
    if constexpr (Specular) {
      if (depth < options.bounces && m.specular != vec3(0.f)) c += m.specular * secondary(sp, m, d, depth, medium);
    }
    return c;
  }

  static vec3 noise_color(const SolidNoise& n, vec3 p) {
    const float w = course_noise_weight(p, n.octaves, n.frequency, n.amplitude);
    return w * n.color1 + (1.f - w) * n.color2;
  }

  // Mirror reflection, or for refractive materials the Fresnel-weighted
  // (Schlick) sum of reflection and refraction (Snell; total internal
  // reflection reflects all). The ray arrives through a medium of index
  // `medium` (ni); entering the surface (against its geometric normal) it
  // passes into the material's index, leaving it into index 1 (nt). The
  // reflected ray stays in ni, the refracted one carries nt.
  vec3 secondary(const SurfacePoint& sp, const Material& m, vec3 d, int depth, float medium) const {
    vec3 n = sp.normal;
    vec3 reflected = d - 2.f * glm::dot(d, n) * n;
    auto trace_dir = [&](vec3 w, float in_medium) {
      bool hit;
      return radiance(spawn_ray(sp.position, sp.position_error, sp.geometric_normal, w), depth + 1, &hit, in_medium);
    };
    if (!(m.refraction_index > 0.f)) return trace_dir(reflected, medium);
    const bool entering = glm::dot(d, sp.geometric_normal) < 0.f;
    const float ni = medium, nt = entering ? m.refraction_index : outside_index;
    const float eta = ni / nt;
    vec3 ns = entering ? n : -n;
    float cos_i = std::clamp(-glm::dot(d, ns), 0.f, 1.f);
    float sin2_t = eta * eta * std::max(0.f, 1.f - cos_i * cos_i);
    if (sin2_t >= 1.f) return trace_dir(reflected, ni);  // total internal reflection
    float cos_t = std::sqrt(1.f - sin2_t);
    vec3 refracted = eta * d + (eta * cos_i - cos_t) * ns;
    float r0 = (nt - ni) / (nt + ni);
    r0 *= r0;
    // Schlick's cosine: of the angle on the side of the lower index.
    float cos_outside = ni <= nt ? cos_i : cos_t;
    float fresnel = r0 + (1.f - r0) * std::pow(1.f - cos_outside, 5.f);
    return fresnel * trace_dir(reflected, ni) + (1.f - fresnel) * trace_dir(refracted, nt);
  }
};

}  // namespace rayform
