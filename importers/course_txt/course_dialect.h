// The two dialects of the MIT 6.837 course scene format (docs/course-format.md),
// shared by the course reader, the course writer and save_scene's options.
#pragma once

namespace rayform {

enum class CourseDialect { v2012, v2019 };

}  // namespace rayform
