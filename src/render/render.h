// Rendering an image: the parameters, the result, and the entry points. The
// image is split into tiles (tile_grid.h) rendered in parallel
// (tile_scheduler.h); each pixel is traced independently, so the result does
// not depend on the number of threads. The loop's parts: the sampler
// (sampling.h, adaptive_sampling.h, grid_filter.h), the integrator
// (whitted_integrator.h), the film (film.h), the per-tile loops
// (tile_renderer.h); render.cpp picks one of eight compiled paths.
#pragma once

#include "rayform/image/image.h"
#include "rayform/image/tone_map.h"
#include "rayform/render/adaptive_sampling.h"
#include "rayform/render/grid_filter.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/sampling.h"
#include "rayform/render/tile_grid.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace rayform {

// How colour and albedo are stored: linear floats (RenderResult::color /
// albedo), or the 8-bit values of an integer image file (color8 / albedo8),
// quantised in the render loop by image/quantize.h's rule: as they are
// (unit8) or after sRGB encoding (srgb8).
enum class ColorFormat : uint8_t { linear_float, unit8, srgb8 };

// Whether RenderResult::coverage is filled and how colour goes with it. A
// pixel's coverage is the filter-weighted fraction of its camera samples that
// hit a surface (1 inside an object, 0 on the background, between on edges).
//   none: no coverage; colour as always (the background where rays miss).
//   straight: colour is the average over the samples that hit (as PNG and TGA
//     store it); a pixel no sample hits keeps the colour it has with none.
//   premultiplied: colour is the average over all samples with misses
//     counting as black (as OpenEXR stores it); background pixels are black.
// Pixels every sample hits have the same colour in all three.
enum class AlphaMode : uint8_t { none, straight, premultiplied };

// The deepest reflection/refraction traced: RenderOptions::bounces above it
// render as max_bounces (the secondary rays recurse, one level a bounce,
// so the depth is bounded whatever a file or flag asks; past it a mirror's
// light is below what an 8-bit picture shows for a specular colour of at most 0.9).
inline constexpr int max_bounces = 64;

// The render parameters, one owner: their defaults are here, their rules in
// render_options_problem below, and the command line fills this struct (no copy).
struct RenderOptions {
  int width = 200, height = 200;  // pixels (the course's default size)
  int camera = 0;                 // index into Scene::cameras
  int threads = 0;                // 0: all hardware threads
  bool shadows = false;           // shadow rays to each light
  int bounces = 0;                // reflection/refraction depth (used up to max_bounces)
  int spp = 1;                    // samples per pixel (1: the pixel centre only)
  PixelFilter filter = PixelFilter::box;
  PixelSampler sampler = PixelSampler::stratified;  // random: also for spp 1 (no centre ray)
  // Adaptive sampling when set (adaptive_sampling.h): rounds of samples per
  // pixel until the standard error of their mean is below target_error (the
  // box filter; spp is then not used). Must be > 0.
  std::optional<float> target_error;
  int max_spp = 256;  // adaptive sampling's most samples per pixel (>= 1)
  // The 2012 assignment 5's 3x3-sample anti-aliasing (grid_filter.h); spp,
  // filter, sampler and target_error are then not used.
  GridFilter grid;
  // Which per-pixel outputs to fill besides colour.
  bool depth = false, normals = false, albedo = false;
  AlphaMode alpha = AlphaMode::none;
  ColorFormat color_format = ColorFormat::linear_float;
  // Colour (not albedo) is scaled by 2^exposure_ev (every format: 8-bit and
  // float outputs alike), then, for 8-bit colour only, mapped by tone_map
  // (image/tone_map.h) before it is encoded and quantised; linear_float
  // colour stays linear (write_color_temporary applies tone_map when such
  // colour is written to an 8-bit file). The background is colour too.
  // exposure_ev must be finite.
  float exposure_ev = 0.f;
  ToneMap tone_map = ToneMap::none;
  bool generic = false;  // force the general path (no feature specialisation)
  bool packets = true;   // camera rays of a one-mesh scene eight at a time (the same image)
  int tile_size = 16;    // the unit of work (tile_grid.h)
  // Called with the fraction of tiles done here (from worker threads, serialised).
  std::function<void(float)> progress;
};

// Per-pixel outputs, rows from the top. Colour is the filtered average of
// the pixel's samples. Depth, normals and albedo come from the ray through the
// pixel centre: depth is the hit distance along it (infinity on a miss),
// normals are unit world-space shading normals (zero on a miss), albedo is the
// unlit surface colour K. Only the buffers asked for are allocated.
struct RenderResult {
  int width = 0, height = 0;
  ColorFormat color_format = ColorFormat::linear_float;  // RenderOptions::color_format: which buffers hold colour
  Image color;                                           // 3 channels, linear, unclamped (ColorFormat::linear_float)
  Image8 color8;                                         // 3 channels (ColorFormat::unit8 or srgb8)
  std::vector<float> depth;
  std::vector<vec3> normals;
  Image albedo;                 // 3 channels, as color
  Image8 albedo8;               // 3 channels, as color8
  std::vector<float> coverage;  // 0..1 per pixel (AlphaMode, above), when alpha is not none
  // RenderOptions::tone_map: applied to color8 by the render; what
  // linear_float colour still needs when it is written to an 8-bit file.
  ToneMap tone_map = ToneMap::none;
  uint64_t samples = 0;  // camera samples traced for colour (all pixels)
};

// What is wrong with `options`, "" when nothing: the one check of the
// parameters a caller sets (image size >= 1 x 1, spp >= 1, bounces >= 0,
// threads >= 0, camera >= 0, target_error > 0 when set (not NaN) with the
// box filter, max_spp >= 1, grid not combined with spp > 1 or target_error). Each message starts with the parameter's
// name, e.g. "size: width and height must be positive, got 0x20", so that a command line can put its own flag in front.
std::string render_options_problem(const RenderOptions& options);

// Throws rayform::Error for options render_options_problem refuses, or a
// camera index the scene does not have.
RenderResult render(const PreparedScene& scene, const RenderOptions& options);

// The tiles render() splits an image of these options into.
TileGrid tile_grid(const RenderOptions& options);

// Rendering part of an image, for a caller that spreads the tiles over
// processes (cli/'s MPI driver) or picks its own order:
//   RenderResult r = allocate_render_result(scene, options);
//   render_tiles_from(scene, options, next_tile, r);
// allocate_render_result checks as render() does (throws rayform::Error) and
// returns the buffers render() fills, holding the values of a pixel no tile
// wrote (colour 0, depth infinity, normals 0, coverage 0).
RenderResult allocate_render_result(const PreparedScene& scene, const RenderOptions& options);
// Renders the tiles (indices into tile_grid(options)) that `next_tile`
// returns until it returns a negative number, each into `result` (from
// allocate_render_result with the same options): every pixel of a tile gets
// the values render() gives it, whichever tiles and order. `next_tile` is
// called from the worker threads, so it must be thread-safe (one call at a
// time is not promised); with options.threads == 1 every call is on the
// calling thread. options.progress, when set, gets the fraction of all
// tiles rendered by this call.
using NextTile = std::function<int()>;
void render_tiles_from(const PreparedScene& scene, const RenderOptions& options, const NextTile& next_tile,
                       RenderResult& result);

// Which specialised path render() takes for this scene and these options
// ("generic" when forced or when no specialisation applies); for reports.
std::string render_path_name(const PreparedScene& scene, const RenderOptions& options);

}  // namespace rayform
