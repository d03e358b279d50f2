#include "adaptive_perception/localization/landmark_colours.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <string>
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
          .add("landmark_min_fit_share", &C::min_fit_share, config::closed(0, 1),
               "a landmark is scored when one of its two templates fits at least this share as "
               "well as a perfect one")
          .add("landmark_min_band_pixels", &C::min_band_pixels, config::closed(1, 1000000),
               "landmarks whose hued bands cover fewer pixels in the image are not scored");
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

/// A landmark's bands in the image: each band's rows [v0, v1) and colour, over columns [u0, u1).
struct BandTemplate {
  int u0 = 0, u1 = 0;
  std::vector<std::array<int, 2>> rows;
  std::vector<std::uint8_t> pose_colours, mirror_colours;
};

/// The landmark `c` as the camera at map_to_optical sees it, with the colours of the landmark at
/// its point mirror (which the mirror pose sees at the same pixels); none when not wholly in front
/// of the camera, without a mirror twin or smaller than a pixel.
std::optional<BandTemplate> bandTemplate(const world::Cylinder& c, const world::FieldMap& map,
                                         const world::PinholeCamera& camera,
                                         const Eigen::Isometry3d& optical_from_map) {
  const world::Cylinder* twin = nullptr;
  for (const world::Cylinder& o : map.cylinders()) {
    if (o.kind == world::SurfaceKind::kBeacon && std::abs(o.cx_m + c.cx_m) < 1e-6 &&
        std::abs(o.cy_m + c.cy_m) < 1e-6 && o.bands.size() == c.bands.size())
      twin = &o;
  }
  if (!twin) return std::nullopt;
  BandTemplate t;
  Eigen::Vector2d centre;
  const Eigen::Vector3d foot = optical_from_map * Eigen::Vector3d(c.cx_m, c.cy_m, 0.0);
  if (!camera.project(foot, &centre)) return std::nullopt;
  // Half its width: the radius at its axis's depth; columns [u0, u1).
  const double half = c.radius_m * camera.fx_px / foot.z();
  t.u0 = static_cast<int>(std::lround(centre.x() - half));
  t.u1 = static_cast<int>(std::lround(centre.x() + half));
  for (std::size_t k = 0; k < c.bands.size(); ++k) {
    Eigen::Vector2d bottom, top;
    if (!camera.project(optical_from_map * Eigen::Vector3d(c.cx_m, c.cy_m, c.bands[k].z0_m),
                        &bottom) ||
        !camera.project(optical_from_map * Eigen::Vector3d(c.cx_m, c.cy_m, c.bands[k].z1_m), &top))
      return std::nullopt;
    t.rows.push_back(
        {static_cast<int>(std::lround(top.y())), static_cast<int>(std::lround(bottom.y()))});
    t.pose_colours.push_back(c.bands[k].color);
    t.mirror_colours.push_back(twin->bands[k].color);
  }
  if (t.u1 - t.u0 < 1) return std::nullopt;
  return t;
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
    throw std::invalid_argument("landmarkMirrorEvidence: needs a CV_8UC3 image of the camera's "
                                "size (" + std::to_string(camera.width_px) + "x" +
                                std::to_string(camera.height_px) + ")");
  const Eigen::Isometry3d optical_from_map =
      (world::planarToIsometry(pose) * base_to_optical).inverse();
  for (const world::Cylinder& c : renderer.map().cylinders()) {
    if (c.kind != world::SurfaceKind::kBeacon || c.bands.empty()) continue;
    const auto t = bandTemplate(c, renderer.map(), camera, optical_from_map);
    if (!t) continue;
    // The search window: the landmark shifted by up to its width sideways and one and a half of
    // its tallest hued band up or down (the pose's error; a band's height is all that tells pink
    // over cyan from cyan over pink). Not the white base's: on the development field it is twice
    // a hued band's height, and a window of one and a half bases let the mirror's template slide
    // its hued bands onto the base of a backlit landmark, whose white looks yellow there.
    int band_px = 1;
    for (std::size_t k = 0; k < t->rows.size(); ++k)
      if (hue(t->pose_colours[k]) || hue(t->mirror_colours[k]))
        band_px = std::max(band_px, t->rows[k][1] - t->rows[k][0]);
    const int du = std::max(3, t->u1 - t->u0), dv = std::max(2, 3 * band_px / 2);
    const cv::Rect window = cv::Rect(t->u0 - du, t->rows.back()[0] - dv, t->u1 - t->u0 + 2 * du,
                                     t->rows.front()[1] - t->rows.back()[0] + 2 * dv) &
                            cv::Rect(0, 0, yuv.cols, yuv.rows);
    if (window.area() <= 0) continue;
    // Per colour of either template, each window pixel's similarity to its hue (0 for a pixel
    // paler than min_chroma), summed in an integral image.
    std::array<cv::Mat, world::kNumColorClasses> sums;
    for (int colour = 0; colour < world::kNumColorClasses; ++colour) {
      const auto h = hue(static_cast<std::uint8_t>(colour));
      if (!h) continue;
      cv::Mat sim(window.size(), CV_64FC1);
      for (int v = 0; v < window.height; ++v) {
        const cv::Vec3b* row = yuv.ptr<cv::Vec3b>(window.y + v) + window.x;
        for (int u = 0; u < window.width; ++u) {
          const Eigen::Vector2d chroma(row[u][1] - 128.0, row[u][2] - 128.0);
          const double n = chroma.norm();
          sim.at<double>(v, u) = n >= config.min_chroma ? h->dot(chroma) / n : 0.0;
        }
      }
      cv::integral(sim, sums[static_cast<std::size_t>(colour)], CV_64F);
    }
    // A template's score at a shift: the sum over its hued bands of the mean similarity inside
    // the band (NaN where a hued band is cut by the image's edge, or too few pixels are scored: a
    // landmark half out of view was scored on its last column, and fitted either template).
    const auto score = [&](const std::vector<std::uint8_t>& colours, int su, int sv) {
      double total = 0.0;
      int bands = 0, pixels = 0;
      for (std::size_t k = 0; k < colours.size(); ++k) {
        const cv::Mat& sum = sums[colours[k]];
        if (sum.empty()) continue;  // white: no hue
        const cv::Rect whole(t->u0 + su - window.x, t->rows[k][0] + sv - window.y, t->u1 - t->u0,
                             t->rows[k][1] - t->rows[k][0]);
        if (whole.area() <= 0) continue;  // a band thinner than a row
        const cv::Rect band = whole & cv::Rect(0, 0, window.width, window.height);
        if (band != whole) return std::nan("");
        total += (sum.at<double>(band.y + band.height, band.x + band.width) -
                  sum.at<double>(band.y, band.x + band.width) -
                  sum.at<double>(band.y + band.height, band.x) + sum.at<double>(band.y, band.x)) /
                 band.area();
        pixels += band.area();
        ++bands;
      }
      return bands == 0 || pixels < config.min_band_pixels ? std::nan("") : total;
    };
    // The landmark's place: the shift where either template fits best. Both poses put it at the
    // same pixels, so both are scored there (each at its own best shift, the mirror's pink band
    // found the pose's pink band and scored as well as the pose's own).
    double mine = std::nan(""), mirror = std::nan(""), placed = -1e9;
    for (int sv = -dv; sv <= dv; ++sv) {
      for (int su = -du; su <= du; ++su) {
        const double a = score(t->pose_colours, su, sv), b = score(t->mirror_colours, su, sv);
        if (std::isnan(a) || std::isnan(b) || std::max(a, b) <= placed) continue;
        placed = std::max(a, b);
        mine = a;
        mirror = b;
      }
    }
    if (std::isnan(mine)) continue;
    // Seen at all: the better template fits at least min_fit_share as well as a perfect one.
    int hued = 0;
    for (std::uint8_t colour : t->pose_colours) hued += hue(colour).has_value();
    if (std::max(mine, mirror) < config.min_fit_share * hued) continue;
    out.mirror_minus_pose_nats += config.concentration * (mirror - mine);
    ++out.landmarks;
  }
  return out;
}

}  // namespace adaptive_perception::localization
