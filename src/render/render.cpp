#include "rayform/render/render.h"

#include "rayform/geometry/ray_offset.h"
#include "rayform/image/color.h"
#include "rayform/image/quantize.h"
#include "rayform/math/perlin_noise.h"
#include "rayform/render/camera_rays.h"
#include "rayform/render/cube_map.h"
#include "rayform/render/render_memory.h"
#include "rayform/render/shade_phong.h"
#include "rayform/base/error.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace rayform {
namespace {

// The index of refraction outside every object (air): camera rays start in
// it, and a ray leaving a refractive object passes into it.
inline constexpr float outside_index = 1.f;

// Compile-time switches of a render path. The generic path has all of them
// on; a specialised path turns off what the prepared scene does not use, so
// its per-ray work skips those tests. Every switch only removes work whose
// contribution is exactly zero for such scenes, so both paths give the same
// image (checked by tests).
template <bool Textures, bool Specular, bool Skips>
struct Tracer {
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

// Adaptive sampling's sums over one pixel's samples so far: all of them,
// those that hit a surface, and the running mean and sum of squared
// deviations (Welford) of their values in the output encoding.
struct AdaptiveState {
  vec3 sum{0.f}, hit_sum{0.f}, mean{0.f}, m2{0.f};
  float covered = 0.f;
  int n = 0;
};

struct PixelOut {
  vec3 color{0.f};
  float depth = infinity;
  vec3 normal{0.f};
  vec3 albedo{0.f};
  float coverage = 0.f;
};

// One sample of an 8-bit output: sRGB-encoded when `srgb` (the quantizer of
// ColorFormat::srgb8, fetched once per render) is given, else as it is.
[[gnu::always_inline]] inline uint8_t quantize_sample(const SrgbQuantizer* srgb, float v) {
  return srgb ? (*srgb)(v) : quantize_unit(v);
}

// One pixel's colour into the buffer of the chosen format.
[[gnu::always_inline]] inline void store_color(ColorFormat format, const SrgbQuantizer* srgb, Image& linear,
                                               Image8& quantised, uint32_t pixel, vec3 c) {
  const size_t i = size_t(pixel) * 3;
  if (format == ColorFormat::linear_float)
    for (int k = 0; k < 3; ++k) linear.pixels[i + k] = c[k];
  else
    for (int k = 0; k < 3; ++k) quantised.pixels[i + k] = quantize_sample(srgb, c[k]);
}

// Renders every tile (next == nullptr) or those *next hands out.
template <bool Textures, bool Specular, bool Skips>
void render_tiles(const PreparedScene& p, const RenderOptions& o, RenderResult& res, const NextTile* next) {
  const Scene& s = *p.scene;
  const int width = o.width, height = o.height;
  const CameraFrame frame = make_camera_frame(s.cameras[o.camera], width, height);
  // Pixel-centre rays of a perspective camera from per-column and per-row terms.
  const std::optional<PixelCentreRays> centre_rays =
      frame.orthographic ? std::nullopt : std::optional<PixelCentreRays>(std::in_place, frame, width, height);
  // The ray through the centre of pixel (i, j) (j from the bottom): camera_ray(frame, i, j).
  auto centre_ray = [&](int i, int j) {
    return centre_rays ? centre_rays->ray(i, j) : camera_ray(frame, float(i), float(j));
  };
  const Tracer<Textures, Specular, Skips> tracer{p, o, s};
  const bool aovs = o.depth || o.normals || o.albedo;
  const bool alpha = o.alpha != AlphaMode::none, premultiplied = o.alpha == AlphaMode::premultiplied;
  const TileGrid layout = tile_grid(o);
  const int tiles = layout.count();
  const bool grid = o.grid.on(), adaptive = !grid && o.target_error.has_value();
  // One ray through each pixel centre (the course's default): the fast paths below.
  const bool centre_only = !grid && !adaptive && o.spp <= 1 && o.sampler == PixelSampler::stratified;
  // Grid anti-aliasing renders all tiles twice (samples, then filtered
  // pixels), adaptive sampling too (first rounds, then the rest).
  const int progress_steps = grid || adaptive ? 2 * tiles : tiles;
  std::atomic<int> done{0};
  std::atomic<uint64_t> adaptive_samples{0};
  std::mutex progress_mutex;
  auto tile_done = [&] {
    if (!o.progress) return;
    int n = ++done;
    std::lock_guard lock(progress_mutex);
    o.progress(float(n) / float(progress_steps));
  };

  // Camera rays of a scene that is one mesh go through it eight at a time
  // (the same hits as one by one).
  const int sole_mesh = o.packets ? sole_mesh_instance(p) : -1;

  // The first hit of a camera ray gives the per-pixel outputs.
  auto shade_primary = [&](const Ray& ray, bool found, Hit hit, PixelOut& px) {
    SurfacePoint sp;
    vec4 k(0.f);
    if (!tracer.closest_from(ray, found, &hit, &sp, &k)) {
      px.color = premultiplied ? vec3(0.f) : tracer.miss(ray);
      return;
    }
    px.coverage = 1.f;
    px.depth = hit.t;
    px.normal = sp.normal;
    px.albedo = vec3(k);
    px.color = tracer.shade(ray, sp, vec3(k), 0);
  };
  auto trace_primary = [&](const Ray& ray, PixelOut& px) {
    Hit hit;
    const bool found = intersect_scene(p, ray, &hit);
    shade_primary(ray, found, hit, px);
  };
  const SrgbQuantizer* srgb = o.color_format == ColorFormat::srgb8 ? &srgb_quantizer() : nullptr;
  auto store = [&](uint32_t pixel, const PixelOut& px) {
    store_color(o.color_format, srgb, res.color, res.color8, pixel, px.color);
    if (o.depth) res.depth[pixel] = px.depth;
    if (o.normals) res.normals[pixel] = px.normal;
    if (o.albedo) store_color(o.color_format, srgb, res.albedo, res.albedo8, pixel, px.albedo);
    if (alpha) res.coverage[pixel] = px.coverage;
  };

  // A camera ray that hits nothing shows the background; without a cube map
  // that is one value, whose 8-bit form is quantised once (most pixels of an
  // asset framed by its bounds are background). Its coverage is 0, as
  // allocated.
  PixelOut background;
  background.color = premultiplied ? vec3(0.f) : s.background.color;
  const bool background_bytes = !p.features.cube_map && !aovs && o.color_format != ColorFormat::linear_float;
  unsigned char background8[3] = {};
  for (int k = 0; k < 3; ++k) background8[k] = quantize_sample(srgb, background.color[k]);

  // A pixel's colour from the sums over its samples: sum and weight over all,
  // hit_sum and covered over those that hit a surface (for AlphaMode).
  auto finish_samples = [&](PixelOut& px, vec3 sum, vec3 hit_sum, float weight, float covered) {
    // Every sample missed: the background itself (the average of equal
    // values, which float sums can miss by a step; an 8-bit output then
    // shows exactly the background's bytes).
    px.color = covered == 0.f && !p.features.cube_map ? background.color : sum / weight;
    if (alpha) {
      px.coverage = covered / weight;
      if (premultiplied) px.color = hit_sum / weight;
      else if (covered > 0.f) px.color = hit_sum / covered;
    }
  };

  // Adaptive sampling (RenderOptions::target_error): rounds of samples
  // (adaptive_round_end: 4, 16, 32, ...) until the standard error of the
  // mean, per channel in the output encoding, is below the target (Welford's
  // running variance of the encoded values). Two passes over the tiles:
  // every pixel's first round of 4 (kept in adaptive_states, allocated once
  // before the tiles), then the rest, where a pixel the first round left
  // settled goes on when its 8 neighbours' first rounds say an edge is near:
  // to adaptive_neighbour_samples when a neighbour is not settled (an edge
  // that crosses a corner of a pixel by less than a stratum can escape its
  // first samples but not its neighbours'), to 16 when a neighbour's mean
  // differs from its own by more than the target (an edge between them may
  // cross it unseen). The second pass reads only first-round states, so no
  // pixel depends on the order of the tiles.
  const float target_variance = adaptive ? *o.target_error * *o.target_error : 0.f;
  std::vector<AdaptiveState> adaptive_states(adaptive ? size_t(width) * size_t(height) : 0);
  auto adaptive_round = [&](AdaptiveState& st, uint32_t pixel, float i, float j) {
    for (const int end = adaptive_round_end(st.n, o.max_spp); st.n < end; ++st.n) {
      const vec2 u = o.sampler == PixelSampler::random ? random_pixel_point(pixel, uint32_t(st.n))
                                                       : progressive_pixel_point(pixel, uint32_t(st.n));
      bool hit;
      const vec3 c = tracer.radiance(camera_ray(frame, i + u.x - 0.5f, j + u.y - 0.5f), 0, &hit);
      st.sum += c;
      if (hit) {
        st.covered += 1.f;
        if (alpha) st.hit_sum += c;
      }
      vec3 e = c;
      if (srgb)
        for (int k = 0; k < 3; ++k) e[k] = linear_to_srgb(std::isnan(c[k]) ? 0.f : std::clamp(c[k], 0.f, 1.f));
      const vec3 delta = e - st.mean;
      st.mean += delta / float(st.n + 1);
      st.m2 += delta * (e - st.mean);
    }
  };
  // Whether the squared standard error of the mean, m2 / (n - 1) / n, is below the target's square.
  auto settled = [&](const AdaptiveState& st) {
    return st.n >= 2 && std::max({st.m2.x, st.m2.y, st.m2.z}) < target_variance * float(st.n - 1) * float(st.n);
  };
  auto adaptive_first_tile = [&](int tile) {
    const TileRect r = layout.rect(tile);
    const int x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
        adaptive_round(adaptive_states[pixel], pixel, float(x), float(height - 1 - y));
      }
    tile_done();
  };
  auto adaptive_pixel = [&](int x, int y, PixelOut& px) -> uint64_t {
    const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
    const float i = float(x), j = float(height - 1 - y);
    AdaptiveState st = adaptive_states[pixel];  // its first round
    if (settled(st) && st.n < o.max_spp) {
      bool neighbour_unsettled = false, neighbour_differs = false;
      for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          const AdaptiveState& nb = adaptive_states[size_t(ny) * size_t(width) + size_t(nx)];
          neighbour_unsettled |= !settled(nb);
          const vec3 d = glm::abs(nb.mean - st.mean);
          neighbour_differs |= std::max({d.x, d.y, d.z}) > *o.target_error;
        }
      const int upto = neighbour_unsettled ? std::min(o.max_spp, adaptive_neighbour_samples)
                       : neighbour_differs ? adaptive_round_end(st.n, o.max_spp)
                                           : st.n;
      while (st.n < upto) adaptive_round(st, pixel, i, j);
    }
    while (st.n < o.max_spp && !settled(st)) adaptive_round(st, pixel, i, j);
    finish_samples(px, st.sum, st.hit_sum, float(st.n), st.covered);
    return uint64_t(st.n);
  };

