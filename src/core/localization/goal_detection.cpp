#include "adaptive_perception/localization/goal_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

namespace adaptive_perception::localization {

const config::Fields<GoalDetectionConfig>& GoalDetectionConfig::fields() {
  using C = GoalDetectionConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("goal_white_max_chroma", &C::white_max_chroma, config::aboveZero(255),
               "a goal's white: chroma at most this far from neutral (levels)")
          .add("goal_white_min_luma_share", &C::white_min_luma_share, config::closed(0, 1),
               "a goal's white: luma at least this share of the way from the carpet's to the line "
               "paint's")
          .add("goal_min_post_height_px", &C::min_post_height_px, config::closed(2, 100000),
               "goal posts shorter than this in the image are not looked for (px)")
          .add("goal_post_min_aspect_share", &C::post_min_aspect_share, config::aboveZero(1),
               "a goal post's height over its width in the image is at least this share of the "
               "post's")
          .add("goal_post_size_tolerance", &C::post_size_tolerance, config::closed(1, 10),
               "a goal post's image width and height may be off by this factor from a post "
               "standing at its foot")
          .add("goal_max_pitch_offset_rad", &C::max_pitch_offset_rad, config::closed(0, 0.5),
               "largest camera pitch error that a goal sighting may correct (rad)")
          .add("goal_min_post_width_px", &C::min_post_width_px, config::closed(1, 1000),
               "goal posts narrower than this in the image are not looked for (px)")
          .add("goal_post_min_field_below_share", &C::post_min_field_below_share,
               config::closed(0, 1),
               "share of the pixels just below a goal post's foot that must "
               "be the field's (carpet or paint)")
          .add("goal_crossbar_min_white_share", &C::crossbar_min_white_share, config::closed(0, 1),
               "share of a goal's crossbar that must be white")
          .add(
              "goal_mouth_max_white_share", &C::mouth_max_white_share, config::closed(0, 1),
              "largest share of a goal's mouth (between the posts, below the crossbar) that may be "
              "white")
          .add("goal_range_ratio_sd", &C::goal_range_ratio_sd, config::closed(0, 2),
               "uncertainty of the log of the ratio of a goal's two posts' ranges")
          .add("goal_bearing_sd_rad", &C::goal_bearing_sd_rad, config::closed(0, 1),
               "uncertainty of a goal post's bearing (rad)");
  return f;
}

namespace {

struct Geometry {
  const world::PinholeCamera& camera;
  Eigen::Isometry3d base_to_optical, optical_from_base;

