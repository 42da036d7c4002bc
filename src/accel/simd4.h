// Four-lane float vectors for the mesh BVH: SSE2 on x86-64 (part of the base
// instruction set, so no special compiler flags), a portable scalar version
// elsewhere. Every operation is a plain IEEE one, lane by lane, so that a
// kernel written with them gives exactly the results of its scalar original.
// min/max follow the SSE rule: vmin(a, b) = a < b ? a : b and
// vmax(a, b) = a > b ? a : b (the second operand when either is NaN).
#pragma once

#include <cmath>
#include <cstdint>

#if defined(__SSE2__) && !defined(RAYFORM_NO_SIMD)
#define RAYFORM_SIMD4_SSE 1
#include <emmintrin.h>
#endif

namespace rayform::simd {

#if RAYFORM_SIMD4_SSE

struct f4 {
  __m128 v;
};
struct m4 {
  __m128 v;
};

inline f4 load(const float* p) { return {_mm_load_ps(p)}; }  // 16-byte aligned
inline f4 loadu(const float* p) { return {_mm_loadu_ps(p)}; }
inline void store(float* p, f4 a) { _mm_storeu_ps(p, a.v); }
inline f4 splat(float x) { return {_mm_set1_ps(x)}; }
inline f4 operator+(f4 a, f4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline f4 operator-(f4 a, f4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline f4 operator*(f4 a, f4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline f4 operator/(f4 a, f4 b) { return {_mm_div_ps(a.v, b.v)}; }
inline f4 vmin(f4 a, f4 b) { return {_mm_min_ps(a.v, b.v)}; }
inline f4 vmax(f4 a, f4 b) { return {_mm_max_ps(a.v, b.v)}; }
inline f4 vabs(f4 a) { return {_mm_and_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)))}; }
inline f4 vsqrt(f4 a) { return {_mm_sqrt_ps(a.v)}; }  // correctly rounded, as std::sqrt
inline m4 operator<(f4 a, f4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
inline m4 operator<=(f4 a, f4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
inline m4 operator>(f4 a, f4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline m4 operator>=(f4 a, f4 b) { return {_mm_cmpge_ps(a.v, b.v)}; }
inline m4 operator==(f4 a, f4 b) { return {_mm_cmpeq_ps(a.v, b.v)}; }
inline m4 operator|(m4 a, m4 b) { return {_mm_or_ps(a.v, b.v)}; }
inline m4 operator&(m4 a, m4 b) { return {_mm_and_ps(a.v, b.v)}; }
inline m4 andnot(m4 a, m4 b) { return {_mm_andnot_ps(b.v, a.v)}; }  // a & ~b
inline m4 operator~(m4 a) { return {_mm_xor_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(-1)))}; }
inline int mask_bits(m4 m) { return _mm_movemask_ps(m.v); }
// Half the surface area of the box [lo, hi] (lanes 0..2), 0 when empty.
inline float half_area(f4 lo, f4 hi) {
  __m128 e = _mm_sub_ps(hi.v, lo.v);
  if ((_mm_movemask_ps(_mm_cmpge_ps(e, _mm_setzero_ps())) & 7) != 7) return 0.f;
  __m128 p = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1)));  // ex ey, ey ez, ez ex
  p = _mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_movehl_ps(p, p));
  return _mm_cvtss_f32(p);
}
// Lanes converted to int, truncating; then clamped to [0, hi].
inline void to_int_clamped(f4 a, int hi, int out[4]) {
  __m128i i = _mm_cvttps_epi32(a.v);
  __m128i z = _mm_setzero_si128(), h = _mm_set1_epi32(hi);
  // SSE2 has no 32-bit min/max: compare and blend.
  __m128i lt0 = _mm_cmplt_epi32(i, z);
  i = _mm_andnot_si128(lt0, i);
  __m128i gth = _mm_cmpgt_epi32(i, h);
  i = _mm_or_si128(_mm_and_si128(gth, h), _mm_andnot_si128(gth, i));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), i);
}

#else

struct f4 {
  float v[4];
};
struct m4 {
  uint32_t v[4];
};

#define RAYFORM_F4_OP(expr)                    \
  f4 r;                                        \
  for (int i = 0; i < 4; ++i) r.v[i] = (expr); \
  return r
#define RAYFORM_M4_OP(expr)                               \
  m4 r;                                                   \
  for (int i = 0; i < 4; ++i) r.v[i] = (expr) ? ~0u : 0u; \
  return r

inline f4 load(const float* p) { RAYFORM_F4_OP(p[i]); }
inline f4 loadu(const float* p) { RAYFORM_F4_OP(p[i]); }
inline void store(float* p, f4 a) {
  for (int i = 0; i < 4; ++i) p[i] = a.v[i];
}
inline f4 splat(float x) { RAYFORM_F4_OP(x); }
inline f4 operator+(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] + b.v[i]); }
inline f4 operator-(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] - b.v[i]); }
inline f4 operator*(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] * b.v[i]); }
inline f4 operator/(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] / b.v[i]); }
inline f4 vmin(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] < b.v[i] ? a.v[i] : b.v[i]); }
inline f4 vmax(f4 a, f4 b) { RAYFORM_F4_OP(a.v[i] > b.v[i] ? a.v[i] : b.v[i]); }
inline f4 vabs(f4 a) { RAYFORM_F4_OP(std::fabs(a.v[i])); }
inline f4 vsqrt(f4 a) { RAYFORM_F4_OP(std::sqrt(a.v[i])); }
inline m4 operator<(f4 a, f4 b) { RAYFORM_M4_OP(a.v[i] < b.v[i]); }
inline m4 operator<=(f4 a, f4 b) { RAYFORM_M4_OP(a.v[i] <= b.v[i]); }
inline m4 operator>(f4 a, f4 b) { RAYFORM_M4_OP(a.v[i] > b.v[i]); }
inline m4 operator>=(f4 a, f4 b) { RAYFORM_M4_OP(a.v[i] >= b.v[i]); }
inline m4 operator==(f4 a, f4 b) { RAYFORM_M4_OP(a.v[i] == b.v[i]); }
inline m4 operator|(m4 a, m4 b) {
  m4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] | b.v[i];
  return r;
}
inline m4 operator&(m4 a, m4 b) {
  m4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] & b.v[i];
  return r;
}
inline m4 andnot(m4 a, m4 b) {
  m4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = a.v[i] & ~b.v[i];
  return r;
}
inline m4 operator~(m4 a) {
  m4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = ~a.v[i];
  return r;
}
inline int mask_bits(m4 m) {
  int r = 0;
  for (int i = 0; i < 4; ++i) r |= int(m.v[i] >> 31) << i;
  return r;
}
inline float half_area(f4 lo, f4 hi) {
  float ex = hi.v[0] - lo.v[0], ey = hi.v[1] - lo.v[1], ez = hi.v[2] - lo.v[2];
  if (!(ex >= 0.f && ey >= 0.f && ez >= 0.f)) return 0.f;
  return ex * ey + ey * ez + ez * ex;
}
inline void to_int_clamped(f4 a, int hi, int out[4]) {
  for (int i = 0; i < 4; ++i) {
    float x = a.v[i];
    out[i] = !(x >= 1.f) ? 0 : (x >= float(hi) ? hi : int(x));  // NaN and negatives: 0
  }
}
#undef RAYFORM_F4_OP
#undef RAYFORM_M4_OP

#endif

}  // namespace rayform::simd
