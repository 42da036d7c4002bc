// Noise-free approximations of environment lighting (issue 31), for the
// deterministic first picture (1 sample a pixel): the diffuse irradiance from
// order-2 spherical harmonics, and the specular reflection from the
// environment prefiltered by the GGX lobe (the split-sum's first factor; the
// second is ggx_split_sum in pbr_brdf.h).
//
// Frames: everything here is in the world frame (glTF, +Y up), with the map's
// rotation and intensity applied (environment_map.h), so an integrator passes
// world directions and normals and gets radiance / irradiance in the map's
// radiance units.
//
// Spherical harmonics: the 9 real basis functions of Ramamoorthi and Hanrahan
// (2001) in world x, y, z of a unit direction, in the order
//   0: Y00 = 0.282095
//   1: Y1-1 = 0.488603 y, 2: Y10 = 0.488603 z, 3: Y11 = 0.488603 x
//   4: Y2-2 = 1.092548 x y, 5: Y2-1 = 1.092548 y z, 6: Y20 = 0.315392 (3 z^2 - 1)
//   7: Y21 = 1.092548 x z, 8: Y22 = 0.546274 (x^2 - y^2)
// (the basis spans the polynomials of degree <= 2 whatever axis is taken as
// the pole). The coefficients L_lm = integral of L(w) Y_lm(w) dw are summed
// over the map's texels, each weighted by its exact solid angle (2 pi / W)
// (cos theta_top - cos theta_bottom) and evaluated at its centre.
//
// Prefiltering: the map is first averaged (solid-angle weighted) down to a
// source of at most 128 x 64 texels for level 1 and 64 x 32 beyond. Level 1 is
// stored as 64 x 32 texels, levels 2 and up as 32 x 16 (each no larger than
// the map). Texel R of level k is sum_l w(R, l) L(l) / sum_l w(R, l) over the
// source texels l, w = D(n.h) max(0, n.l) Omega_l with n = v = R, D the GGX
// distribution at alpha = ggx_alpha(k / (levels - 1)), h = normalize(R + l)
// and Omega_l the source texel's solid angle: the split-sum's prefiltered
// radiance (Karis 2013) with its n.l weighting, evaluated as a sum over every
// source texel instead of by importance sampling (no noise). A constant map
// stays that constant; the kernel depends on R.l only, so the integral of a
// level over the sphere equals the map's up to the discretisation.
#pragma once

#include "rayform/math/math.h"
#include "rayform/render/environment_map.h"

#include <array>
#include <vector>

namespace rayform {

// Order-2 spherical harmonics of an environment's radiance (Ramamoorthi and
// Hanrahan 2001), world frame (the map's rotation and intensity applied);
// sh[k] is the RGB coefficient of basis function k above.
struct EnvironmentIrradiance {
  std::array<vec3, 9> sh{};
};
// All zero for an empty map (width or height 0).
EnvironmentIrradiance environment_irradiance(const EnvironmentMap& env);
// Unshadowed irradiance E(n) = integral of L(w) max(0, n.w) dw at unit normal
// n (W m^-2 when L is in W m^-2 sr^-1), from the SH (the cosine's convolution:
// A0 = pi, A1 = 2 pi / 3, A2 = pi / 4). A Lambertian surface of albedo rho
// reflects rho E / pi. Exact for radiance that is a polynomial of degree <= 2
// in the direction (and for any map whose radiance depends on one axis only
// through a step at the equator: E = pi (1 + n.a) / 2 for L = 1 on the half
// towards a); in general it can be slightly negative where a map is very
// bright on one side: the caller may clamp it at 0.
vec3 irradiance(const EnvironmentIrradiance& e, vec3 n);

// The environment blurred for rough reflections (the split-sum's prefiltered
// radiance): level k of `levels` (level_count) is for perceptual roughness
// k / (levels - 1); level 0 is not stored (the map itself is used), so
// levels[k - 1] holds level k. Each stored level is an equirectangular map
// (64 x 32 for level 1 and 32 x 16 beyond, never larger than the map; see
// above) whose texel in direction R is the GGX-weighted mean of the radiance
// around R with n = v = R, intensity and rotation applied (its own intensity
// is 1 and rotation 0).
struct PrefilteredEnvironment {
  std::vector<EnvironmentMap> levels;
  int level_count = 0;
};
// levels below 2 (or an empty map) store no level: prefiltered_radiance then
// reads the map itself for every roughness. Parallel over output rows (TBB).
PrefilteredEnvironment prefilter_environment(const EnvironmentMap& env, int levels = 6);
// The radiance reflected from `direction` (any non-zero length) by a lobe of
// this perceptual roughness (clamped to [0, 1]): bilinear within the two
// nearest levels and linear between them in roughness; level 0 is
// environment_radiance_bilinear(env, direction), so roughness 0 gives exactly
// that and roughness below 1 / (levels - 1) blends it with level 1. `env` must
// be the map `p` was made from. No allocation.
vec3 prefiltered_radiance(const PrefilteredEnvironment& p, const EnvironmentMap& env, vec3 direction, float roughness);

}  // namespace rayform
