#include "adaptive_perception/ros/msg_conversion.h"

#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/math/gaussian.h"
#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::ros_conv {

namespace enc = sensor_msgs::image_encodings;

io::ImageBuffer imageBuffer(const sensor_msgs::Image& msg) {
  io::ImageBuffer buffer;
  buffer.encoding = msg.encoding;
  buffer.width_px = msg.width;
  buffer.height_px = msg.height;
  buffer.step_bytes = msg.step;
  buffer.data = msg.data.data();
  buffer.size_bytes = msg.data.size();
  return buffer;
}

cv::Mat imageToYuv(const sensor_msgs::Image& msg, std::int64_t max_pixels) {
  return io::bufferToYuv(imageBuffer(msg), max_pixels);
}

cv::Mat imageToBgr8(const sensor_msgs::Image& msg, std::int64_t max_pixels) {
  return io::bufferToBgr8(imageBuffer(msg), max_pixels);
}

sensor_msgs::Image uyvyToImage(const cv::Mat& uyvy, const std_msgs::Header& header) {
  return *cv_bridge::CvImage(header, enc::YUV422, uyvy).toImageMsg();
}

sensor_msgs::Image mono8ToImage(const cv::Mat& mono, const std_msgs::Header& header) {
  return *cv_bridge::CvImage(header, enc::MONO8, mono).toImageMsg();
}

sensor_msgs::Image bgr8ToImage(const cv::Mat& bgr, const std_msgs::Header& header) {
  return *cv_bridge::CvImage(header, enc::BGR8, bgr).toImageMsg();
}

cv::Mat imageToMono8(const sensor_msgs::Image& msg, std::int64_t max_pixels) {
  return io::bufferToMono8(imageBuffer(msg), max_pixels);
}

