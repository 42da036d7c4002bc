// Camera rays (src/render/camera_rays.h) by the course convention of
// COURSE_FORMAT.md: w = normalize(direction), u = normalize(w x up),
// v = u x w (2012) or the raw up (2019); D = 1 / tan(angle / 2) in double;
// pixel (i, j), j from the bottom: x = 2i/(W-1) - 1, y = 2j/(H-1) - 1, no
// aspect correction; direction = normalize(x u + y v + D w), tmin = 0.
#include "rayform/render/camera_rays.h"
#include "rayform/render/render.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rayform {
namespace {

Camera course_camera(vec3 center, vec3 direction, vec3 up, float angle, bool raw_up = false) {
  Camera c;
  c.center = center;
  c.direction = direction;
  c.up = up;
  c.fov_deg = angle;
  c.aspect = Camera::Aspect::stretch;
  c.up_vector = raw_up ? Camera::UpVector::raw : Camera::UpVector::orthonormal;
  return c;
}

double focal_double(double angle_deg) { return 1.0 / std::tan(angle_deg * 3.14159265358979323846 / 360.0); }

// The direction the spec asks for, evaluated in double from the frame vectors.
dvec3 expected_direction(const CameraFrame& f, int i, int j, int W, int H) {
  double x = W > 1 ? 2.0 * i / (W - 1) - 1.0 : 0.0;
  double y = H > 1 ? 2.0 * j / (H - 1) - 1.0 : 0.0;
  return glm::normalize(x * dvec3(f.u) + y * dvec3(f.v) + focal_double(30.0) * dvec3(f.w));
}

// float evaluation: x (1 rounding), the weighted sum (~3) and normalize (~3)
// stay within ~8 ulps of 1 = 1e-6, while a pixel mapped one column off moves
// the direction by about 2/(W-1) / D > 1e-3 for every size used here.
constexpr float kDirTol = 1e-6f;

TEST(CameraRays, Frame2012IsOrthonormal) {
  Camera c = course_camera({0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 30.f);
  CameraFrame f = make_camera_frame(c, 200, 200);
  EXPECT_EQ(f.origin, vec3(0, 0, 10));
  EXPECT_EQ(f.w, vec3(0, 0, -1));
  EXPECT_EQ(f.u, vec3(1, 0, 0));
  EXPECT_EQ(f.v, vec3(0, 1, 0));
  EXPECT_FALSE(f.orthographic);

  // scene04's oblique camera: up is not orthogonal to the direction.
  Camera o = course_camera({13, 11, 30}, {-.16f, -.12f, -.5f}, {0, 1, 0}, 30.f);
  CameraFrame g = make_camera_frame(o, 200, 200);
  // Unit vectors and right angles, to float rounding (a few ulps: 1e-6).
  EXPECT_NEAR(glm::length(g.u), 1.f, 1e-6f);
  EXPECT_NEAR(glm::length(g.v), 1.f, 1e-6f);
  EXPECT_NEAR(glm::length(g.w), 1.f, 1e-6f);
  EXPECT_NEAR(glm::dot(g.u, g.v), 0.f, 1e-6f);
  EXPECT_NEAR(glm::dot(g.u, g.w), 0.f, 1e-6f);
  EXPECT_NEAR(glm::dot(g.v, g.w), 0.f, 1e-6f);
  EXPECT_GT(glm::dot(g.v, vec3(0, 1, 0)), 0.9f) << "v points up";
  // w x (0, 1, 0) = (-w.z, 0, w.x): the y component is exactly zero.
  EXPECT_EQ(g.u.y, 0.f) << "u is horizontal (perpendicular to up)";
  // u = w x up: right-handed, x to the right when looking down -z.
  dvec3 w = glm::normalize(dvec3(-.16, -.12, -.5));
  dvec3 u = glm::normalize(glm::cross(w, dvec3(0, 1, 0)));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(g.w[k], w[k], 1e-6);
    EXPECT_NEAR(g.u[k], u[k], 1e-6);
    EXPECT_NEAR(g.v[k], glm::cross(u, w)[k], 1e-6);
  }
}

TEST(CameraRays, FocalDistanceIsComputedInDouble) {
  for (float angle : {30.f, 45.f, 20.f, 60.f, 33.3f, 90.f, 1.f, 179.f}) {
    Camera c = course_camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, angle);
    EXPECT_EQ(make_camera_frame(c, 10, 10).focal, float(focal_double(double(angle)))) << angle;
  }
}

