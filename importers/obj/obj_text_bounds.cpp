#include "rayform/importers/obj/obj_text_bounds.h"

#include "rayform/base/error.h"
#include "rayform/importers/obj/obj_line_bytes.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <string_view>

namespace rayform::obj {

namespace {
// Pages walked past without a face are let go in steps of this many bytes.
constexpr size_t drop_step = size_t(64) << 20;

// Whether a line "f <blank>..." begins right after a '\n' at some q in
// [from, to) (1 <= from, to <= n - 1, n the bytes looked at). One memchr for
// 'f' over lines of numbers (which hold none).
bool face_line_in(const char* data, size_t from, size_t to) {
  for (size_t p = from; p < to;) {
    const char* f = static_cast<const char*>(std::memchr(data + p, 'f', to - p));
    if (!f) return false;
    const size_t q = size_t(f - data);
    if (data[q - 1] == '\n' && is_space(data[q + 1])) return true;
    p = q + 1;
  }
  return false;
}

// Whether a line "f <blank>..." begins right after a '\n' in the first
// max_obj_line_bytes bytes. Then no line before it is longer than the bound,
// and it is a face line: the walk below would stop at it or at an earlier
// face. With several threads, waves of a block a thread, in order, until a
// wave holds one: the answer does not depend on which match is found, and
// the first touch of the file's pages (most of the time) is shared.
bool early_face(std::string_view text) {
  const char* data = text.data();
  const size_t n = std::min(text.size(), max_obj_line_bytes);
  if (n < 3) return false;
  const size_t threads = size_t(tbb::this_task_arena::max_concurrency());
  constexpr size_t block = size_t(1) << 20;
  if (threads == 1 || n < 2 * block) return face_line_in(data, 1, n - 1);
  for (size_t wave = 1; wave < n - 1; wave += threads * block) {
    std::atomic<bool> found{false};
    tbb::parallel_for(size_t(0), threads, [&](size_t k) {
      const size_t from = wave + k * block, to = std::min(n - 1, from + block);
      if (from < to && face_line_in(data, from, to)) found.store(true, std::memory_order_relaxed);
    });
    if (found.load()) return true;
  }
  return false;
}

}  // namespace

void check_obj_text_bounds(const FileBytes& file, const std::string& path) {
  const std::string_view text = file.view();
  if (early_face(text)) return;
  const char* data = text.data();
  size_t line = 1, dropped = 0;
  for (size_t p = 0; p < text.size(); ++line) {
    // The line's end: '\n', or a lone '\r' (tinyobjloader ends lines at either).
    const size_t window = std::min(text.size() - p, max_obj_line_bytes + 1);
    const size_t end = find_first_byte<'\n', '\r'>(data, p, p + window);
    const bool found = end < p + window, cr = found && data[end] == '\r';
    const size_t length = end - p;
    if (length > max_obj_line_bytes)
      throw Error(path + ":" + std::to_string(line) + ": line longer than " + std::to_string(max_obj_line_bytes) +
                  " bytes (not an OBJ text)");
    size_t t = p;
    while (t < p + length && is_space(data[t])) ++t;
    if (t + 1 < p + length && data[t] == 'f' && is_space(data[t + 1])) return;
    p += length + (found ? 1 : 0);
    if (cr && p < text.size() && data[p] == '\n') ++p;  // "\r\n" is one line end
    if (p - dropped >= drop_step) {
      file.drop_pages(dropped, p);
      dropped = p;
    }
  }
  throw Error(path + ": OBJ file has no faces");
}

}  // namespace rayform::obj
