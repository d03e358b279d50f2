#include "adaptive_perception/world/label_renderer.h"

#include <gtest/gtest.h>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/rng.h"

using namespace adaptive_perception::world;
using adaptive_perception::math::kPi;
using adaptive_perception::math::SE2;

namespace {

// Pose of camera_optical_frame in map for a camera at `pos` whose optical axis points along
// `forward` (x right, y down with `down` roughly the image's down direction).
Eigen::Isometry3d lookAlong(const Eigen::Vector3d& pos, const Eigen::Vector3d& forward,
                            const Eigen::Vector3d& up_hint = Eigen::Vector3d::UnitZ()) {
  const Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d x = z.cross(up_hint);
  if (x.norm() < 1e-9) x = z.cross(Eigen::Vector3d::UnitX());
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = x;
  t.linear().col(1) = y;
  t.linear().col(2) = z;
  t.translation() = pos;
  return t;
}

std::uint8_t centrePixel(const LabelRenderer& r, const Eigen::Isometry3d& pose) {
  const PinholeCamera& c = r.camera();
  std::vector<PixelCoord> px = {
      {static_cast<std::uint16_t>(c.width_px / 2), static_cast<std::uint16_t>(c.height_px / 2)}};
  std::vector<std::uint8_t> out;
  r.renderPixels(pose, px, &out);
  return out[0];
}

class LabelRendererTest : public ::testing::Test {
 protected:
  // An odd-sized camera so that the centre pixel's ray is exactly the optical axis.
  LabelRendererTest() : renderer_(FieldMap(), PinholeCamera::fromFieldOfView(101, 81, 1.0, 0.8)) {}
  LabelRenderer renderer_;
};

}  // namespace

TEST_F(LabelRendererTest, LookingDownSeesCarpetAndLines) {
  const Eigen::Vector3d down(0, 0, -1);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.5, 0.5, 0.3}, down, Eigen::Vector3d::UnitX())),
            kGreen);
  // Halfway line at x = 0, centre circle of radius 0.18 m, side line at y = -1.8 .. -1.775.
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 1.0, 0.3}, down, Eigen::Vector3d::UnitX())),
            kWhite);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.18, 0.0, 0.3}, down, Eigen::Vector3d::UnitX())),
            kWhite);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.0, -1.79, 0.3}, down, Eigen::Vector3d::UnitX())),
            kWhite);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.0, -1.76, 0.3}, down, Eigen::Vector3d::UnitX())),
            kGreen);
  // Penalty area front line of the cyan goal at x = 2.7 - 0.65.
  EXPECT_EQ(centrePixel(renderer_, lookAlong({2.05, 0.3, 0.3}, down, Eigen::Vector3d::UnitX())),
            kWhite);
}

TEST_F(LabelRendererTest, BeaconBandsByHeight) {
  // Beacon at (1.35, -1.95): on the right side (-y) near the cyan goal: white base 0-0.2, cyan
  // 0.2-0.3, pink 0.3-0.4.
  const Eigen::Vector3d towards(0, -1, 0);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.35, 0.0, 0.1}, towards)), kWhite);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.35, 0.0, 0.25}, towards)), kCyan);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.35, 0.0, 0.35}, towards)), kPink);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({1.35, 0.0, 0.45}, towards)), kBackground);
  // The left (+y) beacon near the yellow goal: pink below, yellow above.
  EXPECT_EQ(centrePixel(renderer_, lookAlong({-1.35, 0.0, 0.25}, {0, 1, 0})), kPink);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({-1.35, 0.0, 0.35}, {0, 1, 0})), kYellow);
}

TEST_F(LabelRendererTest, GoalsWallsAndBackground) {
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 0.1, 0.15}, {-1, 0, 0})), kYellow);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 0.1, 0.15}, {1, 0, 0})), kCyan);
  // Between the goal and the corner the field wall (0.1 m high) shows, above it the room.
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 1.0, 0.05}, {1, 0, 0})), kWhite);
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 1.0, 0.2}, {1, 0, 0})), kBackground);
  // Straight up: nothing.
  EXPECT_EQ(centrePixel(renderer_, lookAlong({0.0, 0.0, 0.2}, {0, 0, 1}, Eigen::Vector3d::UnitX())),
            kBackground);
}

TEST_F(LabelRendererTest, CastRayReportsRangeAndNormal) {
  const RayHit h = renderer_.castRay({0.0, 0.1, 0.15}, {-2.0, 0.0, 0.0});
  EXPECT_EQ(h.color, kYellow);
  EXPECT_EQ(h.kind, SurfaceKind::kGoal);
  EXPECT_NEAR(h.range_m, 2.7 + 0.3, 1e-9);  // back panel of the goal
  EXPECT_NEAR(h.normal.x(), 1.0, 1e-12);
  const RayHit g = renderer_.castRay({1.0, 1.0, 0.3}, {0.0, 0.0, -1.0});
  EXPECT_EQ(g.kind, SurfaceKind::kCarpet);
  EXPECT_NEAR(g.range_m, 0.3, 1e-12);
  EXPECT_NEAR(g.normal.z(), 1.0, 1e-12);
}

