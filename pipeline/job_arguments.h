// The render job's arguments as the front ends take them (the command line's
// flags, cli/render_command.cpp; the Python module's keywords,
// python/render_call.cpp): each check and each name -> value mapping written
// once here. A check returns an empty string when the value is good, else
// what was expected, a phrase each front end puts after its own argument
// name ("--fov expects degrees strictly between 0 and 180, got '200'",
// "fov: expected degrees strictly between 0 and 180").
#pragma once

#include "rayform/image/tone_map.h"
#include "rayform/pipeline/render_job.h"
#include "rayform/render/color_output.h"
#include "rayform/render/sampling.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rayform {

// "A,B,..." -> the numbers, all finite; none when anything else is in the
// way (the command line's X,Y,Z, AZ,EL[,DIST] and R,G,B).
std::optional<std::vector<float>> numbers_from_text(const std::string& text);

// A camera opening angle, degrees: empty when strictly between 0 and 180.
std::string fov_problem(float fov_deg);

// A background colour, display values: empty when each channel lies in 0..1.
std::string background_problem(vec3 color);
// "#RRGGBB" (hexadecimal 00..ff, as colour pickers show it) -> display values
// 0..1 (each byte / 255); none for any other text.
std::optional<vec3> background_from_hex(const std::string& text);
// The command line's text: "#RRGGBB" or "R,G,B" (three finite numbers);
// none for any other text. The values are not checked (background_problem).
std::optional<vec3> background_from_text(const std::string& text);

// The environment's radiance scale: empty when finite and >= 0.
std::string env_intensity_problem(float intensity);
// The environment's turn about +y, degrees: empty when finite.
std::string env_rotation_problem(float rotation_deg);
// The environment asked for: `name` a picture's path, "studio" or "none"
// (none given: studio), with `intensity` (default 1) and `rotation_deg`
// (default 0), checked by the two functions above beforehand; none when
// nothing is given (the scene's default).
std::optional<Environment> environment_from_arguments(const std::optional<std::string>& name,
                                                      std::optional<float> intensity,
                                                      std::optional<float> rotation_deg);

// The camera arguments of `job` that cannot be combined: orbit with look_from
// or look_at (it places the camera itself), orbit or frame with a camera index
// (`camera_given`; they replace the file's cameras). Empty when none, else the
// message, the arguments spelled by `name` from their RenderJob names
// ("orbit", "frame", "look_from", "look_at", "camera").
std::string camera_conflict(const RenderJob& job, bool camera_given,
                            const std::function<std::string(const std::string&)>& name);

// The accepted names of each choice, in the order messages list them, and
// the value of a name (none for any other).
const std::vector<std::string>& tone_map_names();  // "khr-neutral", "aces", "none" (tone_map_from_name)
const std::vector<std::string>& encoding_names();  // "auto", "raw", "srgb"
const std::vector<std::string>& filter_names();    // "box", "tent"
const std::vector<std::string>& sampler_names();   // "stratified", "random"
std::optional<ColorEncoding> encoding_from_name(const std::string& name);
std::optional<PixelFilter> filter_from_name(const std::string& name);
std::optional<PixelSampler> sampler_from_name(const std::string& name);

// The names listed for a message, each between `quote`s: "'box' or 'tent'",
// "'auto', 'raw' or 'srgb'"; with quote "": "stratified or random".
std::string quoted_names(const std::vector<std::string>& names, const std::string& quote = "'");

}  // namespace rayform
