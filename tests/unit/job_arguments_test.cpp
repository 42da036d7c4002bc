// The render job's argument checks and names (pipeline/job_arguments.h), as
// both front ends (the command line, the Python module) use them.
#include "rayform/pipeline/job_arguments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rayform {
namespace {

constexpr float nan_value = std::numeric_limits<float>::quiet_NaN();
constexpr float inf_value = std::numeric_limits<float>::infinity();

TEST(JobArguments, FovStrictlyBetween0And180) {
  EXPECT_EQ(fov_problem(40.f), "");
  EXPECT_EQ(fov_problem(179.5f), "");
  EXPECT_EQ(fov_problem(0.f), "degrees strictly between 0 and 180");
  EXPECT_EQ(fov_problem(180.f), "degrees strictly between 0 and 180");
  EXPECT_EQ(fov_problem(-10.f), "degrees strictly between 0 and 180");
  EXPECT_EQ(fov_problem(nan_value), "degrees strictly between 0 and 180");
}

TEST(JobArguments, BackgroundFromHexIsEachByteOver255) {
  const std::optional<vec3> c = background_from_hex("#8040fF");
  ASSERT_TRUE(c);
  EXPECT_EQ((*c)[0], 128.f / 255.f);
  EXPECT_EQ((*c)[1], 64.f / 255.f);
  EXPECT_EQ((*c)[2], 1.f);
  EXPECT_FALSE(background_from_hex("#fff"));
  EXPECT_FALSE(background_from_hex("#1234567"));
  EXPECT_FALSE(background_from_hex("#12345g"));
  EXPECT_FALSE(background_from_hex("123456"));
  EXPECT_FALSE(background_from_hex("0.5,0.5,1"));  // the hex form only
}

TEST(JobArguments, BackgroundFromTextTakesHexOrThreeNumbers) {
  const std::optional<vec3> c = background_from_text("0.5,0.25,1");
  ASSERT_TRUE(c);
  EXPECT_EQ((*c)[0], 0.5f);
  EXPECT_EQ((*c)[1], 0.25f);
  EXPECT_EQ((*c)[2], 1.f);
  const std::optional<vec3> h = background_from_text("#000080");
  ASSERT_TRUE(h);
  EXPECT_EQ((*h)[2], 128.f / 255.f);
  EXPECT_FALSE(background_from_text(""));
  EXPECT_FALSE(background_from_text("0.5,0.5"));
  EXPECT_FALSE(background_from_text("0.5,0.5,0.5,0.5"));
  EXPECT_FALSE(background_from_text("nan,0,0"));
  EXPECT_FALSE(background_from_text("0.5;0.5;0.5"));
  EXPECT_FALSE(background_from_text("#fff"));
  // Parsed, not checked: the range is background_problem's.
  const std::optional<vec3> big = background_from_text("255,255,255");
  ASSERT_TRUE(big);
  EXPECT_EQ((*big)[0], 255.f);
}

TEST(JobArguments, BackgroundChannelsIn0To1) {
  EXPECT_EQ(background_problem(vec3(0.f, 0.5f, 1.f)), "");
  EXPECT_EQ(background_problem(vec3(0.f, 1.5f, 0.f)), "each of r, g, b in 0..1");
  EXPECT_EQ(background_problem(vec3(0.f, 0.f, -0.1f)), "each of r, g, b in 0..1");
  EXPECT_EQ(background_problem(vec3(nan_value, 0.f, 0.f)), "each of r, g, b in 0..1");
}

TEST(JobArguments, NumbersFromTextAreFiniteAndCommaSeparated) {
  const std::optional<std::vector<float>> v = numbers_from_text("1,-2.5,3e2");
  ASSERT_TRUE(v);
  EXPECT_EQ(*v, (std::vector<float>{1.f, -2.5f, 300.f}));
  EXPECT_FALSE(numbers_from_text(""));
  EXPECT_FALSE(numbers_from_text("1,,2"));
  EXPECT_FALSE(numbers_from_text("1,2,"));
  EXPECT_FALSE(numbers_from_text("1,inf"));
  EXPECT_FALSE(numbers_from_text("1 2"));
}

TEST(JobArguments, EnvironmentChecks) {
  EXPECT_EQ(env_intensity_problem(0.f), "");
  EXPECT_EQ(env_intensity_problem(2.5f), "");
  EXPECT_EQ(env_intensity_problem(-1.f), "a finite number >= 0");
  EXPECT_EQ(env_intensity_problem(inf_value), "a finite number >= 0");
  EXPECT_EQ(env_intensity_problem(nan_value), "a finite number >= 0");
  EXPECT_EQ(env_rotation_problem(-720.f), "");
  EXPECT_EQ(env_rotation_problem(inf_value), "degrees");
  EXPECT_EQ(env_rotation_problem(nan_value), "degrees");
}

TEST(JobArguments, EnvironmentFromArguments) {
  EXPECT_FALSE(environment_from_arguments(std::nullopt, std::nullopt, std::nullopt));
  // Intensity or rotation alone: the studio's, changed.
  const std::optional<Environment> studio = environment_from_arguments(std::nullopt, 2.f, std::nullopt);
  ASSERT_TRUE(studio);
  EXPECT_EQ(studio->source, Environment::Source::studio);
  EXPECT_EQ(studio->intensity, 2.f);
  EXPECT_EQ(studio->rotation_deg, 0.f);
  const std::optional<Environment> none = environment_from_arguments(std::string("none"), std::nullopt, 90.f);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->source, Environment::Source::none);
  EXPECT_EQ(none->intensity, 1.f);
  EXPECT_EQ(none->rotation_deg, 90.f);
  EXPECT_EQ(environment_from_arguments(std::string("studio"), std::nullopt, std::nullopt)->source,
            Environment::Source::studio);
  const std::optional<Environment> file = environment_from_arguments(std::string("sky.hdr"), 0.5f, -30.f);
  ASSERT_TRUE(file);
  EXPECT_EQ(file->source, Environment::Source::file);
  EXPECT_EQ(file->path, "sky.hdr");
  EXPECT_EQ(file->intensity, 0.5f);
  EXPECT_EQ(file->rotation_deg, -30.f);
}

