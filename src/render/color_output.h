// How a render's colour is written to a file: the one choice of transfer
// function, made from what the scene's colours mean and the file's type.
//
//   scene colours    8-bit file (png, bmp, tga, jpg, ...)    float file (exr, hdr, tif, ...)
//   linear (assets)  sRGB-encoded (clamped to [0, 1])        linear, unclamped
//   display (course) as computed (clamped to [0, 1])         as computed, unclamped
//
// A caller may force either encoding (the command line's --color raw|srgb).
#pragma once

#include "rayform/image/image.h"
#include "rayform/image/image_file.h"
#include "rayform/image/tone_map.h"
#include "rayform/render/render.h"

#include <cstdint>
#include <string>

namespace rayform {

// What the numbers a scene's lights and materials produce mean.
enum class SceneColors : uint8_t {
  display,  // values meant for the screen as they are (the course writes them raw)
  linear,   // linear light (OBJ, glTF: sRGB textures decoded, shading linear)
};

// The transfer function asked for: automatic follows the table above; raw
// writes the values as computed; srgb encodes them (clamped to [0, 1] first,
// float files too).
enum class ColorEncoding : uint8_t { automatic, raw, srgb };

struct ColorOutput {
  SceneColors scene = SceneColors::linear;
  ColorEncoding encoding = ColorEncoding::automatic;
};

// Whether the pictures are seen through sRGB: encoded into 8-bit files, or
// held linear in float files that a viewer encodes (encoding srgb, or
// automatic for a linear scene). Display values given for such a scene (a
// background colour) are converted to linear.
bool shown_through_srgb(const ColorOutput& output);

// Each function below that takes a path has a form that takes the path
// parsed once (image/image_file.h), for a caller that decides many things of
// one output.

// Whether the values written to `file` are sRGB-encoded: shown through sRGB
// and, unless the encoding is forced, an 8-bit file.
bool writes_srgb(const ColorOutput& output, const ImageFile& file);
bool writes_srgb(const ColorOutput& output, const std::string& path);

// The RenderOptions::color_format for writing colour to `file` and, when
// given, albedo to `albedo`: 8-bit values straight from the render loop
// (unit8 or srgb8) when both are 8-bit files with the same encoding, else
// linear floats, encoded when written.
ColorFormat render_color_format(const ColorOutput& output, const ImageFile& file, const ImageFile* albedo);
ColorFormat render_color_format(const ColorOutput& output, const std::string& path,
                                const std::string& albedo_path = {});

// A float picture as a file holds it: sRGB-encoded (each colour channel
// clamped to [0, 1], NaN to 0, then encoded; a fourth channel, alpha, kept
// linear) or unchanged.
void encode_srgb_in_place(Image& image);

// Each pixel's colour channels (the first three; a fourth, alpha, kept)
// through `map` (image/tone_map.h).
void tone_map_in_place(Image& image, ToneMap map);

enum class ColorPlane : uint8_t { color, albedo };

// Writes `plane` of `result` to a temporary file beside the file in the
// encoding writes_srgb chooses, and returns the temporary's path (commit it
// with commit_temporary, or several with OutputFiles::add_written). Colour
// gets the coverage as a fourth (alpha) channel, linear, when the render has
// one (RenderOptions::alpha; color_with_alpha). A float plane without alpha
// is encoded in place: afterwards `result` holds the file's values. Float
// colour written to a file that is not a float file is first tone mapped by
// result.tone_map (8-bit colour was tone mapped by the render; albedo never is).
// Throws rayform::Error when the plane is missing or holds 8-bit values of
// another encoding, or a float file is asked for from 8-bit values (render
// with render_color_format), or the file cannot be written.
std::string write_color_temporary(const ImageFile& file, RenderResult& result, ColorPlane plane,
                                  const ColorOutput& output);
std::string write_color_temporary(const std::string& path, RenderResult& result, ColorPlane plane,
                                  const ColorOutput& output);

// The colour picture of `result` written to `path` (write_color_temporary,
// then committed): the format follows the extension.
void write_color_image(const std::string& path, RenderResult& result, const ColorOutput& output);

}  // namespace rayform
