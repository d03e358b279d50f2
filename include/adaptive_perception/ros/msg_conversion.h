#pragma once
// Message <-> core conversion. The ONLY place that touches cv_bridge and message layouts of images.
#include <geometry_msgs/Polygon.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/Header.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/io/image_buffer.h"
#include "adaptive_perception/laser/line_evaluation.h"
#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/camera_model.h"

namespace adaptive_perception::ros_conv {

/// Thrown for an image the project cannot read (io/image_buffer.h); names what was wrong.
using ImageFormatError = io::ImageFormatError;
/// The most pixels an image may have before a node refuses it, unless its ~max_image_pixels says
/// otherwise (io/image_buffer.h gives the reason).
constexpr std::int64_t kDefaultMaxImagePixels = io::kDefaultMaxImagePixels;

/// The message's pixels as io::ImageBuffer sees them (a view of its data).
io::ImageBuffer imageBuffer(const sensor_msgs::Image& msg);
/// The image as per-pixel YUV (io::bufferToYuv): yuv422, bgr8, rgb8; throws ImageFormatError
/// naming any other encoding, a malformed buffer or more than `max_pixels` pixels.
cv::Mat imageToYuv(const sensor_msgs::Image& msg, std::int64_t max_pixels = kDefaultMaxImagePixels);
/// The image as bgr8 (io::bufferToBgr8): bgr8, rgb8, mono8, yuv422; throws as imageToYuv.
cv::Mat imageToBgr8(const sensor_msgs::Image& msg,
                    std::int64_t max_pixels = kDefaultMaxImagePixels);
/// UYVY (CV_8UC2) as a `yuv422` image message.
sensor_msgs::Image uyvyToImage(const cv::Mat& uyvy, const std_msgs::Header& header);
/// mono8 (CV_8UC1) / bgr8 (CV_8UC3) image messages.
sensor_msgs::Image mono8ToImage(const cv::Mat& mono, const std_msgs::Header& header);
sensor_msgs::Image bgr8ToImage(const cv::Mat& bgr, const std_msgs::Header& header);
/// The axis-aligned bounding box of a polygon's points (pixels); empty for no point.
cv::Rect2d polygonBox(const geometry_msgs::Polygon& polygon);
/// A mono8 image as CV_8UC1 (shares no memory with the message); throws ImageFormatError otherwise.
cv::Mat imageToMono8(const sensor_msgs::Image& msg,
                     std::int64_t max_pixels = kDefaultMaxImagePixels);

/// CameraInfo of a pinhole camera without distortion.
sensor_msgs::CameraInfo toCameraInfo(const world::PinholeCamera& camera,
                                     const std_msgs::Header& header);
/// The camera of the images a node works on: camera_info's K, or its P (the rectified camera)
/// when it has lens distortion (hasDistortion), as image_geometry defines them. Throws
/// std::invalid_argument on a bad size or focal length.
world::PinholeCamera fromCameraInfo(const sensor_msgs::CameraInfo& info);
/// True when any distortion coefficient is non-zero.
bool hasDistortion(const sensor_msgs::CameraInfo& info);

geometry_msgs::Pose toPose(const math::SE2& pose);
geometry_msgs::Pose toPose(const Eigen::Isometry3d& pose);
/// Planar pose (x, y, yaw) of a 3-D pose.
math::SE2 toSE2(const geometry_msgs::Pose& pose);
Eigen::Isometry3d toIsometry(const geometry_msgs::Pose& pose);
Eigen::Isometry3d toIsometry(const geometry_msgs::Transform& t);
geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& parent_to_child,
                                            const std::string& parent, const std::string& child,
                                            const ros::Time& stamp);

/// A planar pose and its (x, y, yaw) covariance as PoseWithCovarianceStamped (the 6x6 row-major
/// covariance over x, y, z, roll, pitch, yaw; the rest zero).
geometry_msgs::PoseWithCovarianceStamped toPoseWithCovariance(const math::SE2& pose,
                                                              const Eigen::Matrix3d& cov,
                                                              const std_msgs::Header& header);
/// The (x, y, yaw) block of a PoseWithCovariance's covariance.
Eigen::Matrix3d planarCovariance(const geometry_msgs::PoseWithCovariance& msg);

/// A yaw variance at or above this says "yaw unknown" in a pose input read with PoseYaw::kIfKnown
/// (1e3 rad^2: a standard deviation of 31 rad, no information about a heading).
constexpr double kUnknownYawVariance = 1e3;
/// How a pose input's heading is read. kRequired (initialpose): the pose and the whole (x, y, yaw)
/// covariance are used. kIfKnown (external_pose): the heading is used only when its variance is
/// finite, positive and below kUnknownYawVariance; otherwise only the position and its (x, y)
/// block are.
enum class PoseYaw { kRequired, kIfKnown };
struct PlanarPoseInput {
  math::SE2 pose;
  Eigen::Matrix3d cov;  // symmetrised; with has_yaw false only its (x, y) block is checked
  bool has_yaw = true;
};
/// A pose-with-covariance input (initialpose, external_pose) read the one way every node reads
/// it: the position finite, the orientation a finite quaternion of non-zero norm, no NaN in the
/// (x, y, yaw) covariance, and the part of it that is used a covariance by
/// math::covarianceProblem (finite, symmetric, positive definite). Throws std::invalid_argument
/// naming what is wrong; the node logs it and keeps its estimate.
PlanarPoseInput planarPoseInput(const geometry_msgs::PoseWithCovariance& msg, PoseYaw yaw);
/// map -> odom from the estimated map -> base and the odometry odom -> base (flattened to the
/// plane), as a localizer publishes it.
Eigen::Isometry3d mapToOdom(const math::SE2& map_to_base, const Eigen::Isometry3d& odom_to_base);

/// The ColorModel message of a switching filter: the active mode's estimate and every mode's
/// probability.
ColorModel toColorModel(const color::SwitchingColorFilter& filter, const std_msgs::Header& header);

/// The core scan of a LaserScan message.
laser::LaserScan2D fromLaserScan(const sensor_msgs::LaserScan& msg);
/// Segments <-> LineSegmentArray (the header gives the stamp and frame).
LineSegmentArray toLineSegmentArray(const std::vector<laser::LineSegment>& segments,
                                    const std_msgs::Header& header);
std::vector<laser::LineSegment> fromLineSegmentArray(const LineSegmentArray& msg);
/// The true wall pieces of a simulator's ground_truth/walls message (num_points = returns on the
/// piece).
std::vector<laser::TrueWallPiece> wallPieces(const LineSegmentArray& msg);

}  // namespace adaptive_perception::ros_conv