std::string as_flag(const std::string& field) { return "<" + field + ">"; }

TEST(JobArguments, CameraConflicts) {
  RenderJob job;
  EXPECT_EQ(camera_conflict(job, true, as_flag), "");
  job.camera_adjust.look_from = vec3(1.f, 2.f, 3.f);
  EXPECT_EQ(camera_conflict(job, true, as_flag), "");
  job.orbit = Orbit{30.f, 20.f, std::nullopt};
  EXPECT_EQ(camera_conflict(job, false, as_flag),
            "<orbit> places the camera itself: it cannot be combined with <look_from> or <look_at>");
  job.camera_adjust.look_from.reset();
  job.camera_adjust.look_at = vec3(0.f);
  EXPECT_EQ(camera_conflict(job, false, as_flag),
            "<orbit> places the camera itself: it cannot be combined with <look_from> or <look_at>");
  job.camera_adjust.look_at.reset();
  EXPECT_EQ(camera_conflict(job, false, as_flag), "");
  EXPECT_EQ(camera_conflict(job, true, as_flag),
            "<orbit> replaces the file's cameras: it cannot be combined with <camera>");
  job.orbit.reset();
  job.frame = true;
  EXPECT_EQ(camera_conflict(job, false, as_flag), "");
  EXPECT_EQ(camera_conflict(job, true, as_flag),
            "<frame> replaces the file's cameras: it cannot be combined with <camera>");
  job.camera_adjust.look_from = vec3(1.f);  // --frame with --look-from moves the default camera
  EXPECT_EQ(camera_conflict(job, false, as_flag), "");
}

TEST(JobArguments, NamesAndTheirValues) {
  EXPECT_EQ(tone_map_names(), (std::vector<std::string>{"khr-neutral", "aces", "none"}));
  for (const std::string& n : tone_map_names()) EXPECT_TRUE(tone_map_from_name(n)) << n;
  EXPECT_EQ(encoding_names(), (std::vector<std::string>{"auto", "raw", "srgb"}));
  EXPECT_EQ(encoding_from_name("auto"), ColorEncoding::automatic);
  EXPECT_EQ(encoding_from_name("raw"), ColorEncoding::raw);
  EXPECT_EQ(encoding_from_name("srgb"), ColorEncoding::srgb);
  EXPECT_FALSE(encoding_from_name("linear"));
  EXPECT_EQ(filter_names(), (std::vector<std::string>{"box", "tent"}));
  EXPECT_EQ(filter_from_name("box"), PixelFilter::box);
  EXPECT_EQ(filter_from_name("tent"), PixelFilter::tent);
  EXPECT_FALSE(filter_from_name("Tent"));
  EXPECT_EQ(sampler_names(), (std::vector<std::string>{"stratified", "random"}));
  EXPECT_EQ(sampler_from_name("stratified"), PixelSampler::stratified);
  EXPECT_EQ(sampler_from_name("random"), PixelSampler::random);
  EXPECT_FALSE(sampler_from_name(""));
}

TEST(JobArguments, QuotedNames) {
  EXPECT_EQ(quoted_names({"box", "tent"}), "'box' or 'tent'");
  EXPECT_EQ(quoted_names(tone_map_names()), "'khr-neutral', 'aces' or 'none'");
  EXPECT_EQ(quoted_names({"only"}), "'only'");
  EXPECT_EQ(quoted_names(sampler_names(), ""), "stratified or random");
}

}  // namespace
}  // namespace rayform
