// The dialects of the MIT 6.837 course scene format (docs/course-format.md),
// shared by the course reader, the course writer and save_scene's options:
// 2012 (assignment 4, the default), 2019, and a5 (2012's assignment 5: the
// ray tracer with refraction, Noise and .bmp cube maps).
#pragma once

#include <string_view>

namespace rayform {

enum class CourseDialect { v2012, v2019, a5 };

// "2012", "2019" or "a5", as the command lines spell it.
constexpr std::string_view course_dialect_name(CourseDialect d) {
  return d == CourseDialect::v2019 ? "2019" : d == CourseDialect::a5 ? "a5" : "2012";
}

// The reflection/refraction depth of an a5 render whose command line gives
// no -bounces (the solution's default); 2012 and 2019 default to 0.
inline constexpr int course_a5_default_bounces = 4;

}  // namespace rayform
