// A read-only std::streambuf over text kept elsewhere (tinyobjloader reads a
// std::istream; std::istringstream would copy the whole file), optionally
// preceded by a second, short piece of text (a few lines put before a chunk
// of a file).
#pragma once

#include <streambuf>
#include <string_view>

namespace rayform {

class TextStreamBuffer : public std::streambuf {
 public:
  explicit TextStreamBuffer(std::string_view text) : TextStreamBuffer({}, text) {}
  TextStreamBuffer(std::string_view first, std::string_view then) : then_(then) {
    if (first.empty()) {
      show(then_);
      then_ = {};
    } else {
      show(first);
    }
  }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (then_.empty()) return traits_type::eof();
    show(then_);
    then_ = {};
    return traits_type::to_int_type(*gptr());
  }

 private:
  void show(std::string_view s) {
    char* first = const_cast<char*>(s.data());  // never written: get area only
    setg(first, first, first + s.size());
  }

  std::string_view then_;
};

}  // namespace rayform
