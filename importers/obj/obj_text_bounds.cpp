#include "rayform/importers/obj/obj_text_bounds.h"

#include "rayform/base/error.h"

#include <algorithm>
#include <cstring>
#include <string_view>

namespace rayform::obj {

namespace {
// Pages walked past without a face are let go in steps of this many bytes.
constexpr size_t drop_step = size_t(64) << 20;

bool blank(char c) { return c == ' ' || c == '\t'; }
}  // namespace

void check_obj_text_bounds(const FileBytes& file, const std::string& path) {
  const std::string_view text = file.view();
  const char* data = text.data();
  size_t line = 1, dropped = 0;
  for (size_t p = 0; p < text.size(); ++line) {
    // The line's end: '\n', or a lone '\r' (tinyobjloader ends lines at either).
    const size_t window = std::min(text.size() - p, max_obj_line_bytes + 1);
    const char* nl = static_cast<const char*>(std::memchr(data + p, '\n', window));
    const char* cr = static_cast<const char*>(std::memchr(data + p, '\r', nl ? size_t(nl - (data + p)) : window));
    const char* end = cr ? cr : nl;
    const size_t length = end ? size_t(end - (data + p)) : window;
    if (length > max_obj_line_bytes)
      throw Error(path + ":" + std::to_string(line) + ": line longer than " + std::to_string(max_obj_line_bytes) +
                  " bytes (not an OBJ text)");
    size_t t = p;
    while (t < p + length && blank(data[t])) ++t;
    if (t + 1 < p + length && data[t] == 'f' && blank(data[t + 1])) return;
    p += length + (end ? 1 : 0);
    if (cr && p < text.size() && data[p] == '\n') ++p;  // "\r\n" is one line end
    if (p - dropped >= drop_step) {
      file.drop_pages(dropped, p);
      dropped = p;
    }
  }
  throw Error(path + ": OBJ file has no faces");
}

}  // namespace rayform::obj