// renderImage, renderPixels and castRay agree on every pixel, for random poses of the real head
// chain.
TEST_F(LabelRendererTest, AllEntryPointsAgree) {
  adaptive_perception::math::Rng rng(4);
  const HeadChain head;
  const PinholeCamera& cam = renderer_.camera();
  std::vector<std::uint8_t> image(cam.width_px * cam.height_px);
  std::vector<PixelCoord> all;
  for (int v = 0; v < cam.height_px; ++v)
    for (int u = 0; u < cam.width_px; ++u)
      all.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});
  std::vector<std::uint8_t> listed;
  int histogram[256] = {0};
  for (int trial = 0; trial < 30; ++trial) {
    const SE2 base{rng.uniform(-2.5, 2.5), rng.uniform(-1.7, 1.7), rng.uniform(-kPi, kPi)};
    const double pan = rng.uniform(-1.5, 1.5), tilt = rng.uniform(-0.3, 0.6);
    const Eigen::Isometry3d pose = planarToIsometry(base) * head.baseToOptical(pan, tilt);
    renderer_.renderImage(pose, image.data());
    renderer_.renderPixels(pose, all, &listed);
    ASSERT_EQ(image, listed);
    // castRay has no camera rotation and so no per-pose culling: every pixel must agree.
    int disagree = 0;
    for (size_t i = 0; i < all.size(); ++i) {
      const Eigen::Vector3d dir =
          pose.linear() * cam.rayThrough(all[i].u, all[i].v).cast<float>().cast<double>();
      disagree += renderer_.castRay(pose.translation(), dir).color != image[i];
    }
    EXPECT_EQ(disagree, 0) << "trial " << trial;
    for (auto c : image) ++histogram[c];
  }
  // The random views show the main classes.
  EXPECT_GT(histogram[kGreen], 0);
  EXPECT_GT(histogram[kWhite], 0);
  EXPECT_GT(histogram[kBackground], 0);
}

// Per camera pose the renderer skips every primitive whose box, projected into the image, does not
// hold the pixel. Cameras right at the primitives (their boxes reach behind the image plane, or
// fill the view) and beside them looking past: renderImage agrees with castRay, which skips
// nothing.
TEST_F(LabelRendererTest, CullingNearPrimitivesChangesNoPixel) {
  adaptive_perception::math::Rng rng(11);
  FieldDimensions with_ball;
  with_ball.ball_enabled = true;
  with_ball.ball_xy_m = {1.0, -0.5};
  const LabelRenderer renderer(FieldMap(with_ball), renderer_.camera());
  const FieldMap& map = renderer.map();
  const PinholeCamera& cam = renderer.camera();
  std::vector<Eigen::Vector3d> near;
  for (const Cylinder& c : map.cylinders())
    near.push_back({c.cx_m, c.cy_m, 0.5 * (c.bands.front().z0_m + c.bands.back().z1_m)});
  for (const auto& q : map.quads())
    near.push_back({0.5 * (q.p0_m.x() + q.p1_m.x()), 0.5 * (q.p0_m.y() + q.p1_m.y()),
                    0.5 * (q.z0_m + q.z1_m)});
  ASSERT_EQ(map.spheres().size(), 1u);
  for (const auto& b : map.spheres()) near.push_back(b.centre_m);
  std::vector<std::uint8_t> image(cam.width_px * cam.height_px);
  int disagree = 0, non_ground = 0;
  for (const Eigen::Vector3d& target : near) {
    for (int trial = 0; trial < 6; ++trial) {
      const double dist = trial < 3 ? 0.02 + 0.05 * trial : rng.uniform(0.2, 1.5);
      const double az = rng.uniform(-kPi, kPi);
      const Eigen::Vector3d pos =
          target + dist * Eigen::Vector3d(std::cos(az), std::sin(az), rng.uniform(-0.5, 0.5));
      const Eigen::Vector3d forward =
          trial % 2 == 0 ? Eigen::Vector3d(target - pos)
                         : Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), -0.3);
      const Eigen::Isometry3d pose = lookAlong(pos, forward);
      renderer.renderImage(pose, image.data());
      for (int v = 0; v < cam.height_px; ++v)
        for (int u = 0; u < cam.width_px; ++u) {
          const std::uint8_t c = image[static_cast<size_t>(v) * cam.width_px + u];
          const Eigen::Vector3d dir =
              pose.linear() * cam.rayThrough(u, v).cast<float>().cast<double>();
          disagree += renderer.castRay(pose.translation(), dir).color != c;
          non_ground += c != kGreen && c != kWhite && c != kBackground;
        }
    }
  }
  EXPECT_EQ(disagree, 0);
  EXPECT_GT(non_ground, 0);  // the views do show the primitives
}

// Independent check by projection: a point in the middle of a beacon band, seen from a camera with
// nothing in between, lands on a pixel of that band's class.
TEST_F(LabelRendererTest, ProjectedBeaconPointsLandOnTheirColour) {
  const FieldMap& map = renderer_.map();
  const PinholeCamera& cam = renderer_.camera();
  for (const Cylinder& c : map.cylinders()) {
    // Camera 1 m towards the field centre from the beacon, looking at it.
    const Eigen::Vector3d target(c.cx_m, c.cy_m, 0.3);
    const Eigen::Vector3d pos(c.cx_m, c.cy_m - (c.cy_m > 0 ? 1.0 : -1.0), 0.3);
    const Eigen::Isometry3d pose = lookAlong(pos, target - pos);
    std::vector<std::uint8_t> image(cam.width_px * cam.height_px);
    renderer_.renderImage(pose, image.data());
    for (const auto& band : c.bands) {
      const Eigen::Vector3d p(c.cx_m + (pos.x() - c.cx_m) * 0.0,
                              c.cy_m + (c.cy_m > 0 ? -1 : 1) * c.radius_m,
                              0.5 * (band.z0_m + band.z1_m));
      Eigen::Vector2d uv;
      ASSERT_TRUE(cam.project(pose.inverse() * p, &uv));
      const int u = static_cast<int>(uv.x()), v = static_cast<int>(uv.y());
      ASSERT_TRUE(u >= 0 && v >= 0 && u < cam.width_px && v < cam.height_px);
      EXPECT_EQ(image[v * cam.width_px + u], band.color) << c.name << " band at z " << p.z();
    }
  }
}
