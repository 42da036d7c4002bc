// Loading a file ready to render, with the defaults that make a good first
// picture of an asset: one call for a program that renders any model.
//
//   ReadyScene s = load_ready_scene("duck.obj");
//   PreparedScene p = prepare_scene(s.scene);
//   RenderResult r = render(p, s.render);
//   write_color_image("duck.png", r, s.color);
//
// Asset formats (OBJ, glTF) often carry no camera or no light: a file without
// a camera gets the default camera, which frames the scene's bounds
// (scene/scene_defaults.h: add_default_camera); one without lights gets the
// default light rig fixed to the camera rendered (add_light_rig: a head-light,
// a key and a fill). Course scenes are left as the course defines them (they
// always have a camera; without lights their ambient light is white). What
// was added is reported in `notes`; the library prints nothing.
#pragma once

#include "rayform/importers/scene_io.h"
#include "rayform/render/color_output.h"
#include "rayform/render/render.h"
#include "rayform/scene/scene_defaults.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rayform {

// Width and height of an asset's picture, pixels, when the caller gives none.
// Course scenes keep RenderOptions{}'s 200x200, the course's size.
inline constexpr int asset_image_size = 512;

// The render options a scene of `format` starts from: RenderOptions{} with
// the default size of the format, and for a course scene of the a5 dialect
// its default bounces (course_a5_default_bounces).
RenderOptions default_render_options(SceneFormat format, CourseDialect dialect = CourseDialect::v2012);

// Bounces for a scene with physically based materials
// (Material::Model::metallic_roughness): its metals and glossy surfaces show
// the scene in their reflections, reflections of reflections included.
inline constexpr int pbr_default_bounces = 4;
// Bounces for a scene with a transmissive material (pbr.transmission > 0): a
// ray through a glass object crosses at least two surfaces, and reflects on
// the way; 8 lets it through a few such objects.
inline constexpr int transmission_default_bounces = 8;

// default_render_options(format, dialect), then what `scene`'s materials
// need when any of them is metallic-roughness: the Khronos PBR Neutral tone
// map (ToneMap::khr_neutral, as the Khronos Sample Viewer shows such files),
// and transmission_default_bounces when one of them transmits, else
// pbr_default_bounces. Scenes of Phong materials alone (course, OBJ's
// Kd/Ks/Ns) keep the format's options.
RenderOptions default_render_options(const Scene& scene, SceneFormat format,
                                     CourseDialect dialect = CourseDialect::v2012);

// Whether a metallic-roughness material of `scene` transmits light (pbr.transmission > 0).
bool uses_transmission(const Scene& scene);

// What the colours of a scene of `format` mean: course scenes produce values
// for the screen as they are, assets linear light (render/color_output.h).
SceneColors scene_colors(SceneFormat format);

struct ReadyOptions {
  LoadOptions load;
  // The camera rendered (RenderOptions::camera): the light rig follows it.
  int camera = 0;
  // When set, the file's cameras are replaced by one framing camera at this
  // orbit around the scene's bounds (orbit_camera with orbit_fov_deg), any
  // format; no default camera is then added.
  std::optional<Orbit> orbit;
  float orbit_fov_deg = default_camera_fov_deg;
  // When set (and no orbit), the file's cameras are replaced by the default
  // camera (orbit_camera at default_orbit of the scene's bounds), any format.
  bool frame = false;
  // Called once the camera is in place (the file's, the default or the
  // orbit's) and before the lights are added, to change the cameras (the
  // command line's --look-from, --look-at, --up, --fov); may throw.
  std::function<void(Scene&)> adjust_camera;
  // The environment the scene is lit by and shows (the command line's --env,
  // --env-intensity, --env-rotate). When not set, an asset with
  // metallic-roughness materials and no light of its own gets the studio
  // environment (Environment::Source::studio) instead of the light rig.
  std::optional<Environment> environment;
};

struct ReadyScene : LoadedScene {
  // What the defaults added, one line each naming the file ("duck.obj has no
  // camera: added one framing the scene's bounds").
  std::vector<std::string> notes;
  // How to write its pictures (write_color_image): what its colours mean.
  ColorOutput color;
  // default_render_options(scene, format, dialect), with `camera` set to ReadyOptions::camera.
  RenderOptions render;
  // When render.bounces is transmission_default_bounces, the note saying so
  // ("glass.gltf uses transmission: --bounces 8 by default"), for a caller
  // that keeps the default bounces; else empty.
  std::string bounces_note;
};

// load_scene, then the defaults above. Throws rayform::Error as load_scene
// does, or for an orbit orbit_camera refuses.
ReadyScene load_ready_scene(const std::string& path, const ReadyOptions& options = {});

// The same for a scene already loaded from `path` (with options.load): the
// defaults above applied to `loaded`. For a program that renders one file
// many times with different cameras (a turntable's frames) and loads it once.
ReadyScene make_scene_ready(LoadedScene loaded, const std::string& path, const ReadyOptions& options = {});

}  // namespace rayform
