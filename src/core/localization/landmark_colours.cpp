#include "adaptive_perception/localization/landmark_colours.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::localization {

const config::Fields<LandmarkColourConfig>& LandmarkColourConfig::fields() {
  using C = LandmarkColourConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("landmark_hue_concentration", &C::concentration, config::closed(0, 100),
               "concentration of a landmark band's hue density (nats per unit cosine; 0: the "
               "mirror test does not ask the landmarks' hues)")
          .add("landmark_min_chroma", &C::min_chroma, config::closed(0, 128),
               "pixels paler than this (levels from neutral) say nothing of a landmark's hue")
          .add("landmark_min_band_pixels", &C::min_band_pixels, config::closed(1, 1000000),
               "landmark bands with fewer hued pixels in the image are not scored");
  return f;
}

namespace {

/// The unit hue direction (U, V) of a colour class; none for white and the background.
std::optional<Eigen::Vector2d> hue(std::uint8_t c) {
  std::optional<Eigen::Vector3d> rgb;
  switch (c) {
    case world::kPink:
      rgb = Eigen::Vector3d(255, 105, 180);
      break;
    case world::kYellow:
      rgb = Eigen::Vector3d(255, 255, 0);
      break;
    case world::kCyan:
      rgb = Eigen::Vector3d(80, 160, 230);
      break;
    case world::kGreen:
      rgb = Eigen::Vector3d(0, 160, 0);
      break;
    case world::kOrange:
      rgb = Eigen::Vector3d(255, 128, 0);
      break;
    default:
      return std::nullopt;
  }
  const Eigen::Vector3d yuv = color::rgbToYuv(*rgb);
  return Eigen::Vector2d(yuv[1] - 128.0, yuv[2] - 128.0).normalized();
}

}  // namespace

LandmarkColourEvidence landmarkMirrorEvidence(const cv::Mat& yuv,
                                              const world::LabelRenderer& renderer,
                                              const math::SE2& pose,
                                              const Eigen::Isometry3d& base_to_optical,
                                              const LandmarkColourConfig& config) {
  LandmarkColourEvidence out;
  const world::PinholeCamera& camera = renderer.camera();
  if (yuv.type() != CV_8UC3 || yuv.cols != camera.width_px || yuv.rows != camera.height_px)
    return out;
  // The pixels where the pose sees a landmark (its bounding box's image); the mirror pose sees
  // the mirrored landmark at the same pixels.
  const Eigen::Isometry3d map_to_optical = world::planarToIsometry(pose) * base_to_optical;
  const Eigen::Isometry3d optical_from_map = map_to_optical.inverse();
  std::vector<world::PixelCoord> pixels;
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(camera.width_px) * camera.height_px, 0);
  for (const world::Cylinder& c : renderer.map().cylinders()) {
    if (c.kind != world::SurfaceKind::kBeacon || c.bands.empty()) continue;
    double u0 = camera.width_px, u1 = -1, v0 = camera.height_px, v1 = -1;
    bool behind = false;
    for (double dx : {-c.radius_m, c.radius_m})
      for (double dy : {-c.radius_m, c.radius_m})
        for (double z : {c.bands.front().z0_m, c.bands.back().z1_m}) {
          Eigen::Vector2d uv;
          if (!camera.project(optical_from_map * Eigen::Vector3d(c.cx_m + dx, c.cy_m + dy, z),
                              &uv)) {
            behind = true;
            continue;
          }
          u0 = std::min(u0, uv.x()), u1 = std::max(u1, uv.x());
          v0 = std::min(v0, uv.y()), v1 = std::max(v1, uv.y());
        }
    if (behind) continue;
    const int ua = std::max(0, static_cast<int>(std::floor(u0)) - 1);
    const int ub = std::min(camera.width_px - 1, static_cast<int>(std::ceil(u1)) + 1);
    const int va = std::max(0, static_cast<int>(std::floor(v0)) - 1);
    const int vb = std::min(camera.height_px - 1, static_cast<int>(std::ceil(v1)) + 1);
    for (int v = va; v <= vb; ++v)
      for (int u = ua; u <= ub; ++u) {
        auto& mark = seen[static_cast<std::size_t>(v) * camera.width_px + u];
        if (mark) continue;
        mark = 1;
        pixels.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});
      }
  }
  if (pixels.empty()) return out;
  std::vector<std::uint8_t> mine, mirror;
  renderer.renderPixels(map_to_optical, pixels, &mine);
  renderer.renderPixels(world::planarToIsometry(math::pointMirror(pose)) * base_to_optical, pixels,
                        &mirror);
  // Per (pose colour, mirror colour) pair, a band: the sums of its hued pixels' cosines.
  constexpr int kPairs = world::kNumColorClasses * world::kNumColorClasses;
  std::array<double, kPairs> sum_mine{}, sum_mirror{};
  std::array<int, kPairs> count{};
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const std::uint8_t a = mine[i], b = mirror[i];
    if (a == b || a >= world::kNumColorClasses || b >= world::kNumColorClasses) continue;
    const auto ha = hue(a), hb = hue(b);
    if (!ha || !hb) continue;  // white against a colour: a hue cannot tell
    const cv::Vec3b& px = yuv.at<cv::Vec3b>(pixels[i].v, pixels[i].u);
    const Eigen::Vector2d chroma(px[1] - 128.0, px[2] - 128.0);
    const double c = chroma.norm();
    if (c < config.min_chroma) continue;
    const int k = a * world::kNumColorClasses + b;
    sum_mine[k] += ha->dot(chroma) / c;
    sum_mirror[k] += hb->dot(chroma) / c;
    ++count[k];
  }
  for (int k = 0; k < kPairs; ++k) {
    if (count[k] < config.min_band_pixels) continue;
    out.mirror_minus_pose_nats += config.concentration * (sum_mirror[k] - sum_mine[k]) / count[k];
    ++out.bands;
  }
  return out;
}

}  // namespace adaptive_perception::localization
