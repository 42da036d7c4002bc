#include "rayform/render/render.h"

#include "rayform/base/error.h"
#include "rayform/render/adaptive_sampling.h"
#include "rayform/render/film.h"
#include "rayform/render/grid_sample_image.h"
#include "rayform/render/render_memory.h"
#include "rayform/render/tile_renderer.h"
#include "rayform/render/tile_scheduler.h"
#include "rayform/render/whitted_integrator.h"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <optional>

namespace rayform {
namespace {

// Renders every tile (next == nullptr) or those *next hands out, by one of
// the compiled paths (WhittedIntegrator's switches). Grid and adaptive
// sampling take two passes: the second reads the first pass's samples around
// each tile, so with tiles handed out the first still covers the whole image
// (every caller makes it) and only the second is shared.
template <bool Textures, bool Specular, bool Skips>
void render_tiles(const PreparedScene& p, const RenderOptions& o, RenderResult& res, const NextTile* next) {
  const WhittedIntegrator<Textures, Specular, Skips> integrator{p, o, *p.scene};
  const Film film(p, o, res);
  const TileRenderer renderer(p, o, integrator, film);
  const TileGrid layout = tile_grid(o);
  const bool grid = o.grid.on(), adaptive = !grid && o.target_error.has_value();
  TileScheduler scheduler(layout.count(), o.threads, grid || adaptive ? 2 : 1, o.progress);
  const uint64_t pixels = uint64_t(o.width) * uint64_t(o.height);
  if (grid) {
    GridSampleImage samples(o.width, o.height, o.grid.gaussian, film.alpha());
    scheduler.every_tile([&](int t) { renderer.grid_sample(layout.rect(t), samples); });
    scheduler.tiles_from(next, [&](int t) { renderer.grid_filter(layout.rect(t), samples); });
    res.samples = pixels * uint64_t(grid_samples * grid_samples);
  } else if (adaptive) {
    AdaptiveSampler sampler(o.width, o.height, *o.target_error, o.max_spp, o.sampler,
                            o.color_format == ColorFormat::srgb8, film.alpha());
    std::atomic<uint64_t> samples{0};
    scheduler.every_tile([&](int t) { renderer.adaptive_first(layout.rect(t), sampler); });
    scheduler.tiles_from(next, [&](int t) {
      if (const uint64_t n = renderer.adaptive(layout.rect(t), sampler)) samples += n;
    });
    res.samples = samples.load();
  } else if (o.spp > 1 || o.sampler != PixelSampler::stratified) {
    scheduler.tiles_from(next, [&](int t) { renderer.stratified(layout.rect(t)); });
    res.samples = pixels * uint64_t(std::max(o.spp, 1));
  } else if (const int sole_mesh = o.packets ? sole_mesh_instance(p) : -1; sole_mesh >= 0) {
    scheduler.tiles_from(next, [&](int t) { renderer.centre_packets(layout.rect(t), sole_mesh); });
    res.samples = pixels;
  } else {
    scheduler.tiles_from(next, [&](int t) { renderer.centres(layout.rect(t)); });
    res.samples = pixels;
  }
}

struct PathChoice {
  bool textures, specular, skips;  // skips: cut-outs or single-sided materials
};

PathChoice choose_path(const PreparedScene& p, const RenderOptions& o) {
  // The metallic-roughness model is shaded on the generic path only.
  if (o.generic || p.features.pbr) return {true, true, true};
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
  if (!std::isfinite(o.exposure_ev)) return "exposure: must be a finite number, got " + std::to_string(o.exposure_ev);
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
  return allocate_film(o);
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
