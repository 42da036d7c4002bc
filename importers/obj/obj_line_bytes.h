// The byte-level pieces of the OBJ line walks (the text bounds check, the
// chunk scan, the plain chunks' face lines): the blanks tinyobjloader
// skips between words, and the search for the first of a few bytes.
#pragma once

#include <bit>
#include <cstddef>
#include <string_view>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rayform::obj {

// The blanks between a line's words, as tinyobjloader skips them.
inline bool is_space(char c) { return c == ' ' || c == '\t'; }

// s without its leading blanks.
inline std::string_view without_leading_blanks(std::string_view s) {
  size_t lead = 0;
  while (lead < s.size() && is_space(s[lead])) ++lead;
  s.remove_prefix(lead);
  return s;
}

// The first byte of data[p, stop) that is one of Bytes, or stop. 16 bytes a
// step with SSE2: lines of numbers are short, and a call of memchr a line
// costs more than its bytes.
template <char... Bytes>
inline size_t find_first_byte(const char* data, size_t p, size_t stop) {
#if defined(__SSE2__)
  for (; p + 16 <= stop; p += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(data + p));
    __m128i any = _mm_setzero_si128();
    ((any = _mm_or_si128(any, _mm_cmpeq_epi8(x, _mm_set1_epi8(Bytes)))), ...);
    const unsigned hits = unsigned(_mm_movemask_epi8(any));
    if (hits) return p + size_t(std::countr_zero(hits));
  }
#endif
  for (; p < stop; ++p)
    if (((data[p] == Bytes) || ...)) return p;
  return stop;
}

}  // namespace rayform::obj
