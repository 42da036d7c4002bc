#include "rayform/pipeline/camera_adjust.h"

#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/scene/scene_stats.h"

#include <string>

namespace rayform {

void adjust_camera(Scene& scene, int camera, const CameraAdjust& adjust, uint64_t instance_limit) {
  if (camera < 0 || camera >= int(scene.cameras.size()))
    throw UsageError("--camera " + std::to_string(camera) + ": the scene has no such camera to adjust");
  Camera& c = scene.cameras[camera];
  if (adjust.look_from || adjust.look_at) {
    const vec3 from = adjust.look_from.value_or(c.center);
    const vec3 target = adjust.look_at ? *adjust.look_at : framing_target(scene_stats(scene, instance_limit).bounds);
    if (target == from)
      throw UsageError(adjust.look_at ? "--look-at must differ from --look-from"
                                      : "--look-from is the centre of the scene's bounds, where the camera would "
                                        "look: give --look-at");
    c.center = from;
    c.direction = target - from;
    if (!adjust.up) c.up = up_not_parallel(c.up, c.direction);
  }
  if (adjust.up) c.up = *adjust.up;
  if (glm::length(glm::cross(c.direction, c.up)) == 0.f)
    throw UsageError("--up must not be parallel to the view direction");
  if (adjust.fov_deg) c.fov_deg = *adjust.fov_deg;
}

}  // namespace rayform
