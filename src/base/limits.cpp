#include "rayform/base/limits.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <unistd.h>

namespace rayform {
namespace {
constexpr uint64_t unbounded = std::numeric_limits<uint64_t>::max();

struct NamedLimit {
  const char* name;
  uint64_t Limits::*field;
  uint64_t most;  // the largest value that is safe to set
};
// clang-format off
constexpr NamedLimit named_limits[] = {
    {"triangles", &Limits::triangles, unbounded},
    {"vertices", &Limits::vertices, unbounded},
    {"unbacked-elements", &Limits::unbacked_elements, unbounded},
    {"instances", &Limits::instances, unbounded},
    {"texture-texels", &Limits::texture_texels, unbounded},
    {"json-depth", &Limits::json_depth, max_json_depth},
    {"memory", &Limits::memory, unbounded},
};
// clang-format on
}  // namespace

uint64_t physical_memory_bytes() {
  static const uint64_t bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages <= 0 || page <= 0 ? uint64_t(0) : uint64_t(pages) * uint64_t(page);
  }();
  return bytes;
}

uint64_t default_memory_limit() {
  const uint64_t physical = physical_memory_bytes();
  return physical == 0 ? uint64_t(1) << 30 : std::max(physical / 16, uint64_t(256) << 20);
}

std::string limit_names() {
  std::string out;
  for (const NamedLimit& l : named_limits) out += (out.empty() ? "" : ", ") + std::string(l.name);
  return out;
}

std::string set_limit(Limits& limits, const std::string& name, const std::string& value) {
  for (const NamedLimit& l : named_limits) {
    if (name != l.name) continue;
    const std::string too_large =
        "limit " + name + ": " + value + " is too large (at most " + std::to_string(l.most) + ")";
    uint64_t v = 0;
    size_t i = 0;
    for (; i < value.size() && std::isdigit(static_cast<unsigned char>(value[i])); ++i) {
      const uint64_t digit = uint64_t(value[i] - '0');
      if (v > (unbounded - digit) / 10) return too_large;
      v = v * 10 + digit;
    }
    uint64_t scale = 1;
    if (i + 1 == value.size()) {
      switch (value[i]) {
        case 'k': scale = 1000; break;
        case 'M': scale = 1000 * 1000; break;
        case 'G': scale = 1000 * 1000 * 1000; break;
        default: scale = 0;
      }
      ++i;
    }
    if (i == 0 || i != value.size() || scale == 0 || v == 0)
      return "limit " + name + ": expected a positive whole number (optionally with k, M or G), got '" + value + "'";
    if (v > unbounded / scale || v * scale > l.most) return too_large;
    limits.*l.field = v * scale;
    return "";
  }
  return "unknown limit '" + name + "' (expected one of: " + limit_names() + ")";
}

std::string limit_exceeded(const char* name, uint64_t count, uint64_t limit) {
  return std::string(name) + ": " + std::to_string(count) + " is more than the limit of " + std::to_string(limit) +
         " (raise it with --limit " + name + "=N)";
}

}  // namespace rayform
