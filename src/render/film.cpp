#include "rayform/render/film.h"

#include <cmath>

namespace rayform {

RenderResult allocate_film(const RenderOptions& o) {
  const int width = o.width, height = o.height;
  RenderResult res;
  res.width = width;
  res.height = height;
  res.color_format = o.color_format;
  res.tone_map = o.tone_map;
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

Film::Film(const PreparedScene& p, const RenderOptions& o, RenderResult& result)
    : result_(result),
      format_(o.color_format),
      srgb_(o.color_format == ColorFormat::srgb8 ? &srgb_quantizer() : nullptr),
      depth_(o.depth),
      normals_(o.normals),
      albedo_(o.albedo),
      alpha_(o.alpha != AlphaMode::none),
      premultiplied_(o.alpha == AlphaMode::premultiplied),
      cube_map_(p.features.cube_map || p.features.environment_shown),
      exposure_scale_(std::exp2(o.exposure_ev)),
      tone_map_(o.color_format == ColorFormat::linear_float ? ToneMap::none : o.tone_map),
      grades_(exposure_scale_ != 1.f || tone_map_ != ToneMap::none) {
  background_.color = premultiplied_ ? vec3(0.f) : p.scene->background.color;
  misses_are_bytes_ = !cube_map_ && !(o.depth || o.normals || o.albedo) && o.color_format != ColorFormat::linear_float;
  // The bytes store() gives the background.
  const vec3 background = grades_ ? graded(background_) : background_.color;
  for (int k = 0; k < 3; ++k) background8_[k] = quantize_sample(srgb_, background[k]);
}

}  // namespace rayform
