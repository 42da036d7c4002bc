#include "rayform/render/color_output.h"

#include "rayform/image/color.h"
#include "rayform/render/aov_images.h"
#include "rayform/base/error.h"

#include <algorithm>
#include <cmath>

namespace rayform {

bool shown_through_srgb(const ColorOutput& output) {
  switch (output.encoding) {
    case ColorEncoding::raw: return false;
    case ColorEncoding::srgb: return true;
    case ColorEncoding::automatic: break;
  }
  return output.scene == SceneColors::linear;
}

bool writes_srgb(const ColorOutput& output, const ImageFile& file) {
  return shown_through_srgb(output) && (output.encoding == ColorEncoding::srgb || !file.floats);
}

bool writes_srgb(const ColorOutput& output, const std::string& path) { return writes_srgb(output, image_file(path)); }

ColorFormat render_color_format(const ColorOutput& output, const ImageFile& file, const ImageFile* albedo) {
  if (!file.bits8) return ColorFormat::linear_float;
  const bool srgb = writes_srgb(output, file);
  if (albedo && (!albedo->bits8 || writes_srgb(output, *albedo) != srgb)) return ColorFormat::linear_float;
  return srgb ? ColorFormat::srgb8 : ColorFormat::unit8;
}

ColorFormat render_color_format(const ColorOutput& output, const std::string& path, const std::string& albedo_path) {
  const ImageFile albedo = image_file(albedo_path);
  return render_color_format(output, image_file(path), albedo_path.empty() ? nullptr : &albedo);
}

void encode_srgb_in_place(Image& image) {
  const int colour_channels = std::min(image.channels, 3);
  const size_t step = size_t(std::max(image.channels, 1));
  for (size_t i = 0; i + step <= image.pixels.size(); i += step)
    for (int c = 0; c < colour_channels; ++c) {
      float& v = image.pixels[i + size_t(c)];
      v = linear_to_srgb(std::isnan(v) ? 0.f : std::clamp(v, 0.f, 1.f));
    }
}

void tone_map_in_place(Image& image, ToneMap map) {
  if (map == ToneMap::none || image.channels < 3) return;
  const size_t step = size_t(image.channels);
  for (size_t i = 0; i + step <= image.pixels.size(); i += step) {
    float* p = &image.pixels[i];
    const vec3 c = apply_tone_map(map, vec3(p[0], p[1], p[2]));
    for (int k = 0; k < 3; ++k) p[k] = c[k];
  }
}

std::string write_color_temporary(const ImageFile& file, RenderResult& result, ColorPlane plane,
                                  const ColorOutput& output) {
  const std::string& path = file.path;
  const char* what = plane == ColorPlane::color ? "colour" : "albedo";
  const bool srgb = writes_srgb(output, file);
  const bool with_alpha = plane == ColorPlane::color && !result.coverage.empty();
  if (result.color_format != ColorFormat::linear_float) {
    const Image8& bytes = plane == ColorPlane::color ? result.color8 : result.albedo8;
    if (bytes.pixels.empty()) throw Error(path + ": the render has no " + what + " to write");
    if (!file.bits8 || srgb != (result.color_format == ColorFormat::srgb8))
      throw Error(path + ": the render's " + what + " holds 8-bit " +
                  (result.color_format == ColorFormat::srgb8 ? "sRGB" : "raw") +
                  " values, not what this file needs (render with render_color_format)");
    if (with_alpha) return write_image8_temporary(file, color8_with_alpha(result));
    return write_image8_temporary(file, bytes);
  }
  Image& image = plane == ColorPlane::color ? result.color : result.albedo;
  if (image.empty()) throw Error(path + ": the render has no " + what + " to write");
  const ToneMap tone_map = plane == ColorPlane::color && !file.floats ? result.tone_map : ToneMap::none;
  if (with_alpha) {
    Image rgba = color_with_alpha(result);
    tone_map_in_place(rgba, tone_map);
    if (srgb) encode_srgb_in_place(rgba);
    return write_image_temporary(file, rgba);
  }
  tone_map_in_place(image, tone_map);
  if (tone_map != ToneMap::none) result.tone_map = ToneMap::none;  // `image` now holds tone-mapped colour
  if (srgb) encode_srgb_in_place(image);
  return write_image_temporary(file, image);
}

std::string write_color_temporary(const std::string& path, RenderResult& result, ColorPlane plane,
                                  const ColorOutput& output) {
  return write_color_temporary(image_file(path), result, plane, output);
}

void write_color_image(const std::string& path, RenderResult& result, const ColorOutput& output) {
  commit_temporary(write_color_temporary(path, result, ColorPlane::color, output), path);
}

}  // namespace rayform
