// Defaults for scenes whose files carry no camera or no light (OBJ always,
// glTF often): a camera that frames the scene and lights that go with it.
// The same framing places a camera anywhere around the scene (orbit_camera),
// for the command line's --frame and --orbit. The caller decides whether to
// use them (the CLI reports what it added).
#pragma once

#include "rayform/geometry/bounds.h"
#include "rayform/scene/scene.h"

#include <optional>
#include <string>

namespace rayform {

// Vertical opening angle of the default camera, degrees.
inline constexpr float default_camera_fov_deg = 40.f;

// Where a camera stands on a sphere around the centre of a scene's bounds.
struct Orbit {
  // About the +y axis, degrees; 0 is the +z side (where the default camera
  // stands), positive turns counter-clockwise seen from above (+90: the +x
  // side, 180: the -z side, -90 or 270: the -x side).
  float azimuth_deg = 0.f;
  // Above the horizontal (xz) plane, degrees, strictly between -90 and 90
  // (negative: from below).
  float elevation_deg = 0.f;
  // From the centre, > 0; none: the framing distance, at which the whole box
  // lies in view with a 10% margin.
  std::optional<float> distance;
};

// Empty when `orbit` is valid (finite, elevation strictly between -90 and 90,
// distance > 0), else what is wrong, one line naming AZ, EL or DIST.
std::string orbit_problem(const Orbit& orbit);

// The point a camera aims at when nothing else says where: the centre of
// `bounds`, or the origin when they are empty or not finite.
vec3 framing_target(const Bounds3& bounds);

// A perspective camera (aspect fit, vertical field of view fov_deg, up +y) at
// `orbit` around framing_target(bounds), looking at it. The framing distance
// keeps every corner of the box within the view with a 10% margin for any
// image at least as wide as it is tall; for empty bounds it is 5. Orbit{}
// (0, 0) is the default camera of bounds that are not flat (default_orbit):
// on the +z side, looking down -z. Throws
// rayform::Error for an orbit_problem or a fov outside (0, 180).
Camera orbit_camera(const Bounds3& bounds, const Orbit& orbit, float fov_deg = default_camera_fov_deg);

// Bounds whose extent along one axis is below this fraction of both other
// extents are flat: the default camera looks at their large face.
inline constexpr float flat_bounds_fraction = 0.25f;
// The default camera's elevation over flat bounds lying in the xz plane, degrees.
inline constexpr float flat_view_elevation_deg = 45.f;

// Where the default camera stands around `bounds`, so that it sees their
// largest face: Orbit{} (the +z side, looking down -z) unless the bounds are
// flat (flat_bounds_fraction); thin along y (a model lying in the xz plane),
// on the +z side looking down at flat_view_elevation_deg; thin along x, on
// the +x side (azimuth 90). Thin along z, empty or not finite: Orbit{}.
Orbit default_orbit(const Bounds3& bounds);

// `up`, unless it is parallel to `direction` (or zero); then +y, or for a
// vertical direction -z looking down and +z looking up (the limit of tilting
// the default camera's view over the top or under the bottom).
vec3 up_not_parallel(vec3 up, vec3 direction);

// When the scene has no camera, adds the default camera: orbit_camera at
// default_orbit with default_camera_fov_deg around the scene's bounds, named
// "default" (an empty scene gets a camera at (0, 0, 5)). Returns whether a
// camera was added. Throws rayform::Error when the node graph is invalid.
bool add_default_camera(Scene& scene);

// When the scene has no light, adds a white directional "headlight" shining
// along the view direction of camera `camera` (the first when out of range;
// down -z without a camera), so that every surface facing that camera is lit.
// Returns whether a light was added. Call add_default_camera, and apply any
// change to the camera, first.
bool add_headlight(Scene& scene, int camera = 0);

// The default light rig, three white directional lights fixed to the camera
// rendered, for a first picture that shows an asset's shape from any side.
// Each shines from `to_light`, given in the camera's frame (x right, y up, z
// back towards the viewer), with intensity `intensity`:
//   head-light  0.30  from the camera itself       (0, 0, 1)
//   key         0.70  from above, to the right     (1, 1, 1) / sqrt(3)
//   fill        0.20  from the left, a little low  (-1, -0.25, 1) / 1.436
// Every surface the camera sees gets some of the head-light; the key, the
// strongest, shades the sides differently from the top and the front, and
// the fill keeps the sides it misses from going black, so that the shape
// reads. The intensities keep a white diffuse surface within display range:
// one facing the camera gets 0.30 + 0.70 / sqrt(3) + 0.20 / 1.436 = 0.84, and
// no orientation gets more than the length of the intensity-weighted sum of
// the three directions, 0.96 (a surface lit by all three at once). Specular
// highlights and emission may still exceed 1.
struct RigLight {
  const char* name;
  vec3 to_light;  // camera frame, unit
  float intensity;
};
inline const RigLight light_rig[3] = {
    {"headlight", vec3(0.f, 0.f, 1.f), 0.30f},
    {"key", glm::normalize(vec3(1.f, 1.f, 1.f)), 0.70f},
    {"fill", glm::normalize(vec3(-1.f, -0.25f, 1.f)), 0.20f},
};

// When the scene has no light, adds light_rig placed by camera `camera`
// (the first when out of range; the default camera's frame, looking down -z
// with up +y, without a camera). Returns whether lights were added. Call
// add_default_camera, and apply any change to the camera, first: the lights
// are fixed in the world, where that camera's frame put them.
bool add_light_rig(Scene& scene, int camera = 0);

}  // namespace rayform
