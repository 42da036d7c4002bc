#include "rayform/pipeline/job_arguments.h"

#include <cmath>

namespace rayform {
namespace {

template <class T>
std::optional<T> value_of(const std::string& name, const std::vector<std::string>& names,
                          std::initializer_list<T> values) {
  for (size_t i = 0; i < names.size(); ++i)
    if (name == names[i]) return values.begin()[i];
  return std::nullopt;
}

}  // namespace

std::optional<std::vector<float>> numbers_from_text(const std::string& s) {
  std::vector<float> v;
  size_t pos = 0;
  try {
    for (;;) {
      size_t used = 0;
      v.push_back(std::stof(s.substr(pos), &used));
      pos += used;
      if (pos == s.size()) break;
      if (s[pos] != ',') return std::nullopt;
      ++pos;
    }
  } catch (const std::exception&) {
    return std::nullopt;
  }
  for (float x : v)
    if (!std::isfinite(x)) return std::nullopt;
  return v;
}

std::string fov_problem(float fov_deg) {
  return fov_deg > 0.f && fov_deg < 180.f ? "" : "degrees strictly between 0 and 180";
}

std::string background_problem(vec3 color) {
  for (int k = 0; k < 3; ++k)
    if (!(color[k] >= 0.f && color[k] <= 1.f)) return "each of r, g, b in 0..1";
  return "";
}

std::optional<vec3> background_from_hex(const std::string& text) {
  if (text.size() != 7 || text[0] != '#' || text.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos)
    return std::nullopt;
  vec3 c;
  for (int k = 0; k < 3; ++k) c[k] = float(std::stoi(text.substr(1 + 2 * k, 2), nullptr, 16)) / 255.f;
  return c;
}

std::optional<vec3> background_from_text(const std::string& text) {
  if (!text.empty() && text[0] == '#') return background_from_hex(text);
  const std::optional<std::vector<float>> v = numbers_from_text(text);
  if (!v || v->size() != 3) return std::nullopt;
  return vec3((*v)[0], (*v)[1], (*v)[2]);
}

std::string env_intensity_problem(float intensity) {
  return intensity >= 0.f && std::isfinite(intensity) ? "" : "a finite number >= 0";
}

std::string env_rotation_problem(float rotation_deg) { return std::isfinite(rotation_deg) ? "" : "degrees"; }

std::optional<Environment> environment_from_arguments(const std::optional<std::string>& name,
                                                      std::optional<float> intensity,
                                                      std::optional<float> rotation_deg) {
  if (!name && !intensity && !rotation_deg) return std::nullopt;
  Environment e;
  e.intensity = intensity.value_or(1.f);
  e.rotation_deg = rotation_deg.value_or(0.f);
  if (!name || *name == "studio") {
    e.source = Environment::Source::studio;
  } else if (*name == "none") {
    e.source = Environment::Source::none;
  } else {
    e.source = Environment::Source::file;
    e.path = *name;
  }
  return e;
}

std::string camera_conflict(const RenderJob& job, bool camera_given,
                            const std::function<std::string(const std::string&)>& name) {
  if (job.orbit && (job.camera_adjust.look_from || job.camera_adjust.look_at))
    return name("orbit") + " places the camera itself: it cannot be combined with " + name("look_from") + " or " +
           name("look_at");
  if ((job.orbit || job.frame) && camera_given)
    return name(job.orbit ? "orbit" : "frame") + " replaces the file's cameras: it cannot be combined with " +
           name("camera");
  return "";
}

const std::vector<std::string>& tone_map_names() {
  static const std::vector<std::string> names = {tone_map_name(ToneMap::khr_neutral), tone_map_name(ToneMap::aces),
                                                 tone_map_name(ToneMap::none)};
  return names;
}

const std::vector<std::string>& encoding_names() {
  static const std::vector<std::string> names = {"auto", "raw", "srgb"};
  return names;
}

const std::vector<std::string>& filter_names() {
  static const std::vector<std::string> names = {"box", "tent"};
  return names;
}

const std::vector<std::string>& sampler_names() {
  static const std::vector<std::string> names = {"stratified", "random"};
  return names;
}

std::optional<ColorEncoding> encoding_from_name(const std::string& name) {
  return value_of(name, encoding_names(), {ColorEncoding::automatic, ColorEncoding::raw, ColorEncoding::srgb});
}

std::optional<PixelFilter> filter_from_name(const std::string& name) {
  return value_of(name, filter_names(), {PixelFilter::box, PixelFilter::tent});
}

std::optional<PixelSampler> sampler_from_name(const std::string& name) {
  return value_of(name, sampler_names(), {PixelSampler::stratified, PixelSampler::random});
}

std::string quoted_names(const std::vector<std::string>& names, const std::string& quote) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) s += i + 1 == names.size() ? " or " : ", ";
    s += quote + names[i] + quote;
  }
  return s;
}

}  // namespace rayform