  Geometry(const world::PinholeCamera& c, const Eigen::Isometry3d& t)
      : camera(c), base_to_optical(t), optical_from_base(t.inverse()) {}
  /// The same camera on a body leaning forward by `pitch_rad` (leanCamera()).
  Geometry leaning(double pitch_rad) const {
    return Geometry(camera, leanCamera(base_to_optical, pitch_rad));
  }
  /// The ground point (z = 0, base_link) under pixel (u, v); none above the horizon.
  std::optional<Eigen::Vector3d> ground(double u, double v) const {
    const Eigen::Vector3d o = base_to_optical.translation();
    const Eigen::Vector3d ray = base_to_optical.linear() * camera.rayThrough(u, v);
    if (ray.z() > -1e-6 || o.z() <= 0.0) return std::nullopt;
    return Eigen::Vector3d(o + (-o.z() / ray.z()) * ray);
  }
  /// The axis of a post of `radius_m` whose near side stands on the ground at pixel (u, v): that
  /// ground point moved away from the camera by the radius.
  std::optional<Eigen::Vector2d> axis(double u, double v, double radius_m) const {
    const auto p = ground(u, v);
    if (!p) return std::nullopt;
    const Eigen::Vector2d away = p->head<2>() - base_to_optical.translation().head<2>();
    if (away.norm() < 1e-9) return std::nullopt;
    return Eigen::Vector2d(p->head<2>() + radius_m * away.normalized());
  }
  /// The pixel of a base_link point and its depth; none behind the camera.
  std::optional<Eigen::Vector3d> project(const Eigen::Vector3d& p_base) const {
    const Eigen::Vector3d p = optical_from_base * p_base;
    Eigen::Vector2d uv;
    if (!camera.project(p, &uv)) return std::nullopt;
    return Eigen::Vector3d(uv.x(), uv.y(), p.z());
  }
};

/// The line paint's luma: the median over the segmentation's line pixels (its EM colour when it
/// found too few).
double paintLuma(const cv::Mat& yuv, const color::FieldSegmentation& seg) {
  std::vector<std::uint8_t> luma;
  for (int v = 0; v < yuv.rows; ++v) {
    const std::uint8_t* label = seg.labels.ptr<std::uint8_t>(v);
    const cv::Vec3b* in = yuv.ptr<cv::Vec3b>(v);
    for (int u = 0; u < yuv.cols; ++u) {
      if (label[u] == world::kWhite) luma.push_back(in[u][0]);
    }
  }
  if (luma.size() < 50) return seg.line_mean_yuv[0];
  std::nth_element(luma.begin(), luma.begin() + luma.size() / 2, luma.end());
  return luma[luma.size() / 2];
}

cv::Mat whiteMask(const cv::Mat& yuv, const color::FieldSegmentation& seg,
                  const GoalDetectionConfig& config) {
  cv::Mat mask(yuv.size(), CV_8UC1);
  const double carpet = seg.carpet_mean_yuv[0];
  const double min_y = carpet + config.white_min_luma_share * (paintLuma(yuv, seg) - carpet);
  const double max_c2 = config.white_max_chroma * config.white_max_chroma;
  for (int v = 0; v < yuv.rows; ++v) {
    const cv::Vec3b* in = yuv.ptr<cv::Vec3b>(v);
    std::uint8_t* out = mask.ptr<std::uint8_t>(v);
    for (int u = 0; u < yuv.cols; ++u) {
      const double du = in[u][1] - 128.0, dv = in[u][2] - 128.0;
      out[u] = (in[u][0] >= min_y && du * du + dv * dv <= max_c2) ? 1 : 0;
    }
  }
  return mask;
}

/// A vertical run of white pixels in one column: rows [top, bottom].
struct Run {
  int u, top, bottom;
};

/// Each column's white runs at least min_height_px long (gaps of up to 2 rows bridged).
std::vector<std::vector<Run>> columnRuns(const cv::Mat& white, int min_height_px) {
  std::vector<std::vector<Run>> runs(static_cast<std::size_t>(white.cols));
  for (int u = 0; u < white.cols; ++u) {
    int top = -1, last = -10;
    const auto close = [&] {
      if (top >= 0 && last - top + 1 >= min_height_px) runs[u].push_back({u, top, last});
      top = -1;
    };
    for (int v = 0; v < white.rows; ++v) {
      if (!white.at<std::uint8_t>(v, u)) continue;
      if (v - last > 3) close();
      if (top < 0) top = v;
      last = v;
    }
    close();
  }
  return runs;
}

/// Posts: neighbouring columns whose runs end on the same row (the foot; a post's run may go on
/// above it into a white background), as wide and at least as tall as a post standing there, up to
/// the camera pitch's uncertainty, with the field below.
std::vector<GoalPostSighting> findPosts(const Geometry& g, const cv::Mat& white,
                                        const cv::Mat& labels, const world::FieldDimensions& d,
                                        const GoalDetectionConfig& config) {
  std::vector<std::vector<Run>> open, done;
  for (const std::vector<Run>& column : columnRuns(white, config.min_post_height_px)) {
    std::vector<std::vector<Run>> next;
    for (const Run& r : column) {
      auto it = std::find_if(open.begin(), open.end(), [&](const std::vector<Run>& b) {
        return !b.empty() && b.back().u == r.u - 1 && std::abs(b.back().bottom - r.bottom) <= 3;
      });
      if (it == open.end()) {
        next.push_back({r});
      } else {
        it->push_back(r);
        next.push_back(std::move(*it));
        it->clear();
      }
    }
    for (auto& b : open) {
      if (!b.empty()) done.push_back(std::move(b));
    }
    open = std::move(next);
  }
  for (auto& b : open) done.push_back(std::move(b));

  const double aspect = d.goal_height_m / d.goal_post_diameter_m;
  std::vector<GoalPostSighting> posts;
  for (const std::vector<Run>& blob : done) {
    std::vector<int> bottoms, lengths;
    for (const Run& r : blob) {
      bottoms.push_back(r.bottom);
      lengths.push_back(r.bottom - r.top + 1);
    }
    std::nth_element(bottoms.begin(), bottoms.begin() + bottoms.size() / 2, bottoms.end());
    std::sort(lengths.begin(), lengths.end());
    GoalPostSighting post;
    post.u_px = 0.5 * (blob.front().u + blob.back().u);
    post.foot_v_px = bottoms[bottoms.size() / 2] + 0.5;  // the bottom edge (rayThrough's rows)
    post.width_px = static_cast<double>(blob.size());
    post.height_px = lengths[lengths.size() / 4];  // nearly every column at least this tall
    // A post cut by the image's side has no centre to speak of.
    if (blob.front().u == 0 || blob.back().u == white.cols - 1) continue;
    if (post.width_px < config.min_post_width_px ||
        post.height_px < config.post_min_aspect_share * aspect * post.width_px)
      continue;
    int field = 0, below = 0;
    for (const Run& r : blob) {
      const int v0 = static_cast<int>(post.foot_v_px) + 2;
      for (int v = v0; v < std::min(labels.rows, v0 + 6); ++v) {
        ++below;
        field += labels.at<std::uint8_t>(v, r.u) != world::kBackground;
      }
    }
    if (below == 0 || field < config.post_min_field_below_share * below) continue;
    if (const auto foot = g.axis(post.u_px, post.foot_v_px, 0.5 * d.goal_post_diameter_m))
      post.foot_m = *foot;
    posts.push_back(post);
  }
  std::sort(posts.begin(), posts.end(),
            [](const GoalPostSighting& a, const GoalPostSighting& b) { return a.u_px < b.u_px; });
  return posts;
}

/// The post is as wide and, but for a white background above it, as tall as a post standing at its
/// foot under camera `g`, up to post_size_tolerance.
bool standsThere(const Geometry& g, const GoalPostSighting& post, const world::FieldDimensions& d,
                 const GoalDetectionConfig& config) {
  const Eigen::Vector3d foot(post.foot_m.x(), post.foot_m.y(), 0.0);
  const auto foot_px = g.project(foot),
             top_px = g.project(foot + Eigen::Vector3d(0, 0, d.goal_height_m));
  if (!foot_px || !top_px) return false;
  const double f = config.post_size_tolerance;
  const double width = d.goal_post_diameter_m * g.camera.fx_px / foot_px->z();
  const double height = foot_px->y() - top_px->y();
  return post.width_px >= width / f - 2.0 && post.width_px <= width * f + 2.0 &&
         post.height_px >= height / f;
}

/// The share of the crossbar between two posts' tops that is white, under camera `g`.
double crossbarShare(const Geometry& g, const cv::Mat& white, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b, const world::FieldDimensions& d) {
  const double z = d.goal_height_m - 0.5 * d.goal_post_diameter_m;
  int hits = 0, samples = 0;
  for (int k = 1; k < 40; ++k) {
    const Eigen::Vector2d xy = a + (k / 40.0) * (b - a);
    const auto px = g.project(Eigen::Vector3d(xy.x(), xy.y(), z));
    const auto foot = g.project(Eigen::Vector3d(xy.x(), xy.y(), 0.0));
    if (!px || !foot) continue;
    const int u = static_cast<int>(std::lround(px->x()));
    if (u < 0 || u >= white.cols) continue;
    ++samples;
    // Within a sixth of the post's image height of where the crossbar should be.
    const int reach = std::max(2, static_cast<int>((foot->y() - px->y()) / 6.0));
    const int v = static_cast<int>(std::lround(px->y()));
    for (int dv = -reach; dv <= reach; ++dv) {
      if (v + dv >= 0 && v + dv < white.rows && white.at<std::uint8_t>(v + dv, u)) {
        ++hits;
        break;
      }
    }
  }
  return samples > 0 ? static_cast<double>(hits) / samples : 0.0;
}

/// The share of the goal's mouth (between the posts, from a quarter to three quarters of the
/// crossbar's height, away from the posts) that is white, under camera `g`.
double mouthShare(const Geometry& g, const cv::Mat& white, const Eigen::Vector2d& a,
                  const Eigen::Vector2d& b, const world::FieldDimensions& d) {
  int hits = 0, samples = 0;
  for (int k = 4; k <= 36; ++k) {
    const Eigen::Vector2d xy = a + (k / 40.0) * (b - a);
    for (double h : {0.25, 0.5, 0.75}) {
      const auto px = g.project(Eigen::Vector3d(xy.x(), xy.y(), h * d.goal_height_m));
      if (!px) continue;
      // project() puts pixel u's centre at u + 0.5 (rayThrough's convention).
      const int u = static_cast<int>(std::floor(px->x())),
                v = static_cast<int>(std::floor(px->y()));
      if (u < 0 || u >= white.cols || v < 0 || v >= white.rows) continue;
      ++samples;
      hits += white.at<std::uint8_t>(v, u) != 0;
    }
  }
  return samples > 0 ? static_cast<double>(hits) / samples : 1.0;
}

/// The map's goal posts grouped by goal: {left, right} as seen from the field.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> mapGoals(const world::FieldMap& map) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> goals;
  for (double sign : {1.0, -1.0}) {
    std::optional<Eigen::Vector2d> left, right;
    for (const world::Cylinder& c : map.cylinders()) {
      if (c.kind != world::SurfaceKind::kGoal || c.cx_m * sign <= 0.0) continue;
      // Facing the goal at +x, its left post is at +y; facing the one at -x, at -y.
      (c.cy_m * sign > 0.0 ? left : right) = Eigen::Vector2d(c.cx_m, c.cy_m);
    }
    if (left && right) goals.emplace_back(*left, *right);
  }
  return goals;
}

math::SE2 alignFeet(const Eigen::Vector2d& left_b, const Eigen::Vector2d& right_b,
                    const Eigen::Vector2d& left_m, const Eigen::Vector2d& right_m) {
  const Eigen::Vector2d db = right_b - left_b, dm = right_m - left_m;
  const double yaw = std::atan2(dm.y(), dm.x()) - std::atan2(db.y(), db.x());
  const Eigen::Vector2d t = 0.5 * (left_m + right_m) -
                            Eigen::Rotation2Dd(yaw).toRotationMatrix() * (0.5 * (left_b + right_b));
  return math::SE2(t.x(), t.y(), yaw);
}

}  // namespace

