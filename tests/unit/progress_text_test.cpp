// The command line's progress text (cli/progress.h): durations for people and
// the line with the time elapsed and the estimate of the time left.
#include "progress.h"

#include <gtest/gtest.h>

#include <limits>

namespace rayform::cli {
namespace {

TEST(FormatDuration, MinutesAndSeconds) {
  EXPECT_EQ(format_duration(0.0), "0:00");
  EXPECT_EQ(format_duration(7.9), "0:07");
  EXPECT_EQ(format_duration(65.0), "1:05");
  EXPECT_EQ(format_duration(59.999), "0:59");
  EXPECT_EQ(format_duration(600.0), "10:00");
}

TEST(FormatDuration, HoursWhenNeeded) {
  EXPECT_EQ(format_duration(3599.0), "59:59");
  EXPECT_EQ(format_duration(3600.0), "1:00:00");
  EXPECT_EQ(format_duration(3723.0), "1:02:03");
  EXPECT_EQ(format_duration(100 * 3600.0 + 1), "100:00:01");
}

TEST(FormatDuration, NonsenseIsZero) {
  EXPECT_EQ(format_duration(-3.0), "0:00");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::quiet_NaN()), "0:00");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "0:00");
}

TEST(ProgressText, ElapsedAndEstimate) {
  // 25 % in 10 s: 30 s left.
  EXPECT_EQ(progress_text("rendering", 0.25f, 10.0), "rendering  25%  0:10 elapsed, about 0:30 left");
  EXPECT_EQ(progress_text("rendering", 0.5f, 65.0), "rendering  50%  1:05 elapsed, about 1:05 left");
  EXPECT_EQ(progress_text("rendering", 1.f, 3.0), "rendering 100%  0:03 elapsed, about 0:00 left");
}

TEST(ProgressText, NoEstimateBelowOnePercent) {
  EXPECT_EQ(progress_text("rendering", 0.f, 0.4), "rendering   0%  0:00 elapsed");
  EXPECT_EQ(progress_text("rendering", 0.005f, 2.0), "rendering   0%  0:02 elapsed");
}

TEST(ProgressText, FractionClamped) {
  EXPECT_EQ(progress_text("x", -1.f, 1.0), "x   0%  0:01 elapsed");
  EXPECT_EQ(progress_text("x", 2.f, 1.0), "x 100%  0:01 elapsed, about 0:00 left");
}

}  // namespace
}  // namespace rayform::cli
