// A camera moved and aimed by the caller (the command line's --look-from,
// --look-at, --up and --fov), applied once the file's camera, the default
// camera or an orbit camera is in place (scene_ready.h).
#pragma once

#include "rayform/math/math.h"
#include "rayform/scene/scene.h"

#include <optional>

namespace rayform {

struct CameraAdjust {
  std::optional<vec3> look_from, look_at, up;  // world space
  std::optional<float> fov_deg;                // opening angle, degrees

  bool any() const { return look_from || look_at || up || fov_deg; }
};

// Applies `adjust` to scene.cameras[camera]. look_from alone aims at the
// centre of the scene's bounds (its instances bounded by `instance_limit`,
// Limits::instances); an up vector the new direction makes useless is
// replaced (up_not_parallel), an explicit up parallel to it is an error.
// Throws UsageError naming the command line's flags (--camera, --look-at,
// --look-from, --up) for a camera the scene lacks or a placement that
// defines no view.
void adjust_camera(Scene& scene, int camera, const CameraAdjust& adjust, uint64_t instance_limit);

}  // namespace rayform
