#include "messages.h"

#include <cstdint>
#include <cstdio>
#include <iostream>

namespace rayform::cli {
namespace {
bool quiet_ = false;

void say(const char* kind, const std::string& message) {
  if (!quiet_) std::cerr << kind + terminal_text(message) + "\n";
}

// The length of the well-formed UTF-8 sequence at text[i] (2 to 4 bytes:
// no overlong form, no surrogate, at most U+10FFFF) and its code point; 0
// when there is none.
size_t utf8_sequence(const std::string& text, size_t i, uint32_t* code) {
  const auto byte = [&](size_t k) { return i + k < text.size() ? uint8_t(text[i + k]) : uint8_t(0); };
  const uint8_t b0 = byte(0);
  size_t n = 0;
  uint32_t c = 0, least = 0;
  if (b0 >= 0xc2 && b0 <= 0xdf) n = 2, c = b0 & 0x1fu, least = 0x80;
  else if (b0 >= 0xe0 && b0 <= 0xef) n = 3, c = b0 & 0x0fu, least = 0x800;
  else if (b0 >= 0xf0 && b0 <= 0xf4) n = 4, c = b0 & 0x07u, least = 0x10000;
  else return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(k) & 0xc0) != 0x80) return 0;
    c = (c << 6) | (byte(k) & 0x3fu);
  }
  if (c < least || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff)) return 0;
  *code = c;
  return n;
}
}  // namespace

std::string terminal_text(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  auto escape = [&](uint32_t c) {
    char u[8];
    std::snprintf(u, sizeof u, "\\u%04x", unsigned(c));
    out += u;
  };
  for (size_t i = 0; i < text.size();) {
    const uint8_t b = uint8_t(text[i]);
    if (b < 0x80) {
      if (b < 0x20 || b == 0x7f) escape(b);
      else out += char(b);
      ++i;
      continue;
    }
    uint32_t code = 0;
    const size_t n = utf8_sequence(text, i, &code);
    if (n == 0) {
      out += "\xef\xbf\xbd";  // U+FFFD REPLACEMENT CHARACTER
      ++i;
    } else {
      if (code <= 0x9f) escape(code);  // C1 controls (8-bit CSI and the like)
      else out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

void set_quiet(bool quiet) { quiet_ = quiet; }
bool quiet() { return quiet_; }

void warn(const std::string& message) { say("warning: ", message); }
void note(const std::string& message) { say("note: ", message); }

}  // namespace rayform::cli
