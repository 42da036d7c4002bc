// Ken Perlin's improved noise (SIGGRAPH 2002, "Improving Noise"), with his
// reference permutation table: a smooth pseudo-random function of a 3-D
// point, 0 at every integer lattice point, periodic with period 256 in each
// axis, and bounded by 1 in magnitude. Computed in double as the reference
// (Java) implementation does. The course's a5 `Noise` material is built on
// it (scene.h: SolidNoise, course_noise below).
#pragma once

#include "rayform/math/math.h"

#include <array>
#include <cstdint>

namespace rayform {

// The reference permutation of 0..255 (Perlin 2002).
extern const std::array<uint8_t, 256> perlin_permutation;

// The improved noise at (x, y, z).
double perlin_noise(double x, double y, double z);

// The course's turbulence-modulated sine at world point p:
//   M = sin(frequency * p.x + amplitude * sum_{i < octaves} perlin_noise(2^i p) / 2^i),
// returned as the weight w = (M + 1) / 2 of the first colour (0..1).
float course_noise_weight(vec3 p, int octaves, float frequency, float amplitude);

}  // namespace rayform