sensor_msgs::CameraInfo toCameraInfo(const world::PinholeCamera& c,
                                     const std_msgs::Header& header) {
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = c.width_px;
  info.height = c.height_px;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {c.fx_px, 0.0, c.cx_px, 0.0, c.fy_px, c.cy_px, 0.0, 0.0, 1.0};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {c.fx_px, 0.0, c.cx_px, 0.0, 0.0, c.fy_px, c.cy_px, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

bool hasDistortion(const sensor_msgs::CameraInfo& info) {
  for (double d : info.D)
    if (d != 0.0) return true;
  return false;
}

world::PinholeCamera fromCameraInfo(const sensor_msgs::CameraInfo& info) {
  world::PinholeCamera c;
  c.width_px = static_cast<int>(info.width);
  c.height_px = static_cast<int>(info.height);
  const bool rectified = hasDistortion(info) && info.P[0] > 0.0 && info.P[5] > 0.0;
  c.fx_px = rectified ? info.P[0] : info.K[0];
  c.fy_px = rectified ? info.P[5] : info.K[4];
  c.cx_px = rectified ? info.P[2] : info.K[2];
  c.cy_px = rectified ? info.P[6] : info.K[5];
  c.validate();
  return c;
}

geometry_msgs::Pose toPose(const math::SE2& p) {
  geometry_msgs::Pose m;
  m.position.x = p.x_m;
  m.position.y = p.y_m;
  m.orientation.z = std::sin(0.5 * p.yaw_rad);
  m.orientation.w = std::cos(0.5 * p.yaw_rad);
  return m;
}

geometry_msgs::Pose toPose(const Eigen::Isometry3d& t) {
  geometry_msgs::Pose m;
  m.position.x = t.translation().x();
  m.position.y = t.translation().y();
  m.position.z = t.translation().z();
  const Eigen::Quaterniond q(t.linear());
  m.orientation.x = q.x();
  m.orientation.y = q.y();
  m.orientation.z = q.z();
  m.orientation.w = q.w();
  return m;
}

Eigen::Isometry3d toIsometry(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
          .normalized()
          .toRotationMatrix();
  return t;
}

Eigen::Isometry3d toIsometry(const geometry_msgs::Transform& tr) {
  geometry_msgs::Pose p;
  p.position.x = tr.translation.x;
  p.position.y = tr.translation.y;
  p.position.z = tr.translation.z;
  p.orientation = tr.rotation;
  return toIsometry(p);
}

math::SE2 toSE2(const geometry_msgs::Pose& p) {
  const Eigen::Isometry3d t = toIsometry(p);
  const Eigen::Vector3d x_axis = t.linear().col(0);
  return math::SE2(t.translation().x(), t.translation().y(), std::atan2(x_axis.y(), x_axis.x()));
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& t, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped m;
  m.header.stamp = stamp;
  m.header.frame_id = parent;
  m.child_frame_id = child;
  const geometry_msgs::Pose p = toPose(t);
  m.transform.translation.x = p.position.x;
  m.transform.translation.y = p.position.y;
  m.transform.translation.z = p.position.z;
  m.transform.rotation = p.orientation;
  return m;
}

laser::LaserScan2D fromLaserScan(const sensor_msgs::LaserScan& msg) {
  laser::LaserScan2D s;
  s.angle_min_rad = msg.angle_min;
  s.angle_increment_rad = msg.angle_increment;
  s.range_min_m = msg.range_min;
  s.range_max_m = msg.range_max;
  s.ranges_m = msg.ranges;
  return s;
}

adaptive_perception::LineSegmentArray toLineSegmentArray(
    const std::vector<laser::LineSegment>& segments, const std_msgs::Header& header) {
  adaptive_perception::LineSegmentArray out;
  out.header = header;
  for (const auto& s : segments) {
    adaptive_perception::LineSegment m;
    m.rho = s.line.rho_m;
    m.alpha = s.line.alpha_rad;
    m.covariance = {s.line.cov(0, 0), s.line.cov(0, 1), s.line.cov(1, 0), s.line.cov(1, 1)};
    m.start.x = s.start_m.x();
    m.start.y = s.start_m.y();
    m.end.x = s.end_m.x();
    m.end.y = s.end_m.y();
    m.num_points = static_cast<std::uint32_t>(s.num_points);
    out.segments.push_back(m);
  }
  return out;
}

std::vector<laser::LineSegment> fromLineSegmentArray(
    const adaptive_perception::LineSegmentArray& msg) {
  std::vector<laser::LineSegment> out;
  for (const auto& m : msg.segments) {
    laser::LineSegment s;
    s.line.rho_m = m.rho;
    s.line.alpha_rad = m.alpha;
    s.line.cov << m.covariance[0], m.covariance[1], m.covariance[2], m.covariance[3];
    s.start_m = {m.start.x, m.start.y};
    s.end_m = {m.end.x, m.end.y};
    s.num_points = static_cast<int>(m.num_points);
    out.push_back(s);
  }
  return out;
}

std::vector<laser::TrueWallPiece> wallPieces(const adaptive_perception::LineSegmentArray& msg) {
  std::vector<laser::TrueWallPiece> out;
  for (const auto& w : msg.segments)
    out.push_back({Eigen::Vector2d(w.start.x, w.start.y), Eigen::Vector2d(w.end.x, w.end.y),
                   static_cast<int>(w.num_points)});
  return out;
}

ColorModel toColorModel(const color::SwitchingColorFilter& f, const std_msgs::Header& header) {
  ColorModel model;
  model.header = header;
  for (auto c : f.modelConfig().classes) model.color_names.push_back(world::colorClassName(c));
  const color::ColorFilter& a = f.active();
  model.mean.assign(a.mean().data(), a.mean().data() + a.mean().size());
  model.covariance.resize(a.cov().size());
  for (int i = 0; i < a.cov().rows(); ++i)
    for (int j = 0; j < a.cov().cols(); ++j)
      model.covariance[i * a.cov().cols() + j] = a.cov()(i, j);
  for (int ch = 0; ch < 3; ++ch) model.pixel_noise_var[ch] = a.pixelNoiseVar()[ch];
  for (int j = 0; j < f.numModes(); ++j) model.mode_names.push_back(f.modeName(j));
  model.mode_probabilities = f.modeProbabilities();
  model.active_mode = static_cast<std::uint8_t>(f.activeMode());
  return model;
}

geometry_msgs::PoseWithCovarianceStamped toPoseWithCovariance(const math::SE2& pose,
                                                              const Eigen::Matrix3d& cov,
                                                              const std_msgs::Header& header) {
  geometry_msgs::PoseWithCovarianceStamped out;
  out.header = header;
  out.pose.pose = toPose(pose);
  const int idx[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.pose.covariance[idx[i] * 6 + idx[j]] = cov(i, j);
  return out;
}

Eigen::Matrix3d planarCovariance(const geometry_msgs::PoseWithCovariance& msg) {
  Eigen::Matrix3d cov;
  const int idx[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cov(i, j) = msg.covariance[idx[i] * 6 + idx[j]];
  return cov;
}

PlanarPoseInput planarPoseInput(const geometry_msgs::PoseWithCovariance& msg, PoseYaw yaw) {
  const geometry_msgs::Point& p = msg.pose.position;
  const geometry_msgs::Quaternion& q = msg.pose.orientation;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw std::invalid_argument("position (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                                ", " + std::to_string(p.z) + ") is not finite");
  const double q_norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!std::isfinite(q_norm) || q_norm < 1e-6)
    throw std::invalid_argument("orientation quaternion of norm " + std::to_string(q_norm) +
                                " is not a rotation");
  PlanarPoseInput in;
  in.pose = toSE2(msg.pose);
  const Eigen::Matrix3d cov = planarCovariance(msg);
  if (cov.hasNaN()) throw std::invalid_argument("the (x, y, yaw) covariance holds a NaN");
  in.has_yaw = yaw == PoseYaw::kRequired ||
               (std::isfinite(cov(2, 2)) && cov(2, 2) > 0.0 && cov(2, 2) < kUnknownYawVariance);
  // The used block is checked as sent (symmetric to 1e-9), then symmetrised and checked again:
  // what is returned is what passed (a Cholesky factorisation reads one triangle only).
  const int n = in.has_yaw ? 3 : 2;
  const Eigen::MatrixXd used = cov.topLeftCorner(n, n);
  const Eigen::MatrixXd symmetric = 0.5 * (used + used.transpose());
  std::string problem = math::covarianceProblem(used);
  if (problem.empty()) problem = math::covarianceProblem(symmetric);
  if (!problem.empty())
    throw std::invalid_argument(std::string("the ") + (in.has_yaw ? "(x, y, yaw)" : "(x, y)") +
                                " covariance " + problem);
  in.cov = cov;
  in.cov.topLeftCorner(n, n) = symmetric;
  return in;
}

Eigen::Isometry3d mapToOdom(const math::SE2& map_to_base, const Eigen::Isometry3d& odom_to_base) {
  const Eigen::Isometry3d odom_planar =
      world::planarToIsometry(world::isometryToPlanar(odom_to_base));
  return world::planarToIsometry(map_to_base) * odom_planar.inverse();
}

cv::Rect2d polygonBox(const geometry_msgs::Polygon& polygon) {
  if (polygon.points.empty()) return {};
  double x0 = polygon.points[0].x, x1 = x0, y0 = polygon.points[0].y, y1 = y0;
  for (const auto& q : polygon.points) {
    x0 = std::min<double>(x0, q.x);
    x1 = std::max<double>(x1, q.x);
    y0 = std::min<double>(y0, q.y);
    y1 = std::max<double>(y1, q.y);
  }
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace adaptive_perception::ros_conv