  auto render_tile = [&](int tile) {
    // Copies of what every pixel reads, local to the tile, so that the
    // compiler need not reload them after each byte it stores.
    const bool misses_bytes = background_bytes, misses_shaded = p.features.cube_map;
    const unsigned char bg0 = background8[0], bg1 = background8[1], bg2 = background8[2];
    unsigned char* const color8 = res.color8.pixels.data();
    auto store_miss = [&](uint32_t pixel) {
      if (!misses_bytes) return store(pixel, background);
      unsigned char* out = color8 + size_t(pixel) * 3;
      out[0] = bg0;
      out[1] = bg1;
      out[2] = bg2;
    };
    const TileRect r = layout.rect(tile);
    const int x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
    uint64_t tile_samples = 0;
    if (centre_only && sole_mesh >= 0) {
      // Rows of eight pixels; a shorter end of row repeats its last ray in the unused lanes.
      // Every packet rewrites all rays, and the hits of the rays that hit (the only ones read).
      Ray rays[8];
      Hit hits[8];
      for (int y = y0; y < y1; ++y)
        for (int xs = x0; xs < x1; xs += 8) {
          const int n = std::min(8, x1 - xs);
          if (centre_rays) centre_rays->rays8(xs, n, height - 1 - y, rays);
          else
            for (int l = 0; l < 8; ++l)
              rays[l] = camera_ray(frame, float(xs + std::min(l, n - 1)), float(height - 1 - y));
          const int found = intersect_sole_mesh8(p, sole_mesh, rays, (1 << n) - 1, hits);
          const uint32_t pixel0 = uint32_t(y) * uint32_t(width) + uint32_t(xs);
          if (misses_bytes) {
            // Background bytes in all n pixels first, then the hits shaded over them.
            unsigned char* out = color8 + size_t(pixel0) * 3;
            for (int l = 0; l < n; ++l, out += 3) {
              out[0] = bg0;
              out[1] = bg1;
              out[2] = bg2;
            }
            for (int rest = found; rest;) {
              const int l = std::countr_zero(unsigned(rest));
              rest &= rest - 1;
              PixelOut px;
              shade_primary(rays[l], true, hits[l], px);
              store(pixel0 + uint32_t(l), px);
            }
            continue;
          }
          for (int l = 0; l < n; ++l) {
            const uint32_t pixel = pixel0 + uint32_t(l);
            if (!((found >> l) & 1) && !misses_shaded) {
              store_miss(pixel);
              continue;
            }
            PixelOut px;
            shade_primary(rays[l], (found >> l) & 1, hits[l], px);
            store(pixel, px);
          }
        }
    } else {
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          // Row y counts from the top; the camera's j counts from the bottom.
          const float i = float(x), j = float(height - 1 - y);
          const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
          PixelOut px;
          if (centre_only) {
            const Ray ray = centre_ray(x, height - 1 - y);
            Hit hit;
            const bool found = intersect_scene(p, ray, &hit);
            if (!found && !misses_shaded) {
              store_miss(pixel);
              continue;
            }
            shade_primary(ray, found, hit, px);
          } else if (adaptive) {
            if (aovs) trace_primary(camera_ray(frame, i, j), px);
            tile_samples += adaptive_pixel(x, y, px);
          } else {
            if (aovs) trace_primary(camera_ray(frame, i, j), px);
            // sum and weight over all samples; hit_sum and covered over
            // those that hit a surface (for AlphaMode).
            vec3 sum(0.f), hit_sum(0.f);
            float weight = 0.f, covered = 0.f;
            for (int n = 0; n < o.spp; ++n) {
              PixelSampleOffset so = pixel_sample(pixel, n, o.spp, o.filter, o.sampler);
              if (so.weight <= 0.f) continue;
              bool hit;
              const vec3 c = tracer.radiance(camera_ray(frame, i + so.offset.x, j + so.offset.y), 0, &hit);
              sum += so.weight * c;
              weight += so.weight;
              if (hit) {
                covered += so.weight;
                if (alpha) hit_sum += so.weight * c;
              }
            }
            if (weight <= 0.f) {  // no sample with weight: the centre ray alone
              bool hit;
              sum = tracer.radiance(camera_ray(frame, i, j), 0, &hit);
              weight = 1.f;
              covered = hit ? 1.f : 0.f;
              hit_sum = hit ? sum : vec3(0.f);
            }
            finish_samples(px, sum, hit_sum, weight, covered);
          }
          store(pixel, px);
        }
    }
    if (tile_samples) adaptive_samples += tile_samples;
    tile_done();
  };

  // The 3x3-sample grid (grid_filter.h): the sample image, 3W x 3H, each
  // sample's colour, whether it hit (for the background and coverage) and,
  // with alpha, its colour when it hit. Allocated once, before the tiles.
  const int grid_channels = alpha ? 7 : 4;
  const size_t grid_width = size_t(grid_samples) * size_t(width);
  std::vector<float> grid_image;
  std::vector<GridAxisWeights> grid_wx, grid_wy;
  if (grid) {
    grid_image.resize(grid_width * size_t(grid_samples) * size_t(height) * size_t(grid_channels));
    grid_wx = grid_axis_weights(width, o.grid.gaussian);
    grid_wy = grid_axis_weights(height, o.grid.gaussian);
  }
  auto grid_sample_tile = [&](int tile) {
    const TileRect r = layout.rect(tile);
    const int x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const float i = float(x), j = float(height - 1 - y);
        const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
        for (int b = 0; b < grid_samples; ++b)
          for (int a = 0; a < grid_samples; ++a) {
            const vec2 off = grid_sample_offset(pixel, a, b, o.grid.jitter);
            bool hit;
            const vec3 c = tracer.radiance(camera_ray(frame, i + off.x, j - off.y), 0, &hit);
            float* out = grid_image.data() + ((size_t(grid_samples) * size_t(y) + size_t(b)) * grid_width +
                                              size_t(grid_samples) * size_t(x) + size_t(a)) *
                                                 size_t(grid_channels);
            for (int k = 0; k < 3; ++k) out[k] = c[k];
            out[3] = hit ? 1.f : 0.f;
            if (alpha)
              for (int k = 0; k < 3; ++k) out[4 + k] = hit ? c[k] : 0.f;
          }
      }
    tile_done();
  };
  auto grid_filter_tile = [&](int tile) {
    const TileRect r = layout.rect(tile);
    const int x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
    const int sample_w = grid_samples * width, sample_h = grid_samples * height;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
        PixelOut px;
        if (aovs) trace_primary(camera_ray(frame, float(x), float(height - 1 - y)), px);
        float sums[7] = {};
        for (int ky = 0; ky < 7; ++ky) {
          const int sy = grid_samples * y - 2 + ky;
          const float wy = grid_wy[size_t(y)][size_t(ky)];
          if (sy < 0 || sy >= sample_h || wy == 0.f) continue;
          for (int kx = 0; kx < 7; ++kx) {
            const int sx = grid_samples * x - 2 + kx;
            const float w = wy * grid_wx[size_t(x)][size_t(kx)];
            if (sx < 0 || sx >= sample_w || w == 0.f) continue;
            const float* in = grid_image.data() + (size_t(sy) * grid_width + size_t(sx)) * size_t(grid_channels);
            for (int k = 0; k < grid_channels; ++k) sums[k] += w * in[k];
          }
        }
        // The weights sum to 1: the filtered colour, coverage and hit colour.
        finish_samples(px, vec3(sums[0], sums[1], sums[2]), vec3(sums[4], sums[5], sums[6]), 1.f, sums[3]);
        store(pixel, px);
      }
    tile_done();
  };

  std::unique_ptr<tbb::global_control> limit;
  if (o.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  // Every tile, each to a worker.
  auto each_tile = [&](const auto& tile_fn) {
    if (o.threads == 1) {
      for (int t = 0; t < tiles; ++t) tile_fn(t);
    } else {
      tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
        for (int t = r.begin(); t < r.end(); ++t) tile_fn(t);
      });
    }
  };
  // The tiles *next hands out (all of them without it), each to a worker.
  auto our_tiles = [&](const auto& tile_fn) {
    if (!next) return each_tile(tile_fn);
    auto work = [&] {
      for (int t; (t = (*next)()) >= 0;) {
        if (t >= tiles)
          throw Error("render: tile " + std::to_string(t) + " handed out, the image has " + std::to_string(tiles));
        tile_fn(t);
      }
    };
    if (o.threads == 1) work();
    else tbb::parallel_for(0, tbb::this_task_arena::max_concurrency(), [&](int) { work(); });
  };
  // The second pass of grid and adaptive sampling reads the first pass's
  // samples around each tile, so with tiles handed out the first pass still
  // covers the whole image (every caller makes it) and only the second is shared.
  if (grid) {
    each_tile(grid_sample_tile);
    our_tiles(grid_filter_tile);
  } else {
    if (adaptive) each_tile(adaptive_first_tile);
    our_tiles(render_tile);
  }
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  res.samples = grid       ? pixels * uint64_t(grid_samples * grid_samples)
                : adaptive ? adaptive_samples.load()
                           : pixels * uint64_t(std::max(o.spp, 1));
}

