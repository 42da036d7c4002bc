// The per-tile loops of a render, one per way of sampling: for each pixel of
// a tile, the sampler's positions (sampling.h, adaptive_sampling.h,
// grid_filter.h) as camera rays, their colour from the integrator
// (whitted_integrator.h), the pixel's values into the film (film.h). Pixels
// are rows from the top; the camera's j counts from the bottom.
#pragma once

#include "rayform/render/adaptive_sampling.h"
#include "rayform/render/camera_rays.h"
#include "rayform/render/film.h"
#include "rayform/render/grid_sample_image.h"
#include "rayform/render/render.h"
#include "rayform/render/scene_intersect.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <optional>

namespace rayform {

template <class Integrator>
class TileRenderer {
 public:
  TileRenderer(const PreparedScene& p, const RenderOptions& o, const Integrator& integrator, const Film& film)
      : prepared_(p),
        options_(o),
        integrator_(integrator),
        film_(film),
        width_(o.width),
        height_(o.height),
        frame_(make_camera_frame(p.scene->cameras[size_t(o.camera)], o.width, o.height)),
        aovs_(o.depth || o.normals || o.albedo) {
    if (!frame_.orthographic) centre_rays_.emplace(frame_, width_, height_);
  }

  // One ray through each pixel centre (the course's default) for a scene
  // that is one mesh: rows of eight pixels through it at a time, the same
  // hits as one by one (intersect_sole_mesh8).
  void centre_packets(const TileRect& r, int sole_mesh) const {
    // Copies of what every pixel reads, local to the tile, so that the
    // compiler need not reload them after each byte it stores.
    const bool misses_bytes = film_.misses_are_bytes(), misses_shaded = film_.misses_shaded();
    const unsigned char* bg = film_.background_bytes();
    const unsigned char bg0 = bg[0], bg1 = bg[1], bg2 = bg[2];
    unsigned char* const color8 = film_.color8();
    // A shorter end of row repeats its last ray in the unused lanes. Every
    // packet rewrites all rays, and the hits of the rays that hit (the only ones read).
    Ray rays[8];
    Hit hits[8];
    for (int y = r.y0; y < r.y1; ++y)
      for (int xs = r.x0; xs < r.x1; xs += 8) {
        const int n = std::min(8, r.x1 - xs);
        if (centre_rays_) centre_rays_->rays8(xs, n, height_ - 1 - y, rays);
        else
          for (int l = 0; l < 8; ++l)
            rays[l] = camera_ray(frame_, float(xs + std::min(l, n - 1)), float(height_ - 1 - y));
        const int found = intersect_sole_mesh8(prepared_, sole_mesh, rays, (1 << n) - 1, hits);
        const uint32_t pixel0 = uint32_t(y) * uint32_t(width_) + uint32_t(xs);
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
            PixelValues px;
            shade_primary(rays[l], true, hits[l], px);
            film_.store(pixel0 + uint32_t(l), px);
          }
          continue;
        }
        for (int l = 0; l < n; ++l) {
          const uint32_t pixel = pixel0 + uint32_t(l);
          if (!((found >> l) & 1) && !misses_shaded) {
            film_.store(pixel, film_.background());
            continue;
          }
          PixelValues px;
          shade_primary(rays[l], (found >> l) & 1, hits[l], px);
          film_.store(pixel, px);
        }
      }
  }

  // One ray through each pixel centre, one ray at a time.
  void centres(const TileRect& r) const {
    const bool misses_bytes = film_.misses_are_bytes(), misses_shaded = film_.misses_shaded();
    const unsigned char* bg = film_.background_bytes();
    const unsigned char bg0 = bg[0], bg1 = bg[1], bg2 = bg[2];
    unsigned char* const color8 = film_.color8();
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
        const Ray ray = centre_ray(x, height_ - 1 - y);
        Hit hit;
        const bool found = intersect_scene(prepared_, ray, &hit);
        if (!found && !misses_shaded) {
          if (!misses_bytes) {
            film_.store(pixel, film_.background());
            continue;
          }
          unsigned char* out = color8 + size_t(pixel) * 3;
          out[0] = bg0;
          out[1] = bg1;
          out[2] = bg2;
          continue;
        }
        PixelValues px;
        shade_primary(ray, found, hit, px);
        film_.store(pixel, px);
      }
  }

  // RenderOptions::spp samples a pixel (pixel_sample: stratified or random,
  // box or tent filter).
  void stratified(const TileRect& r) const {
    const RenderOptions& o = options_;
    const bool alpha = film_.alpha();
    each_pixel(r, [&](int x, int y, uint32_t pixel, PixelValues& px) {
      const float i = float(x), j = float(height_ - 1 - y);
      // sum and weight over all samples; hit_sum and covered over those
      // that hit a surface (for AlphaMode).
      vec3 sum(0.f), hit_sum(0.f);
      float weight = 0.f, covered = 0.f;
      for (int n = 0; n < o.spp; ++n) {
        PixelSampleOffset so = pixel_sample(pixel, n, o.spp, o.filter, o.sampler);
        if (so.weight <= 0.f) continue;
        const Ray ray = camera_ray(frame_, i + so.offset.x, j + so.offset.y);
        float coverage;
        const vec3 c = integrator_.radiance(ray, 0, &coverage);
        sum += so.weight * c;
        weight += so.weight;
        if (coverage > 0.f) {
          covered += so.weight * coverage;
          if (alpha) hit_sum += so.weight * integrator_.covered_part(ray, c, coverage);
        }
      }
      if (weight <= 0.f) {  // no sample with weight: the centre ray alone
        const Ray ray = camera_ray(frame_, i, j);
        float coverage;
        sum = integrator_.radiance(ray, 0, &coverage);
        weight = 1.f;
        covered = coverage;
        hit_sum = integrator_.covered_part(ray, sum, coverage);
      }
      film_.finish(px, sum, hit_sum, weight, covered);
    });
  }

  // Adaptive sampling's first pass (adaptive_sampling.h): every pixel's first round.
  void adaptive_first(const TileRect& r, AdaptiveSampler& sampler) const {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const float i = float(x), j = float(height_ - 1 - y);
        sampler.first_round(x, y, [&](vec2 u) { return trace(i + u.x - 0.5f, j + u.y - 0.5f); });
      }
  }

  // Its second pass: the rest of every pixel's samples. Returns the samples taken.
  uint64_t adaptive(const TileRect& r, const AdaptiveSampler& sampler) const {
    uint64_t samples = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const float i = float(x), j = float(height_ - 1 - y);
        const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
        PixelValues px;
        if (aovs_) trace_primary(camera_ray(frame_, i, j), px);
        const AdaptiveState st = sampler.complete(x, y, [&](vec2 u) { return trace(i + u.x - 0.5f, j + u.y - 0.5f); });
        film_.finish(px, st.sum, st.hit_sum, float(st.n), st.covered);
        film_.store(pixel, px);
        samples += uint64_t(st.n);
      }
    return samples;
  }

  // The 3x3-sample grid's first pass (grid_filter.h): the tile's pixels' samples.
  void grid_sample(const TileRect& r, GridSampleImage& image) const {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const float i = float(x), j = float(height_ - 1 - y);
        const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
        for (int b = 0; b < grid_samples; ++b)
          for (int a = 0; a < grid_samples; ++a) {
            const vec2 off = grid_sample_offset(pixel, a, b, options_.grid.jitter);
            const TracedSample s = trace(i + off.x, j - off.y);
            image.set(x, y, a, b, s.color, s.coverage, s.covered);
          }
      }
  }

  // Its second pass: each pixel filtered from the samples around it.
  void grid_filter(const TileRect& r, const GridSampleImage& image) const {
    each_pixel(r, [&](int x, int y, uint32_t, PixelValues& px) {
      float sums[GridSampleImage::max_channels] = {};
      image.filter(x, y, sums);
      // The weights sum to 1: the filtered colour, coverage and hit colour.
      film_.finish(px, vec3(sums[0], sums[1], sums[2]), vec3(sums[4], sums[5], sums[6]), 1.f, sums[3]);
    });
  }

 private:
  // Every pixel (x, y) of the tile, row y from the top: value(x, y, pixel,
  // px) sets its colour and coverage in px, which holds the depth, normal
  // and albedo of the ray through the pixel's centre when they are asked
  // for; px is then stored.
  template <class PixelValueFn>
  [[gnu::always_inline]] void each_pixel(const TileRect& r, PixelValueFn&& value) const {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const uint32_t pixel = uint32_t(y) * uint32_t(width_) + uint32_t(x);
        PixelValues px;
        if (aovs_) trace_primary(camera_ray(frame_, float(x), float(height_ - 1 - y)), px);
        value(x, y, pixel, px);
        film_.store(pixel, px);
      }
  }

  // The ray through the centre of pixel (i, j) (j from the bottom): camera_ray(frame, i, j).
  Ray centre_ray(int i, int j) const {
    return centre_rays_ ? centre_rays_->ray(i, j) : camera_ray(frame_, float(i), float(j));
  }

  // The sample at continuous pixel coordinates (i, j).
  [[gnu::always_inline]] TracedSample trace(float i, float j) const {
    TracedSample s;
    const Ray ray = camera_ray(frame_, i, j);
    s.color = integrator_.radiance(ray, 0, &s.coverage);
    s.covered = integrator_.covered_part(ray, s.color, s.coverage);
    return s;
  }

  // The per-pixel outputs from the first hit of a camera ray (`found`, hit).
  void shade_primary(const Ray& ray, bool found, Hit hit, PixelValues& px) const {
    SurfacePoint sp;
    vec4 k(0.f);
    if (!integrator_.closest_from(ray, found, &hit, &sp, &k)) {
      px.color = film_.premultiplied() ? vec3(0.f) : integrator_.miss(ray);
      return;
    }
    px.coverage = 1.f;
    px.depth = hit.t;
    px.normal = sp.normal;
    px.albedo = vec3(k);
    if (integrator_.layered()) {  // what lies behind the first hit counts
      float coverage;
      const vec3 c = integrator_.radiance(ray, 0, &coverage);
      film_.finish(px, c, integrator_.covered_part(ray, c, coverage), 1.f, coverage);
      return;
    }
    px.color = integrator_.shade(ray, sp, vec3(k), 0);
  }
  void trace_primary(const Ray& ray, PixelValues& px) const {
    Hit hit;
    const bool found = intersect_scene(prepared_, ray, &hit);
    shade_primary(ray, found, hit, px);
  }

  const PreparedScene& prepared_;
  const RenderOptions& options_;
  const Integrator& integrator_;
  const Film& film_;
  int width_, height_;
  CameraFrame frame_;
  // Pixel-centre rays of a perspective camera from per-column and per-row terms.
  std::optional<PixelCentreRays> centre_rays_;
  bool aovs_;  // depth, normals or albedo asked for: from the centre ray's first hit
};

}  // namespace rayform
