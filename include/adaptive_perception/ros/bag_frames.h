#pragma once
// Offline access to a bag's camera frames with their camera pose in `map`, for the evaluate_* and
// learn_* tools: every image on camera/image_raw (as YUV), its true labels from camera/labels when
// the bag has them (simulator bags), the camera model from camera/camera_info, and map ->
// camera_optical_frame at the image stamp from the bag's own tf tree, closed to `map` with the
// ground truth as ground_truth_tf_publisher does (map -> odom = truth * (odom -> base_link)^-1 at
// the truth's stamp).
#include <ros/time.h>

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/world/camera_model.h"

namespace tf2 {
class BufferCore;
}

namespace adaptive_perception::ros_bag {

struct CameraFrame {
  ros::Time stamp;
  cv::Mat yuv;          // CV_8UC3 Y, U, V
  cv::Mat true_labels;  // CV_8UC1 class ids, empty when the bag has none
  world::PinholeCamera camera;
  bool has_pose = false;
  Eigen::Isometry3d map_to_optical = Eigen::Isometry3d::Identity();
  std::string lighting_condition;  // from lighting/state when present
  // From the bag's own tf (no ground truth needed): odom -> base_link and base_link -> camera at
  // the stamp.
  bool has_odom = false;
  Eigen::Isometry3d odom_to_base = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d base_to_optical = Eigen::Isometry3d::Identity();
  // Ground truth base_link in map at the stamp, when the bag has it.
  bool has_truth = false;
  Eigen::Isometry3d map_to_base = Eigen::Isometry3d::Identity();
};

class BagFrameReader {
 public:
  /// Opens and indexes the bag (tf, ground truth, labels). Throws std::runtime_error naming the
  /// file on an unreadable bag or one without camera/image_raw.
  explicit BagFrameReader(const std::string& path,
                          const std::string& camera_frame = "camera_optical_frame");
  ~BagFrameReader();

  /// All frames in stamp order (images that cannot be read are counted in skippedFrames()).
  std::vector<CameraFrame> readAll();
  int skippedFrames() const { return skipped_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_, camera_frame_;
  std::unique_ptr<tf2::BufferCore> tf_;
  std::map<ros::Time, cv::Mat> labels_;
  std::map<ros::Time, std::string> conditions_;
  world::PinholeCamera camera_;
  bool has_camera_info_ = false;
  int skipped_ = 0;
};

}  // namespace adaptive_perception::ros_bag
