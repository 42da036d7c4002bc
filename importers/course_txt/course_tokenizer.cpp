#include "rayform/importers/course_txt/course_tokenizer.h"

#include "rayform/base/error.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace rayform {

CourseTokenizer::CourseTokenizer(std::string_view text, std::string path) : path_(std::move(path)) {
  int line = 1, col = 1;
  size_t i = 0;
  auto advance = [&](char c) {
    if (c == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  };
  while (i < text.size()) {
    char c = text[i];
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') {
        advance(text[i]);
        ++i;
      }
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c)) || c == '\0') {
      advance(c);
      ++i;
      continue;
    }
    Token t;
    t.line = line;
    t.column = col;
    if (c == '{' || c == '}') {
      t.text = std::string(1, c);
      advance(c);
      ++i;
    } else {
      size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '{' &&
             text[i] != '}' && text[i] != '#' && text[i] != '\0') {
        advance(text[i]);
        ++i;
      }
      t.text = std::string(text.substr(start, i - start));
    }
    tokens_.push_back(std::move(t));
  }
  end_line_ = line;
  end_column_ = col;
}

Token CourseTokenizer::next() { return tokens_[pos_++]; }

Token CourseTokenizer::peek_token() const {
  if (!at_end()) return tokens_[pos_];
  return Token{"", end_line_, end_column_};
}

Token CourseTokenizer::next_or_fail(const std::string& what) {
  if (at_end()) fail(peek_token(), "unexpected end of file: expected " + what);
  return next();
}

std::string CourseTokenizer::line_col(const Token& t) const {
  return std::to_string(t.line) + ":" + std::to_string(t.column);
}
std::string CourseTokenizer::where(const Token& t) const { return path_ + ":" + line_col(t); }

std::string shown(std::string_view text) {
  constexpr size_t most = 64;
  if (text.size() <= most) return std::string(text);
  return std::string(text.substr(0, most)) + "...";
}

void CourseTokenizer::fail(const Token& t, const std::string& message) const { throw Error(where(t) + ": " + message); }

void CourseTokenizer::expect(std::string_view word, std::string_view context) {
  std::string what = "'";  // (built by appends: GCC 12 warns falsely on "'" + string)
  what.append(word).append("' in ").append(context);
  Token t = next_or_fail(what);
  if (t.text != word) fail(t, "expected " + what + ", found '" + shown(t.text) + "'");
}

float CourseTokenizer::number() {
  Token t = next_or_fail("a number");
  const char* s = t.text.c_str();
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s, &end);
  if (end == s || *end != '\0') fail(t, "expected a number, found '" + shown(t.text) + "'");
  if (!std::isfinite(v) || errno == ERANGE || std::abs(v) > 3.4e38)
    fail(t, "expected a finite number, found '" + shown(t.text) + "'");
  return float(v);
}

int CourseTokenizer::count() {
  Token t = next_or_fail("a whole number");
  const char* s = t.text.c_str();
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(s, &end, 10);
  if (end == s || *end != '\0' || errno == ERANGE) fail(t, "expected a whole number, found '" + shown(t.text) + "'");
  if (v < 0 || v > 100000000) fail(t, "expected a count between 0 and 100000000, found '" + shown(t.text) + "'");
  return int(v);
}

CourseDialectMarks course_dialect_marks(std::string_view text) {
  CourseDialectMarks marks;
  CourseTokenizer tk(text, "");
  while (!tk.at_end()) {
    Token t = tk.next();
    if (t.text == "falloff" || t.text == "bump") marks.v2019 = true;
    else if (t.text == "Noise" || t.text == "refractionIndex") marks.a5 = true;
    else if (t.text == "cubeMap" && !tk.at_end()) marks.cube_map_dir = tk.next().text;
  }
  return marks;
}

}  // namespace rayform
