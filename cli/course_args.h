// The course's own command line, verbatim: single-dash flags in any order,
//   -input F.txt -size W H -output IMG [-depth MIN MAX IMG] [-normals IMG]
//   [-dialect 2012|2019|a5] [-bounces N] [-shadows] [-jitter] [-filter]
// (-bounces defaults to 4 for a scene of the a5 dialect, else 0)
// (plus rayform's -threads N, -spp N, -sampler stratified|random, -target-error E,
// -max-spp N, -stats, -generic and -quiet). Unknown flags are errors.
// The 2012 assignment-5 anti-aliasing flags are the assignment's 3x3 samples per
// pixel (render/grid_filter.h): -jitter jitters them, -filter blurs the 3W x 3H
// sample image with the 5-tap Gaussian; either averages each pixel's 3x3 block.
#pragma once

#include "run_job.h"

#include <string>
#include <vector>

namespace rayform::cli {

// Whether the arguments use the course style (the first is one of its flags).
bool is_course_command_line(const std::vector<std::string>& args);

struct CourseCommand {
  RenderJob job;
  Reporting reporting;  // -quiet, -stats
};

// Throws UsageError.
CourseCommand parse_course_command_line(const std::vector<std::string>& args);

}  // namespace rayform::cli