Eigen::Isometry3d leanCamera(const Eigen::Isometry3d& base_to_optical, double pitch_rad) {
  // A positive turn about +y takes +x (forward) towards -z: the body leans forward. The camera
  // turns where it is (where the body pivots is not known; the head chain placed the camera).
  Eigen::Isometry3d out = base_to_optical;
  out.linear() = Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                 base_to_optical.linear();
  return out;
}

std::vector<GoalSighting> detectGoals(const cv::Mat& yuv, const color::FieldSegmentation& seg,
                                      const world::PinholeCamera& camera,
                                      const Eigen::Isometry3d& base_to_optical,
                                      const world::FieldMap& map,
                                      const GoalDetectionConfig& config) {
  if (yuv.type() != CV_8UC3 || yuv.cols != camera.width_px || yuv.rows != camera.height_px ||
      seg.labels.type() != CV_8UC1 || seg.labels.size() != yuv.size())
    throw std::invalid_argument(
        "detectGoals: needs a CV_8UC3 image of the camera's size and its "
        "segmentation's labels (CV_8UC1) of the same size");
  const world::FieldDimensions& d = map.dimensions();
  // (White posts: the detector's paint.)
  if (d.goal_post_diameter_m <= 0.0 || d.goal_color_minus_x != world::kWhite ||
      d.goal_color_plus_x != world::kWhite)
    return {};
  const Geometry g(camera, base_to_optical);
  const cv::Mat white = whiteMask(yuv, seg, config);
  const std::vector<GoalPostSighting> posts = findPosts(g, white, seg.labels, d, config);

  // Pairs of posts: the camera pitch offset (within max_pitch_offset_rad) that puts their feet
  // the goal's width apart, and a white crossbar where that camera sees the goal's top.
  const double post_distance = d.goal_width_m + d.goal_post_diameter_m;
  std::vector<GoalSighting> goals;
  for (std::size_t i = 0; i < posts.size(); ++i) {
    for (std::size_t j = i + 1; j < posts.size(); ++j) {
      const GoalPostSighting &a = posts[i], &b = posts[j];
      // Pitching the camera down brings both feet closer, and with them each other.
      const double r = 0.5 * d.goal_post_diameter_m;
      const auto apart = [&](double pitch) -> double {
        const Geometry c = g.leaning(pitch);
        const auto fa = c.axis(a.u_px, a.foot_v_px, r), fb = c.axis(b.u_px, b.foot_v_px, r);
        return fa && fb ? (*fa - *fb).norm() : std::numeric_limits<double>::infinity();
      };
      double lo = -config.max_pitch_offset_rad, hi = config.max_pitch_offset_rad;
      if (!(apart(lo) >= post_distance && apart(hi) <= post_distance)) continue;
      for (int k = 0; k < 30; ++k) {
        const double mid = 0.5 * (lo + hi);
        (apart(mid) > post_distance ? lo : hi) = mid;
      }
      const double pitch = 0.5 * (lo + hi);
      const Geometry c = g.leaning(pitch);
      GoalSighting s{a, b, 0.0, pitch};
      const auto fa = c.axis(a.u_px, a.foot_v_px, r), fb = c.axis(b.u_px, b.foot_v_px, r);
      if (!fa || !fb) continue;
      s.left.foot_m = *fa;
      s.right.foot_m = *fb;
      if (!standsThere(c, s.left, d, config) || !standsThere(c, s.right, d, config)) continue;
      s.crossbar_white_share = crossbarShare(c, white, s.left.foot_m, s.right.foot_m, d);
      if (s.crossbar_white_share < config.crossbar_min_white_share) continue;
      // A frame, not a white patch: what the mouth shows is not the posts' white.
      // (A white net fills the mouth with the posts' white: no such check there.)
      s.mouth_white_share = mouthShare(c, white, s.left.foot_m, s.right.foot_m, d);
      if (d.goal_net_color != world::kWhite && s.mouth_white_share > config.mouth_max_white_share)
        continue;
      // Seen from the carpet (a pose that sees it from outside is a look-alike beyond the field).
      const std::vector<math::SE2> poses = goalPoses(s, map);
      if (poses.empty() || !map.isFree(poses.front().x_m, poses.front().y_m, 0.0)) continue;
      goals.push_back(s);
    }
  }
  std::sort(goals.begin(), goals.end(), [](const GoalSighting& a, const GoalSighting& b) {
    return a.crossbar_white_share > b.crossbar_white_share;
  });
  std::vector<GoalSighting> kept;
  for (const GoalSighting& s : goals) {
    const bool shares = std::any_of(kept.begin(), kept.end(), [&](const GoalSighting& k) {
      return k.left.u_px == s.left.u_px || k.left.u_px == s.right.u_px ||
             k.right.u_px == s.left.u_px || k.right.u_px == s.right.u_px;
    });
    if (!shares) kept.push_back(s);
  }
  return kept;
}

