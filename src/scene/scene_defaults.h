// Defaults for scenes whose files carry no camera or no light (OBJ always,
// glTF often): a camera that frames the scene and a light that goes with it.
// The caller decides whether to use them (the CLI reports what it added).
#pragma once

#include "scene/scene.h"

namespace rayform {

// Vertical opening angle of the default camera, degrees.
inline constexpr float default_camera_fov_deg = 40.f;

// When the scene has no camera, adds a perspective camera (aspect fit,
// vertical field of view default_camera_fov_deg, +y up) on the +z side of the
// scene's bounds, looking down -z at their centre, far enough that the whole
// box lies inside the view with a 10% margin for any image at least as wide
// as it is tall. An empty scene gets a camera at (0, 0, 5). Returns whether a
// camera was added. Throws rayform::Error when the node graph is invalid.
bool add_default_camera(Scene& scene);

// When the scene has no light, adds a white directional "headlight" shining
// along the view direction of camera `camera` (the first when out of range;
// down -z without a camera), so that every surface facing that camera is lit.
// Returns whether a light was added. Call add_default_camera, and apply any
// change to the camera, first.
bool add_headlight(Scene& scene, int camera = 0);

}  // namespace rayform
