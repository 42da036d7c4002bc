#include "rayform/pipeline/scene_ready.h"

#include "rayform/scene/scene_stats.h"

#include <algorithm>
#include <string>
#include <utility>

namespace rayform {

RenderOptions default_render_options(SceneFormat format, CourseDialect dialect) {
  RenderOptions o;
  if (format != SceneFormat::course_txt) o.width = o.height = asset_image_size;
  else if (dialect == CourseDialect::a5) o.bounces = course_a5_default_bounces;
  return o;
}

bool uses_transmission(const Scene& scene) {
  return std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
    return m.model == Material::Model::metallic_roughness && m.pbr.transmission > 0.f;
  });
}

RenderOptions default_render_options(const Scene& scene, SceneFormat format, CourseDialect dialect) {
  RenderOptions o = default_render_options(format, dialect);
  const bool pbr = std::any_of(scene.materials.begin(), scene.materials.end(),
                               [](const Material& m) { return m.model == Material::Model::metallic_roughness; });
  if (!pbr) return o;
  o.tone_map = ToneMap::khr_neutral;
  o.bounces = uses_transmission(scene) ? transmission_default_bounces : pbr_default_bounces;
  return o;
}

SceneColors scene_colors(SceneFormat format) {
  return format == SceneFormat::course_txt ? SceneColors::display : SceneColors::linear;
}

ReadyScene load_ready_scene(const std::string& path, const ReadyOptions& options) {
  return make_scene_ready(load_scene(path, options.load), path, options);
}

ReadyScene make_scene_ready(LoadedScene loaded, const std::string& path, const ReadyOptions& options) {
  ReadyScene ready;
  static_cast<LoadedScene&>(ready) = std::move(loaded);
  Scene& scene = ready.scene;
  const bool asset = ready.format != SceneFormat::course_txt;
  if (options.orbit || options.frame) {
    const Bounds3 bounds = scene_stats(scene, options.load.limits.instances).bounds;
    scene.cameras = {
        orbit_camera(bounds, options.orbit ? *options.orbit : default_orbit(bounds), options.orbit_fov_deg)};
  } else if (asset && add_default_camera(scene)) {
    ready.notes.push_back(path + " has no camera: added one framing the scene's bounds");
  }
  if (options.adjust_camera) options.adjust_camera(scene);
  const bool pbr = std::any_of(scene.materials.begin(), scene.materials.end(),
                               [](const Material& m) { return m.model == Material::Model::metallic_roughness; });
  if (options.environment) {
    scene.background.environment = *options.environment;
  } else if (asset && pbr && scene.lights.empty()) {
    scene.background.environment.source = Environment::Source::studio;
    ready.notes.push_back(path + " has no light: lit by the built-in studio environment (--env FILE for another)");
  }
  // The light rig, for what the environment does not light: the course's
  // Phong materials.
  const bool lit_by_environment = pbr && scene.background.environment.source != Environment::Source::none;
  if (asset && !lit_by_environment && add_light_rig(scene, options.camera))
    ready.notes.push_back(path + " has no light: added the default light rig (a head-light, a key and a fill) " +
                          "around the camera");
  ready.color.scene = scene_colors(ready.format);
  ready.render = default_render_options(scene, ready.format, ready.dialect);
  ready.render.camera = options.camera;
  if (uses_transmission(scene))
    ready.bounces_note =
        path + " uses transmission: --bounces " + std::to_string(transmission_default_bounces) + " by default";
  return ready;
}

}  // namespace rayform
