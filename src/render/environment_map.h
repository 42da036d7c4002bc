// Equirectangular environment maps (issue 31): radiance arriving from every
// direction, looked up from a latitude-longitude image, and its importance
// sampling by a piecewise-constant distribution over the texels.
//
// Mapping (../shared/reference-pbr/NOTES.md, verified against Cycles), in
// glTF coordinates (+Y up): for a direction d = (dx, dy, dz) of any length,
//   u = 0.5 + atan2(dz, dx) / (2 pi)   (mod 1, u in [0, 1), from the left edge)
//   v = acos(dy / |d|) / pi            (v in [0, 1], from the top edge)
// so +X is the image centre (0.5, 0.5), -Z u = 0.25, +Z u = 0.75, -X the
// left/right seam u = 0, +Y the top edge and -Y the bottom edge. Texel (i, j),
// j counted from the top row, covers [i, i+1) / W x [j, j+1) / H in (u, v)
// and is centred at ((i + 0.5) / W, (j + 0.5) / H).
//
// Rotation (--env-rotate): the environment is turned by `rotation` radians
// about +Y, right-handed (counter-clockwise seen from above): what the
// unrotated map shows in direction d appears in direction R_y(rotation) d, so
// the map's centre column (+X) appears towards (cos r, 0, -sin r). In (u, v)
// this adds rotation / (2 pi) to u: u = 0.5 + (atan2(dz, dx) + rotation) /
// (2 pi). Every function below applies it the same way.
//
// Lookups: environment_radiance takes the nearest texel (the radiance is then
// piecewise constant exactly as the sampling pdf is, which the furnace tests
// rely on); environment_radiance_bilinear interpolates between texel centres
// as Cycles does (periodic in u; clamped in v, where Cycles wraps v too: the
// two differ only within half a texel row of a pole), for what the camera
// sees. Both are scaled by the map's intensity.
//
// Sampling: texel (i, j) gets the weight w_ij = max(0, Y(texel)) sin(theta_j),
// Y the Rec. 709 luminance of the linear RGB and theta_j = pi (j + 0.5) / H
// the polar angle of the row centre. The density in (u, v) is piecewise
// constant, p_uv = w_ij W H / sum(w), sampled through the marginal CDF over
// rows and one conditional CDF per row; since d omega = 2 pi^2 sin(theta) du dv,
// the density in solid angle is p = p_uv / (2 pi^2 sin theta), theta the
// direction's own polar angle (p grows as 1 / sin theta towards the poles
// inside the first and last rows; it stays integrable). Texels of luminance
// <= 0 are never sampled: with bilinear radiance the estimator that samples
// the environment alone misses the light blended into them from neighbours,
// which BSDF sampling combined by MIS (light pdf 0 there) picks up. A map
// whose weights are all 0 (all black) is marked `samplable = false`:
// sample_environment then returns pdf 0 and radiance 0, and environment_pdf
// returns 0; its radiance is 0 everywhere (up to negative texels), so an
// integrator loses nothing by skipping it.
//
// Loading a file is not done here: read the float Image (image/image.h,
// read_image) and pass it to environment_from_image.
#pragma once

#include "rayform/math/math.h"

#include <vector>

namespace rayform {

struct Image;

// Relative luminance of linear Rec. 709 / sRGB primaries (the weights of
// ITU-R BT.709), in the units of the colour.
inline float environment_luminance(vec3 rgb) { return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b; }

struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width * height * 3 linear RGB radiance (W m^-2 sr^-1 up to scale), row 0 = top
  float intensity = 1.f;   // radiance scale applied by every lookup and sample (--env-intensity)
  float rotation = 0.f;    // radians about +Y, right-handed (--env-rotate, see above)

  // The sampling distribution (built by make_environment_map).
  std::vector<float> texel_weight;  // width * height: w_ij = max(0, luminance) sin(theta_j), row 0 = top
  std::vector<float> row_cdf;       // height + 1: marginal CDF over rows, row_cdf[0] = 0, row_cdf[height] = 1
  std::vector<float> column_cdf;    // height * (width + 1): per row its conditional CDF over the columns
  float pdf_uv_scale = 0.f;         // W H / sum(w): p_uv of texel (i, j) = texel_weight[j W + i] pdf_uv_scale
  bool samplable = false;           // false when every weight is 0: sampling returns pdf 0
};

