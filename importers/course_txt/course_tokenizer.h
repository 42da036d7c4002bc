// Tokens of the course format: white-space separated words, with '{' and '}'
// always tokens of their own (so `shininess 20}` reads as three tokens) and
// `#` comments to the end of the line. Every token remembers its line and
// column (1-based) for error messages.
#pragma once

#include "rayform/math/math.h"

#include <string>
#include <string_view>
#include <vector>

namespace rayform {

struct Token {
  std::string text;
  int line = 0, column = 0;
};

class CourseTokenizer {
 public:
  CourseTokenizer(std::string_view text, std::string path);

  bool at_end() const { return pos_ >= tokens_.size(); }
  Token next();  // call only when !at_end()
  // The next token, or an error "unexpected end of file: expected <what>".
  Token next_or_fail(const std::string& what);
  Token peek_token() const;  // the next token (or an end-of-file position)
  const Token& last() const { return tokens_[pos_ - 1]; }

  void expect(std::string_view word, std::string_view context);
  float number();  // a finite number
  int count();     // a non-negative integer
  vec3 vec3_value() {
    float x = number(), y = number(), z = number();
    return vec3(x, y, z);
  }

  std::string where(const Token& t) const;     // "file:line:column"
  std::string line_col(const Token& t) const;  // "line:column"
  [[noreturn]] void fail(const Token& t, const std::string& message) const;

 private:
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  std::string path_;
  int end_line_ = 1, end_column_ = 1;
};

// A token's text as an error message shows it: at most 64 bytes, then "...".
std::string shown(std::string_view text);

// The words of a scene text that choose its dialect (course_reader.h).
struct CourseDialectMarks {
  bool v2019 = false;        // falloff or bump (2019, unless an a5 mark or .bmp faces say a5)
  bool a5 = false;           // Noise or refractionIndex (assignment 5)
  std::string cube_map_dir;  // the folder after the last cubeMap, if any
};
CourseDialectMarks course_dialect_marks(std::string_view text);

}  // namespace rayform