TEST(CameraRays, PixelToRayMappingSquare) {
  Camera c = course_camera({0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 30.f);
  const int W = 5, H = 5;
  CameraFrame f = make_camera_frame(c, W, H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      Ray r = camera_ray(f, float(i), float(j));
      EXPECT_EQ(r.origin, vec3(0, 0, 10));
      EXPECT_EQ(r.tmin, 0.f);
      dvec3 e = expected_direction(f, i, j, W, H);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.direction[k], e[k], kDirTol) << i << "," << j;
    }
  // The outermost pixel centres lie on +-1: corner (0, 0) is down-left.
  Ray corner = camera_ray(f, 0.f, 0.f);
  double D = focal_double(30.0), n = std::sqrt(2.0 + D * D);
  EXPECT_NEAR(corner.direction.x, -1.0 / n, kDirTol);
  EXPECT_NEAR(corner.direction.y, -1.0 / n, kDirTol);
  EXPECT_NEAR(corner.direction.z, -D / n, kDirTol);
  Ray centre = camera_ray(f, 2.f, 2.f);
  EXPECT_EQ(centre.direction, vec3(0, 0, -1));
}

TEST(CameraRays, NonSquareImagesAreStretchedNotCorrected) {
  Camera c = course_camera({0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 30.f);
  for (auto [W, H] : {std::pair{400, 100}, std::pair{100, 400}, std::pair{399, 200}, std::pair{7, 3}}) {
    CameraFrame f = make_camera_frame(c, W, H);
    // Both axes span [-1, 1] whatever the shape: the corners are the same rays.
    for (auto [i, j] : {std::pair{0, 0}, std::pair{W - 1, 0}, std::pair{0, H - 1}, std::pair{W - 1, H - 1}}) {
      Ray r = camera_ray(f, float(i), float(j));
      dvec3 e = expected_direction(f, i, j, W, H);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.direction[k], e[k], kDirTol) << W << "x" << H << " " << i << "," << j;
      EXPECT_NEAR(std::abs(r.direction.x), std::abs(r.direction.y), kDirTol) << "corner rays are diagonal";
    }
    for (int i = 0; i < W; i += std::max(1, W / 13)) {
      Ray r = camera_ray(f, float(i), 0.f);
      dvec3 e = expected_direction(f, i, 0, W, H);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.direction[k], e[k], kDirTol) << W << "x" << H << " column " << i;
    }
  }
}

TEST(CameraRays, EvenColumnsOf399AreExactlyThe200Columns) {
  // x = 2i/(W-1) - 1 with one correctly rounded division: at W = 399 pixel 2i
  // has 4i/398 = 2i/199, the same rational as pixel i at W = 200, so the rays
  // must be bit-identical (what course_parity_sizes.sh relies on).
  Camera c = course_camera({13, 11, 30}, {-.16f, -.12f, -.5f}, {0, 1, 0}, 30.f);
  CameraFrame f200 = make_camera_frame(c, 200, 200), fw = make_camera_frame(c, 399, 200),
              fh = make_camera_frame(c, 200, 399), fb = make_camera_frame(c, 399, 399);
  for (int j = 0; j < 200; j += 3)
    for (int i = 0; i < 200; ++i) {
      Ray a = camera_ray(f200, float(i), float(j));
      ASSERT_EQ(camera_ray(fw, float(2 * i), float(j)).direction, a.direction) << i << "," << j;
      ASSERT_EQ(camera_ray(fh, float(j), float(2 * i)).direction, camera_ray(f200, float(j), float(i)).direction);
      ASSERT_EQ(camera_ray(fb, float(2 * i), float(2 * j)).direction, a.direction);
    }
}

