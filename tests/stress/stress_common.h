// Shared helpers of the numerical stress suite: the size knob, a small
// deterministic random generator, long double vectors for the references,
// random transforms, a parallel sample loop with deterministic per-chunk
// seeds, and reporting of "ours vs fixed epsilon" counts.
#pragma once

#include "rayform/math/math.h"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>

namespace rayform::stress {

// RAYFORM_STRESS_SCALE multiplies every sample count (default 1; e.g. 10 for a long run).
inline double stress_scale() {
  const char* e = std::getenv("RAYFORM_STRESS_SCALE");
  if (!e || !*e) return 1.0;
  double s = std::atof(e);
  return s > 0.0 ? s : 1.0;
}
inline int64_t scaled(int64_t n) { return int64_t(double(n) * stress_scale()); }

// SplitMix64: tiny, fast and the same on every platform (unlike std:: distributions).
struct Rng {
  uint64_t state;
  explicit Rng(uint64_t seed) : state(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1p-53; }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
  uint32_t index(uint32_t n) { return uint32_t(uniform() * n) % n; }
  dvec3 unit_vector() {
    double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * 3.14159265358979323846);
    double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
  // Uniform random rotation (unit quaternion from four normals' directions).
  glm::dmat3 rotation() {
    double u1 = uniform(), u2 = uniform(), u3 = uniform();
    const double tau = 2.0 * 3.14159265358979323846;
    double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    double x = a * std::sin(tau * u2), y = a * std::cos(tau * u2), z = b * std::sin(tau * u3),
           w = b * std::cos(tau * u3);
    glm::dmat3 m;
    m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    m[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    m[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    return m;
  }
};

// Long double vectors for the reference computations.
using ld = long double;
struct lvec3 {
  ld x = 0, y = 0, z = 0;
  lvec3() = default;
  lvec3(ld a, ld b, ld c) : x(a), y(b), z(c) {}
  explicit lvec3(vec3 v) : x(v.x), y(v.y), z(v.z) {}
  explicit lvec3(dvec3 v) : x(v.x), y(v.y), z(v.z) {}
  ld operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  ld& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  vec3 to_float() const { return vec3(float(x), float(y), float(z)); }
};
inline lvec3 operator+(lvec3 a, lvec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline lvec3 operator-(lvec3 a, lvec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline lvec3 operator*(ld s, lvec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline ld dot(lvec3 a, lvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline lvec3 cross(lvec3 a, lvec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline ld length(lvec3 a) { return std::sqrt(dot(a, a)); }

// An affine float matrix (as the renderer stores it) and the exact inverse of
// that float matrix, in long double: the "true" object-to-world map is the
// float matrix applied without rounding.
struct LAffine {
  ld m[3][4];  // rows: m[i][0..2] linear part, m[i][3] translation
  lvec3 point(lvec3 p) const {
    lvec3 r;
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3];
    return r;
  }
  lvec3 vector(lvec3 v) const {
    lvec3 r;
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v.x + m[i][1] * v.y + m[i][2] * v.z;
    return r;
  }
};
inline LAffine to_laffine(const mat4& f) {
  LAffine a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) a.m[i][j] = f[j][i];
  return a;
}
inline LAffine inverse(const LAffine& a) {
  const auto& m = a.m;
  ld c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
     c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  ld det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  LAffine r;
  r.m[0][0] = c00 / det;
  r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r.m[1][0] = c01 / det;
  r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r.m[2][0] = c02 / det;
  r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  for (int i = 0; i < 3; ++i) r.m[i][3] = -(r.m[i][0] * m[0][3] + r.m[i][1] * m[1][3] + r.m[i][2] * m[2][3]);
  return r;
}

// Object-to-world matrix: translate(t) * rotate(rot) * scale(s), rounded to float once.
inline mat4 make_affine(const glm::dmat3& rot, dvec3 s, dvec3 t) {
  mat4 m(1.f);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c][r] = float(rot[c][r] * s[c]);
  m[3] = vec4(float(t.x), float(t.y), float(t.z), 1.f);
  return m;
}

// Runs fn(rng, counters, begin, end) over [0, n) in chunks in parallel; chunk
// k gets the seed (seed, k), so the counts do not depend on the thread count.
// Counters must have operator+=.
template <class Counters, class Fn>
Counters parallel_samples(int64_t n, int64_t chunk, uint64_t seed, Fn&& fn) {
  Counters total{};
  std::mutex mu;
  const int64_t chunks = (n + chunk - 1) / chunk;
  tbb::parallel_for(tbb::blocked_range<int64_t>(0, chunks, 1), [&](const tbb::blocked_range<int64_t>& r) {
    for (int64_t k = r.begin(); k < r.end(); ++k) {
      Rng rng(seed * 1000003ull + uint64_t(k));
      Counters c{};
      fn(rng, c, k * chunk, std::min(n, (k + 1) * chunk));
      std::lock_guard lock(mu);
      total += c;
    }
  });
  return total;
}

// Prints one result row and records it as test properties (in the XML report).
inline void report(const std::string& what, int64_t samples, int64_t ours_failures, int64_t naive_failures,
                   const std::string& naive_name) {
  std::cout << "[stress] " << what << ": " << samples << " samples, ours " << ours_failures << " failures, "
            << naive_name << " " << naive_failures << " failures\n";
  ::testing::Test::RecordProperty(what + ".samples", std::to_string(samples));
  ::testing::Test::RecordProperty(what + ".ours_failures", std::to_string(ours_failures));
  ::testing::Test::RecordProperty(what + ".fixed_eps_failures", std::to_string(naive_failures));
}

}  // namespace rayform::stress
