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
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/laser/line_evaluation.h"
#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/camera_model.h"

namespace adaptive_perception::ros_conv {

/// Thrown for an image the project cannot read; the message names the encoding or size problem.
class ImageFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The image as per-pixel YUV (CV_8UC3, channels Y U V, BT.601 full range). Accepts `yuv422`
/// (UYVY), `bgr8` and `rgb8`; throws ImageFormatError naming any other encoding or a malformed
/// buffer.
cv::Mat imageToYuv(const sensor_msgs::Image& msg);
/// The image as bgr8 (CV_8UC3, its own memory). Accepts `bgr8`, `rgb8`, `mono8` (the three
/// channels equal) and `yuv422` (UYVY, BT.601 full range); throws ImageFormatError naming any other encoding or a malformed buffer.
cv::Mat imageToBgr8(const sensor_msgs::Image& msg);
/// UYVY (CV_8UC2) as a `yuv422` image message.
sensor_msgs::Image uyvyToImage(const cv::Mat& uyvy, const std_msgs::Header& header);
/// mono8 (CV_8UC1) / bgr8 (CV_8UC3) image messages.
sensor_msgs::Image mono8ToImage(const cv::Mat& mono, const std_msgs::Header& header);
sensor_msgs::Image bgr8ToImage(const cv::Mat& bgr, const std_msgs::Header& header);
/// The axis-aligned bounding box of a polygon's points (pixels); empty for no point.
cv::Rect2d polygonBox(const geometry_msgs::Polygon& polygon);
/// A mono8 image as CV_8UC1 (shares no memory with the message); throws ImageFormatError otherwise.
cv::Mat imageToMono8(const sensor_msgs::Image& msg);

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
