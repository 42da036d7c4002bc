// The integrator: the colour seen along a ray, by recursive (Whitted) ray
// tracing: the closest hit that is not skipped, its lights (with shadow rays
// when asked), and mirror reflection and refraction up to
// RenderOptions::bounces. A hit is shaded by its material's model: the
// course's Phong model (shade_phong.h), or glTF's metallic-roughness model
// (shade_pbr.h, pbr_brdf.h; only on the generic path, which a scene with
// such materials takes), whose blended surfaces let the rest of the ray
// through and whose volumes attenuate the light inside them. One per render
// path: its template switches remove the tests a prepared scene does not need.
#pragma once

#include "rayform/geometry/ray_offset.h"
#include "rayform/math/hash.h"
#include "rayform/math/perlin_noise.h"
#include "rayform/render/cube_map.h"
#include "rayform/render/environment_filter.h"
#include "rayform/render/environment_map.h"
#include "rayform/render/pbr_sampling.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/sampling.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/render/shade_pbr.h"
#include "rayform/render/shade_phong.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rayform {

// The seed of a camera ray's random numbers (metallic-roughness shading
// under an environment): a hash of the bits of its origin and direction, so
// that a sample's numbers are the same whatever the thread, the tile order or
// the process that traces it.
inline uint32_t ray_seed(const Ray& r) {
  const float parts[6] = {r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z};
  uint32_t h = 0x9e3779b9u;
  for (float f : parts) {
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    h = hash_bits(h ^ bits);
  }
  return h;
}

// The index of refraction outside every object (air): camera rays start in
// it, and a ray leaving a refractive object passes into it.
inline constexpr float outside_index = 1.f;