// Builds a map from width * height * 3 floats (row 0 = top, linear RGB).
// Throws rayform::Error when a size is not positive, rgb has another length,
// a texel is not finite, or intensity is negative or not finite, or rotation
// is not finite. Texels may be negative (resampled HDR files hold a few);
// they are kept for lookups and weigh 0 for sampling.
EnvironmentMap make_environment_map(int width, int height, std::vector<float> rgb, float intensity = 1.f,
                                    float rotation_rad = 0.f);

// From a float image (image/image.h) of 3 (RGB) or 4 (RGBA, alpha ignored)
// channels; throws rayform::Error for any other channel count.
EnvironmentMap environment_from_image(const Image& image, float intensity = 1.f, float rotation_rad = 0.f);

// The mapping above. direction_to_uv takes any non-zero length (a zero or
// non-finite direction gives NaN); u is in [0, 1), v in [0, 1]. uv_to_direction
// returns a unit vector; u outside [0, 1) wraps.
vec2 direction_to_uv(vec3 direction, float rotation_rad = 0.f);
vec3 uv_to_direction(vec2 uv, float rotation_rad = 0.f);

// Radiance arriving from `direction` (any non-zero length), times intensity:
// the nearest texel, or bilinear between texel centres (see above). 0 for a
// zero or non-finite direction.
vec3 environment_radiance(const EnvironmentMap& map, vec3 direction);
vec3 environment_radiance_bilinear(const EnvironmentMap& map, vec3 direction);

struct EnvironmentSample {
  vec3 direction{0.f, 1.f, 0.f};  // unit, towards the environment
  vec3 radiance{0.f};             // the sampled texel's radiance times intensity (environment_radiance's value)
  float pdf = 0.f;                // per steradian; 0 when the map is not samplable
};

// A direction drawn with density environment_pdf from the uniform point u in
// [0, 1)^2 (u.y picks the row, u.x the column, each by its CDF, and the
// remainder places the point inside the texel uniformly in (u, v)). The pdf is
// the texel's p_uv / (2 pi^2 sin theta) at the sampled point. No allocation.
EnvironmentSample sample_environment(const EnvironmentMap& map, vec2 u);

// The density per steradian with which sample_environment draws `direction`
// (any non-zero length); 0 at the poles' single points, for a map that is not
// samplable, and for a zero or non-finite direction.
float environment_pdf(const EnvironmentMap& map, vec3 direction);

// The default environment, made by the program (issue 31: "a neutral studio,
// no file needed"), so that metals reflect something out of the box. Neutral
// grey (R = G = B) everywhere; linear radiance, the values below before the
// final scale (last item):
// - a backdrop by elevation e (radians above the horizon): a dark floor
//   (0.10 towards the nadir) rising through a soft horizon band (e from -0.25
//   to 0.10) to a light grey wall (0.42) and a brighter ceiling (0.55 at the
//   zenith);
// - three large soft-edged rectangular softboxes, each a rectangle in
//   (azimuth, elevation) around its centre direction with edges that fade over
//   a few degrees: a key light in front right above (towards +X, +Y, +Z: the
//   side a glTF front camera at +Z looks from), a dimmer fill front left lower,
//   and a rim light behind above (-Z);
// - everything scaled so that a white Lambertian surface facing +Y, lit by the
//   map read with nearest texels, has outgoing radiance E_up / pi =
//   studio_up_radiance (E_up = integral of L cos+ over the sphere, computed
//   exactly per texel row: a texel row's integral of cos(theta) sin(theta) is
//   closed form).
// width and height must be positive (height even keeps the horizon on a texel
// row boundary); intensity 1, rotation 0.
inline constexpr float studio_up_radiance = 0.8f;
EnvironmentMap studio_environment(int width = 256, int height = 128);

}  // namespace rayform
