// Tone mapping: linear scene colour (unbounded, >= 0) to display-linear
// colour in [0, 1], before the output's transfer function (sRGB encoding or
// raw) and quantisation. Applied to 8-bit colour outputs only (float files
// stay linear); RenderOptions::tone_map chooses.
#pragma once

#include "rayform/math/math.h"

#include <cstdint>
#include <optional>
#include <string>

namespace rayform {

enum class ToneMap : uint8_t {
  none,         // as it is (the output clamps to [0, 1])
  khr_neutral,  // Khronos PBR Neutral: colours below the compression start kept (less an offset), highlights compressed
  aces,         // ACES filmic, Stephen Hill's fit of the RRT and sRGB ODT, with three.js' 1/0.6 exposure boost
};

// Khronos PBR Neutral (github.com/KhronosGroup/ToneMapping, PBR_Neutral):
// with x = min(r, g, b), the offset f = x - x^2 / (4 F90) for x <= 2 F90,
// else F90 (F90 = 0.04, the Fresnel reflectance of IOR 1.5), is taken from
// every channel; when the largest of the results, p, is at most the
// compression start Ks = 0.8 - F90 the colour is c - f, else it is scaled to
// the compressed peak p_n = 1 - (1 - Ks)^2 / (p + 1 - 2 Ks) and mixed towards
// grey p_n by 1 - g, g = 1 / (Kd (p - p_n) + 1) with the desaturation speed
// Kd = 0.15. Negative and NaN channels count as 0. The result lies in [0, 1].
vec3 tone_map_khr_neutral(vec3 linear);

// Stephen Hill's fit of ACES (BakingLab ACES.hlsl: sRGB to the RRT's input
// space, the rational fit of the RRT and the sRGB ODT, back to sRGB, clamped
// to [0, 1]), after scaling by 1 / 0.6 as three.js' ACESFilmicToneMapping and
// the Khronos Sample Viewer's "ACES Hill exposure boost" do (mid grey 0.18
// shows as about 0.21 instead of 0.11). Negative and NaN channels count as 0.
vec3 tone_map_aces(vec3 linear);

// `linear` through `map` (none: unchanged).
vec3 apply_tone_map(ToneMap map, vec3 linear);

// The command line's names: "none", "khr-neutral", "aces".
const char* tone_map_name(ToneMap map);
std::optional<ToneMap> tone_map_from_name(const std::string& name);

}  // namespace rayform
