// Output file names of a batch render: templates with placeholders
//   {stem}   the input file's name without folder and extension (duck.glb -> duck; safe_stem)
//   {frame}  the turntable frame number, four digits from 0000 (--frames)
// e.g. -o 'out/{stem}.png', -o 'spin/{stem}_{frame}.png'.
#pragma once

#include <string>

namespace rayform::cli {

// The {stem} of `input`: its file name without folder and extension, made
// only of dots ("", ".", "..": "...txt" has the stem "..") as that many '_'
// (at least one), '/' and '\\' as '_', so that it never names a folder.
std::string safe_stem(const std::string& input);

// Whether `pattern` names the placeholder `name` ("stem" or "frame").
bool has_placeholder(const std::string& pattern, const std::string& name);

// `pattern` with {stem} and {frame} replaced. Throws UsageError (naming
// `option`) for any other {...} in it or an unclosed brace.
std::string expand_output_name(const std::string& pattern, const std::string& input, int frame,
                               const std::string& option);

}  // namespace rayform::cli