struct PathChoice {
  bool textures, specular, skips;  // skips: cut-outs or single-sided materials
};

PathChoice choose_path(const PreparedScene& p, const RenderOptions& o) {
  if (o.generic) return {true, true, true};
  return {p.features.textures, p.features.specular, p.features.alpha_cutout || p.features.single_sided};
}

// Dispatch to one of the eight compiled paths.
void render_path(const PreparedScene& p, const RenderOptions& o, RenderResult& res, const NextTile* next) {
  PathChoice c = choose_path(p, o);
  int key = (c.textures ? 4 : 0) | (c.specular ? 2 : 0) | (c.skips ? 1 : 0);
  switch (key) {
    case 0: render_tiles<false, false, false>(p, o, res, next); break;
    case 1: render_tiles<false, false, true>(p, o, res, next); break;
    case 2: render_tiles<false, true, false>(p, o, res, next); break;
    case 3: render_tiles<false, true, true>(p, o, res, next); break;
    case 4: render_tiles<true, false, false>(p, o, res, next); break;
    case 5: render_tiles<true, false, true>(p, o, res, next); break;
    case 6: render_tiles<true, true, false>(p, o, res, next); break;
    default: render_tiles<true, true, true>(p, o, res, next); break;
  }
}

}  // namespace

TileGrid tile_grid(const RenderOptions& o) { return make_tile_grid(o.width, o.height, o.tile_size); }