// How a ray that leaves the scene sees the environment (metallic-roughness
// shading): brdf_pdf > 0: the ray was drawn from a BRDF with that pdf, and
// the environment is weighted against its own samples (multiple importance
// sampling); blur > 0: blurred to that perceptual roughness (the reflections
// of the deterministic first picture).
struct EnvironmentLookup {
  float brdf_pdf = 0.f;
  float blur = 0.f;
};

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
  // The reflection/refraction depth traced: options.bounces, at most
  // max_bounces (render.h), which bounds the recursion below (each level
  // holds a few frames of radiance -> shade -> secondary on the stack).
  int bounces = std::min(options.bounces, max_bounces);
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
  // Whether metallic-roughness shading samples the environment's light
  // (unbiased, converging with the samples a pixel: more than one, adaptive,
  // or random sampling), or approximates it without noise (one sample at the
  // pixel's centre: the deterministic first picture).
  bool samples_environment = options.spp > 1 ||
                             options.target_error.has_value() || options.sampler == PixelSampler::random;
  // Shadow rays ask for the closest hit (some material's back faces cast no
  // shadow, Material::back_faces_cast_shadows) rather than any hit.
  bool closest_shadows = prepared.features.back_face_shadow_gaps;

  // What a ray that leaves the scene sees: the environment (for a camera
  // ray, depth 0, only where it is shown), the cube map or the background
  // colour; `lookup` says how it sees the environment.
  vec3 miss(const Ray& ray, int depth = 0, EnvironmentLookup lookup = {}) const {
    if (prepared.features.environment && (depth > 0 || prepared.features.environment_shown)) {
      const EnvironmentMap& env = prepared.environment;
      // Weighed against the environment's samples: the texel those samples
      // carry (the same integrand). Seen directly: interpolated.
      if (lookup.brdf_pdf > 0.f)
        return environment_radiance(env, ray.direction) *
               power_heuristic(lookup.brdf_pdf, environment_pdf(env, ray.direction));
      if (lookup.blur > 0.f)
        return prefiltered_radiance(prepared.prefiltered_environment, env, ray.direction, lookup.blur);
      return environment_radiance_bilinear(env, ray.direction);
    }
    return prepared.features.cube_map ? sample_cube_map(prepared.cube_map, ray.direction) : scene.background.color;
  }

  // Whether this path shades the metallic-roughness model (the generic one).
  static constexpr bool shades_pbr = Textures && Specular && Skips;

  vec4 albedo(const Material& m, const SurfacePoint& sp) const {
    if constexpr (Textures) {
      if constexpr (shades_pbr)
        if (m.model == Material::Model::metallic_roughness) return pbr_base_color(prepared, m.pbr, sp);
      return surface_albedo(prepared, m, sp);
    } else {
      return vec4(m.diffuse * sp.color, 1.f);
    }
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
  // (camera rays: outside_index), and the fraction of it that surfaces
  // cover (*coverage: 1 on a hit, 0 on a miss, between behind blended
  // surfaces; for AlphaMode).
  // `seed` and `lookup` matter to metallic-roughness shading under an
  // environment only: the random numbers of a secondary ray (camera rays
  // take theirs from the ray itself, ray_seed), and how it sees the
  // environment when it leaves the scene (miss).
  vec3 radiance(const Ray& ray, int depth, float* coverage, float medium = outside_index, uint32_t seed = 0,
                EnvironmentLookup lookup = {}) const {
    if constexpr (shades_pbr)
      if (prepared.features.blend || prepared.features.transmission)
        return radiance_layers(ray, depth, coverage, seed, lookup);
    Hit h;
    SurfacePoint sp;
    vec4 k(0.f);
    const bool hit = closest(ray, &h, &sp, &k);
    *coverage = hit ? 1.f : 0.f;
    if (!hit) return miss(ray, depth, lookup);
    return shade(ray, sp, vec3(k), depth, medium, seed);
  }

  // Whether radiance() goes through radiance_layers (blended or
  // transmissive materials): the first hit alone does not give the colour.
  bool layered() const {
    if constexpr (shades_pbr) return prepared.features.blend || prepared.features.transmission;
    else return false;
  }

  // The part of a camera ray's colour c that its covering surfaces give
  // (the background behind them left out): c on a hit, 0 on a miss.
  vec3 covered_part(const Ray& ray, vec3 c, float coverage) const {
    if (coverage >= 1.f) return c;
    if (coverage <= 0.f) return vec3(0.f);
    return c - (1.f - coverage) * miss(ray);
  }

  vec3 shade(const Ray& ray, const SurfacePoint& sp, vec3 k, int depth, float medium = outside_index,
             uint32_t seed = 0) const {
    const Material& m = prepared.materials[sp.material];
    if (m.unlit) return k;
    if constexpr (shades_pbr)
      if (m.model == Material::Model::metallic_roughness)
        return shade_pbr(ray, sp, m, k, depth, depth == 0 ? ray_seed(ray) : seed);
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
      if (depth < bounces && m.specular != vec3(0.f)) c += m.specular * secondary(sp, m, d, depth, medium);
    }
    return c;
  }

  // radiance() through the layers of a scene with blended or transmissive
  // materials: a blended hit of alpha a adds a times its colour and lets
  // 1 - a of the rest of the ray through (in ray order); a hit seen from
  // inside a volume is attenuated over the distance the ray travelled in it.
  vec3 radiance_layers(Ray ray, int depth, float* coverage, uint32_t seed, EnvironmentLookup lookup) const {
    vec3 sum(0.f);
    float through = 1.f;  // the share of the ray not yet covered
    for (;;) {
      Hit h;
      SurfacePoint sp;
      vec4 k(0.f);
      if (!closest(ray, &h, &sp, &k)) {
        *coverage = 1.f - through;
        return sum + through * miss(ray, depth, lookup);
      }
      const Material& m = prepared.materials[sp.material];
      vec3 c = shade(ray, sp, vec3(k), depth, outside_index, seed);
      const bool pbr = m.model == Material::Model::metallic_roughness;
      if (pbr && m.pbr.thickness > 0.f && glm::dot(ray.direction, sp.geometric_normal) > 0.f)
        c *= volume_transmittance(m.pbr, h.t * glm::length(ray.direction));
      const float alpha = pbr && m.pbr.alpha_mode == PbrMaterial::AlphaMode::blend ? std::clamp(k.a, 0.f, 1.f) : 1.f;
      sum += through * alpha * c;
      through *= 1.f - alpha;
      if (!(through > 0.f)) {
        *coverage = 1.f;
        return sum;
      }
      ray.tmin = next_float_up(h.t);
    }
  }

  // The share of a light's colour that reaches the hit point: 0 or 1, or
  // with blended materials the product of 1 - alpha over the blended
  // surfaces on the way (any other surface blocks). With cut-outs or
  // blending the way is followed hit by hit (closest), so that light passes
  // through the holes of a MASK texture.
  vec3 light_through(const SurfacePoint& sp, const Light& l, const LightSample& ls) const {
    if (!prepared.features.blend && !prepared.features.alpha_cutout) return blocked(sp, l, ls) ? vec3(0.f) : vec3(1.f);
    return way_through(l.kind == Light::Kind::directional
                           ? spawn_ray(sp.position, sp.position_error, sp.geometric_normal, ls.to_light)
                           : spawn_ray_to(sp.position, sp.position_error, sp.geometric_normal, l.position));
  }

  // The share of light that passes along `shadow` (light_through's rule).
  vec3 way_through(Ray shadow) const {
    if (!prepared.features.blend && !prepared.features.alpha_cutout)
      return occluded(prepared, shadow) ? vec3(0.f) : vec3(1.f);
    float through = 1.f;
    for (;;) {
      Hit h;
      SurfacePoint blocker;
      vec4 k(0.f);
      if (!closest(shadow, &h, &blocker, &k)) return vec3(through);
      const Material& m = prepared.materials[blocker.material];
      if (m.model != Material::Model::metallic_roughness || m.pbr.alpha_mode != PbrMaterial::AlphaMode::blend)
        return vec3(0.f);
      through *= 1.f - std::clamp(k.a, 0.f, 1.f);
      if (!(through > 0.f)) return vec3(0.f);
      shadow.tmin = next_float_up(h.t);
    }
  }

  // The light of the environment reflected at a metallic-roughness hit
  // towards v, by multiple importance sampling (power heuristic) of one
  // environment sample (environment_map.h, shadowed by way_through) and one
  // BRDF sample (pbr_sampling.h). The BRDF sample's ray sees the
  // environment if it leaves the scene; from a glossy or coat lobe it goes
  // on (radiance at depth + 1, up to RenderOptions::bounces), from the
  // diffuse lobe it ends there, giving only the light of an emitting
  // surface it hits (no diffuse interreflection: the `direct` light
  // transport). Random numbers: sample_random(seed, depth, 0..4).
  // The occlusion texture is not applied: the environment's visibility is
  // traced.
  vec3 environment_light(const SurfacePoint& sp, const PbrPoint& point, vec3 v, int depth, uint32_t seed) const {
    const PbrSurface& s = point.surface;
    const vec3 n = point.normal;
    const EnvironmentMap& env = prepared.environment;
    vec3 c(0.f);
    const EnvironmentSample es =
        sample_environment(env, vec2(sample_random(seed, uint32_t(depth), 0), sample_random(seed, uint32_t(depth), 1)));
    if (es.pdf > 0.f) {
      const vec3 f = pbr_reflection(s, n, v, es.direction);
      if (f != vec3(0.f) && glm::dot(es.direction, sp.geometric_normal) > 0.f) {
        const vec3 through = way_through(spawn_ray(sp.position, sp.position_error, sp.geometric_normal, es.direction));
        if (through != vec3(0.f))
          c += f * es.radiance * through * (power_heuristic(es.pdf, pbr_pdf(s, n, v, es.direction)) / es.pdf);
      }
    }
    const BrdfSample bs =
        sample_pbr(s, n, v,
                   vec3(sample_random(seed, uint32_t(depth), 2), sample_random(seed, uint32_t(depth), 3),
                        sample_random(seed, uint32_t(depth), 4)));
    // A transmission sample adds nothing here: shade_pbr traces the
    // transmitted light itself (the reflection's estimate stays unbiased).
    if (!(bs.pdf > 0.f) || bs.specular_transmission || bs.weight == vec3(0.f) ||
        glm::dot(bs.direction, sp.geometric_normal) <= 0.f)
      return c;
    const Ray r = spawn_ray(sp.position, sp.position_error, sp.geometric_normal, bs.direction);
    if (!bs.diffuse && depth < bounces) {
      float coverage;
      return c + bs.weight * radiance(r, depth + 1, &coverage, outside_index, hash_bits(seed + 2u), {bs.pdf, 0.f});
    }
    if (prepared.features.emission) {  // an emitting surface the path ends at gives its light
      Hit h;
      SurfacePoint hit;
      vec4 k(0.f);
      if (closest(r, &h, &hit, &k)) return c + bs.weight * emitted(hit);
    }
    const vec3 through = way_through(r);
    if (through != vec3(0.f)) c += bs.weight * through * miss(r, depth + 1, {bs.pdf, 0.f});
    return c;
  }

  // The radiance a surface emits at a hit (its material's emission).
  vec3 emitted(const SurfacePoint& sp) const {
    const Material& m = prepared.materials[sp.material];
    if (m.model != Material::Model::metallic_roughness) return m.emission;
    const vec3 e = m.pbr.emissive * m.pbr.emissive_strength;
    return e == vec3(0.f) ? e : e * vec3(slot_texel(prepared, m.pbr.emissive_texture, sp));
  }

  // A metallic-roughness hit: emission, the ambient light on the diffuse
  // base, each light through the BRDF (irradiance pi x the light's colour,
  // scene.h), and up to RenderOptions::bounces one mirror-direction ray
  // weighted by the specular layers' albedo and one refraction ray
  // weighted by the transmission (straight through a thin wall, bent by the
  // index into and out of a volume). The occlusion texture scales the
  // indirect light: the ambient term and the reflection ray.
  vec3 shade_pbr(const Ray& ray, const SurfacePoint& sp, const Material& m, vec3 base, int depth, uint32_t seed) const {
    const vec3 d = glm::normalize(ray.direction), v = -d;
    const bool flipped = m.two_sided_lighting && glm::dot(ray.direction, sp.geometric_normal) > 0.f;
    const PbrPoint point = pbr_point(prepared, m.pbr, sp, base, d, flipped);
    const PbrSurface& s = point.surface;
    const vec3 n = point.normal;
    vec3 c = point.emission +
             scene.background.ambient * s.base * ((1.f - s.metallic) * (1.f - s.transmission) * point.occlusion);
    for (const PreparedLight& l : prepared.lights) {
      const LightSample ls = sample_light(l, sp.position);
      const vec3 f = pbr_reflection(s, n, v, ls.to_light);
      if (f == vec3(0.f)) continue;
      vec3 through(1.f);
      if (options.shadows) {
        through = light_through(sp, l.light, ls);
        if (through == vec3(0.f)) continue;
      }
      c += f * (pi * ls.color) * through;
    }
    const float n_dot_v = std::max(glm::dot(n, v), 0.f), coat_n_dot_v = glm::dot(s.clearcoat_normal, v);
    const bool sampled = prepared.features.environment && samples_environment;
    if (sampled) {
      c += environment_light(sp, point, v, depth, seed);
    } else if (prepared.features.environment) {
      // The first picture's environment light, without noise: the diffuse
      // base under the unshadowed irradiance, darkened by the occlusion
      // texture; the specular layers by the mirror ray below.
      const float diffuse = (1.f - s.metallic) * (1.f - s.transmission) *
                            (1.f - max_component(fresnel_schlick(dielectric_f0(s), vec3(s.specular), n_dot_v)));
      c += s.base * (diffuse * point.occlusion / pi) * irradiance(prepared.environment_irradiance, n);
    }
    if (depth >= bounces) return c;
    // A ray from the hit; when it leaves the scene it sees the environment
    // blurred to `blur` (the mirror ray of a rough surface).
    auto trace_dir = [&](vec3 w, float blur) {
      float coverage;
      return radiance(spawn_ray(sp.position, sp.position_error, sp.geometric_normal, w), depth + 1, &coverage,
                      outside_index, hash_bits(seed + 1u), EnvironmentLookup{0.f, blur});
    };
    const vec3 reflected = d + 2.f * n_dot_v * n;
    // With the environment sampled the reflection is too (environment_light);
    // otherwise one mirror ray stands in for it.
    const vec3 specular = sampled ? vec3(0.f) : pbr_specular_albedo(s, n_dot_v, coat_n_dot_v) * point.occlusion;
    vec3 reflection_weight = specular;
    if (s.transmission > 0.f && s.metallic < 1.f) {
      const vec3 weight = pbr_transmission_weight(s, n_dot_v, coat_n_dot_v);
      if (weight != vec3(0.f)) {
        vec3 refracted = d;  // a thin wall: straight through
        if (point.volume && s.ior > 1.f) {
          const bool entering = glm::dot(d, sp.geometric_normal) < 0.f;
          const float eta = entering ? 1.f / s.ior : s.ior;
          const float sin2_t = eta * eta * std::max(0.f, 1.f - n_dot_v * n_dot_v);
          if (sin2_t < 1.f) refracted = eta * d + (eta * n_dot_v - std::sqrt(1.f - sin2_t)) * n;
          else refracted = vec3(0.f);  // total internal reflection: the weight goes to the reflection
        }
        if (refracted != vec3(0.f)) c += weight * trace_dir(refracted, 0.f);
        else reflection_weight += weight;
      }
    }
    if (reflection_weight != vec3(0.f)) c += reflection_weight * trace_dir(reflected, s.roughness);
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
      float coverage;
      return radiance(spawn_ray(sp.position, sp.position_error, sp.geometric_normal, w), depth + 1, &coverage,
                      in_medium);
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