std::vector<math::SE2> goalPoses(const GoalSighting& sighting, const world::FieldMap& map) {
  std::vector<math::SE2> poses;
  for (const auto& [left, right] : mapGoals(map)) {
    poses.push_back(alignFeet(sighting.left.foot_m, sighting.right.foot_m, left, right));
  }
  return poses;
}

std::vector<math::SE2> sampleGoalPoses(const GoalSighting& sighting, const world::FieldMap& map,
                                       const GoalDetectionConfig& config, int count,
                                       math::Rng& rng) {
  const auto goals = mapGoals(map);
  std::vector<math::SE2> poses;
  if (goals.empty()) return poses;
  const Eigen::Vector2d &l = sighting.left.foot_m, &r = sighting.right.foot_m;
  const double distance = (goals[0].first - goals[0].second).norm();
  const double ratio = l.norm() / r.norm();
  const double bearing_l = std::atan2(l.y(), l.x()), bearing_r = std::atan2(r.y(), r.x());
  int tries = 0;
  // Pairs (one pose per goal, from the same perturbation: on a point-symmetric field, point
  // mirrors of each other), as PoseSearch's pools are.
  while (static_cast<int>(poses.size()) + static_cast<int>(goals.size()) <= count) {
    if (++tries > 100 * count) break;  // (the sighting puts almost no pose on the carpet)
    // The bearings and the ratio of the ranges perturbed; the ranges then follow from the goal's
    // width (law of cosines).
    const double bl = bearing_l + rng.gaussian(0.0, config.goal_bearing_sd_rad);
    const double br = bearing_r + rng.gaussian(0.0, config.goal_bearing_sd_rad);
    const double q = ratio * std::exp(rng.gaussian(0.0, config.goal_range_ratio_sd));
    const double c = q * q + 1.0 - 2.0 * q * std::cos(bl - br);
    if (!(c > 1e-9) || !(bl > br)) continue;
    const double rr = distance / std::sqrt(c), rl = q * rr;
    const Eigen::Vector2d fl(rl * std::cos(bl), rl * std::sin(bl));
    const Eigen::Vector2d fr(rr * std::cos(br), rr * std::sin(br));
    std::vector<math::SE2> group;
    for (const auto& [left, right] : goals) {
      const math::SE2 pose = alignFeet(fl, fr, left, right);
      if (map.isFree(pose.x_m, pose.y_m, 0.0)) group.push_back(pose);
    }
    if (group.size() == goals.size()) poses.insert(poses.end(), group.begin(), group.end());
  }
  return poses;
}

}  // namespace adaptive_perception::localization
