// The film: where a pixel's values go. It turns the sums over a pixel's
// samples into its colour and coverage (AlphaMode), knows the background a
// missed camera ray shows, and stores colour, depth, normals, albedo and
// coverage into a RenderResult's buffers, quantising 8-bit colour as it
// stores (image/quantize.h's rule, raw or sRGB: RenderOptions::color_format).
// Colour is stored exposed (RenderOptions::exposure_ev) and, when 8-bit,
// tone mapped (RenderOptions::tone_map); albedo as it is.
#pragma once

#include "rayform/image/quantize.h"
#include "rayform/image/tone_map.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"

#include <cstdint>

namespace rayform {

// One pixel's values before they are stored. Depth, normal and albedo come
// from the ray through the pixel centre (RenderResult).
struct PixelValues {
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

// The buffers of `options`' outputs, holding the values of a pixel no tile
// wrote (colour 0, depth infinity, normals 0, coverage 0).
RenderResult allocate_film(const RenderOptions& options);

class Film {
 public:
  // Stores into `result` (from allocate_film with the same options).
  Film(const PreparedScene& scene, const RenderOptions& options, RenderResult& result);

  // The values of a camera ray that hits nothing: the background colour
  // (black when premultiplied), coverage 0. With a cube map the background
  // depends on the ray: misses_shaded.
  const PixelValues& background() const { return background_; }
  bool misses_shaded() const { return cube_map_; }
  // Whether a miss changes nothing but the background's bytes in color8
  // (8-bit colour, no AOVs, no cube map): background_bytes() then holds them,
  // quantised once (most pixels of an asset framed by its bounds are background).
  bool misses_are_bytes() const { return misses_are_bytes_; }
  const unsigned char* background_bytes() const { return background8_; }
  unsigned char* color8() const { return result_.color8.pixels.data(); }

  bool premultiplied() const { return premultiplied_; }
  // Whether coverage is kept (AlphaMode not none): the sums of the samples
  // that hit are then needed.
  bool alpha() const { return alpha_; }

  // A pixel's colour and coverage from the sums over its samples: sum and
  // weight over all, hit_sum and covered over those that hit a surface.
  [[gnu::always_inline]] void finish(PixelValues& px, vec3 sum, vec3 hit_sum, float weight, float covered) const {
    // Every sample missed: the background itself (the average of equal
    // values, which float sums can miss by a step; an 8-bit output then
    // shows exactly the background's bytes).
    px.color = covered == 0.f && !cube_map_ ? background_.color : sum / weight;
    if (alpha_) {
      px.coverage = covered / weight;
      if (premultiplied_) px.color = hit_sum / weight;
      else if (covered > 0.f) px.color = hit_sum / covered;
    }
  }

  // Pixel `pixel` (row by row from the top left) of every buffer kept.
  [[gnu::always_inline]] void store(uint32_t pixel, const PixelValues& px) const {
    store_color(format_, srgb_, result_.color, result_.color8, pixel, grades_ ? graded(px) : px.color);
    if (depth_) result_.depth[pixel] = px.depth;
    if (normals_) result_.normals[pixel] = px.normal;
    if (albedo_) store_color(format_, srgb_, result_.albedo, result_.albedo8, pixel, px.albedo);
    if (alpha_) result_.coverage[pixel] = px.coverage;
  }

 private:
  // The colour stored for px: exposed, then tone mapped (8-bit colour). A
  // premultiplied colour is tone mapped as the straight colour it stands for.
  vec3 graded(const PixelValues& px) const {
    const vec3 c = px.color * exposure_scale_;
    if (tone_map_ == ToneMap::none) return c;
    if (!premultiplied_) return apply_tone_map(tone_map_, c);
    return px.coverage > 0.f ? apply_tone_map(tone_map_, c / px.coverage) * px.coverage : c;
  }

  RenderResult& result_;
  ColorFormat format_;
  const SrgbQuantizer* srgb_;  // ColorFormat::srgb8's, else null
  bool depth_, normals_, albedo_, alpha_, premultiplied_, cube_map_, misses_are_bytes_;
  float exposure_scale_;  // 2^RenderOptions::exposure_ev
  ToneMap tone_map_;      // RenderOptions::tone_map for 8-bit colour, else none
  bool grades_;           // whether either changes colour
  PixelValues background_;
  unsigned char background8_[3] = {};
};

}  // namespace rayform