TEST(CameraRays, Raw2019UpIsNotOrthogonalised) {
  // 2019: v is `up` as written, neither normalised nor made orthogonal.
  const vec3 up(0.f, 2.f, 1.f);
  Camera c = course_camera({0, 0, 10}, {0, 0, -1}, up, 30.f, /*raw_up=*/true);
  CameraFrame f = make_camera_frame(c, 11, 11);
  EXPECT_EQ(f.v, up);
  EXPECT_EQ(f.u, vec3(1, 0, 0));
  // Top-centre pixel: x = 0, y = 1: direction = normalize(up + D w).
  Ray r = camera_ray(f, 5.f, 10.f);
  dvec3 e = glm::normalize(dvec3(up) + focal_double(30.0) * dvec3(0, 0, -1));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.direction[k], e[k], kDirTol);
  // The 2012 rule would have used (0, 1, 0) instead: clearly different.
  Camera c12 = c;
  c12.up_vector = Camera::UpVector::orthonormal;
  Ray r12 = camera_ray(make_camera_frame(c12, 11, 11), 5.f, 10.f);
  EXPECT_GT(std::abs(r12.direction.y - r.direction.y), 0.1f);
  EXPECT_EQ(make_camera_frame(c12, 11, 11).v, vec3(0, 1, 0));
}

TEST(CameraRays, SingleColumnOrRowLooksAhead) {
  Camera c = course_camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 30.f);
  CameraFrame f = make_camera_frame(c, 1, 1);
  EXPECT_EQ(camera_ray(f, 0.f, 0.f).direction, vec3(0, 0, -1));
  CameraFrame g = make_camera_frame(c, 1, 3);
  Ray top = camera_ray(g, 0.f, 2.f);
  EXPECT_EQ(top.direction.x, 0.f);
  EXPECT_GT(top.direction.y, 0.f);
}

TEST(CameraRays, FitAspectScalesX) {
  // Asset cameras: the angle spans the vertical axis, x is scaled by W/H.
  Camera c = course_camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 30.f);
  c.aspect = Camera::Aspect::fit;
  CameraFrame f = make_camera_frame(c, 400, 200);
  EXPECT_EQ(f.sx, 2.f);
  EXPECT_EQ(f.sy, 1.f);
  Ray r = camera_ray(f, 399.f, 199.f);
  // x = 1 * 2, y = 1: the ratio survives normalize to a few ulps (1e-6).
  EXPECT_NEAR(r.direction.x / r.direction.y, 2.f, 1e-6f);
}

// Through the renderer: image row 0 is the top (j = H - 1), column 0 the left.
TEST(CameraRays, RenderedImageIsUprightAndNotMirrored) {
  Scene s;
  s.cameras.push_back(course_camera({0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 30.f));
  s.spheres.push_back({vec3(1.5f, 1.5f, 0.f), 0.6f});  // up and to the right
  s.nodes.push_back(test::shape_node(ShapeKind::sphere, 0));
  s.root = 0;
  PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = 41;
  o.height = 21;
  o.depth = true;
  o.threads = 1;
  RenderResult res = render(p, o);
  auto hit = [&](int x, int y) { return std::isfinite(res.depth[size_t(y) * 41 + x]); };
  // The sphere centre projects to x = y = 1.5 D / 10 ~ 0.56 of the half-size:
  // column 20 + 0.56 * 20 ~ 31, row 10 - 0.56 * 10 ~ 4 (from the top).
  EXPECT_TRUE(hit(31, 4));
  EXPECT_FALSE(hit(9, 4));
  EXPECT_FALSE(hit(31, 16));
  EXPECT_FALSE(hit(9, 16));
}

}  // namespace
}  // namespace rayform