std::string render_path_name(const PreparedScene& p, const RenderOptions& o) {
  if (o.generic) return "generic";
  PathChoice c = choose_path(p, o);
  if (c.textures && c.specular && c.skips) return "generic";
  std::string name = "specialised (without";
  if (!c.textures) name += " textures";
  if (!c.specular) name += " specular";
  if (!c.skips) name += " cut-outs/culling";
  return name + ")";
}

std::string render_options_problem(const RenderOptions& o) {
  if (o.width <= 0 || o.height <= 0)
    return "size: width and height must be positive, got " + std::to_string(o.width) + "x" + std::to_string(o.height);
  if (o.spp < 1) return "spp: samples per pixel must be at least 1, got " + std::to_string(o.spp);
  if (o.bounces < 0) return "bounces: must not be negative, got " + std::to_string(o.bounces);
  if (o.threads < 0) return "threads: must not be negative, got " + std::to_string(o.threads);
  if (o.camera < 0) return "camera: must not be negative, got " + std::to_string(o.camera);
  if (o.target_error && !(*o.target_error > 0.f))
    return "target-error: must be a positive number, got " + std::to_string(*o.target_error);
  if (o.target_error && o.filter != PixelFilter::box) return "target-error: adaptive sampling uses the box filter";
  if (o.max_spp < 1) return "max-spp: must be at least 1, got " + std::to_string(o.max_spp);
  if (o.grid.on() && (o.spp > 1 || o.target_error))
    return std::string(o.spp > 1 ? "spp" : "target-error") +
           ": the 3x3 samples per pixel of -jitter/-filter cannot be combined with other sampling";
  return "";
}

RenderResult allocate_render_result(const PreparedScene& p, const RenderOptions& o) {
  const Scene& s = *p.scene;
  if (std::string problem = render_options_problem(o); !problem.empty()) throw Error("render: " + problem);
  if (std::string problem = render_memory_problem(o, available_memory_bytes()); !problem.empty())
    throw Error("render: " + problem);
  if (o.camera >= int(s.cameras.size()))
    throw Error("render: the scene has no camera " + std::to_string(o.camera) + " (it has " +
                std::to_string(s.cameras.size()) + ")");
  const int width = o.width, height = o.height;
  RenderResult res;
  res.width = width;
  res.height = height;
  res.color_format = o.color_format;
  auto allocate_color = [&](Image& linear, Image8& quantised) {
    if (o.color_format == ColorFormat::linear_float) linear = Image(width, height, 3);
    else quantised = Image8{width, height, 3, std::vector<unsigned char>(size_t(width) * height * 3)};
  };
  allocate_color(res.color, res.color8);
  if (o.depth) res.depth.assign(size_t(width) * height, infinity);
  if (o.normals) res.normals.assign(size_t(width) * height, vec3(0.f));
  if (o.albedo) allocate_color(res.albedo, res.albedo8);
  if (o.alpha != AlphaMode::none) res.coverage.assign(size_t(width) * height, 0.f);
  return res;
}

RenderResult render(const PreparedScene& p, const RenderOptions& o) {
  RenderResult res = allocate_render_result(p, o);
  render_path(p, o, res, nullptr);
  return res;
}

void render_tiles_from(const PreparedScene& p, const RenderOptions& o, const NextTile& next_tile, RenderResult& res) {
  if (res.width != o.width || res.height != o.height || res.color_format != o.color_format)
    throw Error("render: the result was allocated for other options");
  render_path(p, o, res, &next_tile);
}

}  // namespace rayform
