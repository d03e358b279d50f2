#include "adaptive_perception/ros/head_tf_publisher_node.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/node_run.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"

namespace adaptive_perception {

namespace {
constexpr char kDefaultCamera[] = "config/cameras/nao_v6_top.yaml";
constexpr double kTorsoPitchMaxAge_s = 0.5;
constexpr bool kLeanFromImu = true;
}  // namespace

std::vector<config::ParameterDoc> HeadTfNode::parameters() {
  return {
      {"camera_file", "string", kDefaultCamera, "a camera file",
       "the camera and head chain (world/robot_camera.h; relative: from the package); its "
       "pan_joint and tilt_joint name the joints read from joint_states"},
      ros_params::frameParameter("base"),
      {"pan_frame", "string", ros_topics::kHeadPanFrame, "", "the frame the pan joint turns"},
      {"tilt_frame", "string", ros_topics::kHeadTiltFrame, "", "the frame the tilt joint turns"},
      {"camera_frame", "string", ros_topics::kCameraFrame, "", "the lens, x forward"},
      {"optical_frame", "string", ros_topics::kCameraOpticalFrame, "",
       "the camera's optical frame (z forward, x right, y down): the images' frame_id"},
      {"lean_from_imu", "bool", kLeanFromImu ? "true" : "false", "",
       "lean the head by the torso's pitch from imu, for a camera file with a "
       "torso_pitch_reference_rad (the body's lean, which the head's joints do not see)"},
      {"torso_pitch_max_age_s", "double", config::formatReal(kTorsoPitchMaxAge_s), "[0, 60]",
       "the imu reading stamped nearest a joint_states message leans the head if it is within "
       "this time of it (s); else no lean. An inertial unit publishes at 10 Hz or more, and a "
       "standing robot's lean changes over seconds"}};
}

HeadTfNode::HeadTfNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "head_tf", 1.0, 1000.0) {
  camera_file_ = ros_params::getName(pnh, "camera_file", kDefaultCamera);
  camera_ = world::RobotCamera::loadYaml(ros_params::resolvePackagePath(camera_file_));
  base_frame_ = ros_params::getFrameId(pnh, "base_frame", ros_topics::kBaseFrame);
  pan_frame_ = ros_params::getFrameId(pnh, "pan_frame", ros_topics::kHeadPanFrame);
  tilt_frame_ = ros_params::getFrameId(pnh, "tilt_frame", ros_topics::kHeadTiltFrame);
  camera_frame_ = ros_params::getFrameId(pnh, "camera_frame", ros_topics::kCameraFrame);
  optical_frame_ = ros_params::getFrameId(pnh, "optical_frame", ros_topics::kCameraOpticalFrame);
  torso_pitch_max_age_s_ =
      ros_params::getInRange(pnh, "torso_pitch_max_age_s", kTorsoPitchMaxAge_s, 0.0, 60.0);
  const ros::Time now = ros::Time::now();
  static_broadcaster_.sendTransform(std::vector<geometry_msgs::TransformStamped>{
      ros_conv::toTransform(camera_.head.tiltCamera(), tilt_frame_, camera_frame_, now),
      ros_conv::toTransform(world::HeadChain::cameraOptical(), camera_frame_, optical_frame_,
                            now)});
  sub_ = nh.subscribe(ros_topics::kJointStates, 100, &HeadTfNode::callback, this);
  lean_from_imu_ = ros_params::get(pnh, "lean_from_imu", kLeanFromImu) &&
                   std::isfinite(camera_.head.torso_pitch_reference_rad);
  if (lean_from_imu_)
    imu_sub_ = nh.subscribe(ros_topics::kImu, 200, &HeadTfNode::imuCallback, this);
  diagnostics_.add("head chain", this, &HeadTfNode::check);
  ROS_INFO("head_tf_publisher: camera %s (%s): %s -> %s from joint_states %s and %s%s",
           camera_.name.c_str(), camera_file_.c_str(), base_frame_.c_str(), optical_frame_.c_str(),
           camera_.pan_joint.c_str(), camera_.tilt_joint.c_str(),
           lean_from_imu_ ? ", leaned by the torso's pitch from imu"
                          : " (imu is not read: ~lean_from_imu off or the camera file has no "
                            "torso_pitch_reference_rad)");
}

void HeadTfNode::imuCallback(const sensor_msgs::ImuConstPtr& msg) {
  const auto& o = msg->orientation;
  const Eigen::Quaterniond q(o.w, o.x, o.y, o.z);
  std::string problem;
  if (msg->orientation_covariance[0] == -1.0) {
    problem = "imu gives no orientation (orientation_covariance[0] = -1)";
  } else if (!q.coeffs().allFinite() || q.norm() < 1e-6) {
    std::ostringstream s;
    s << "imu orientation (" << o.x << ", " << o.y << ", " << o.z << ", " << o.w
      << ") is not a rotation (non-finite or zero)";
    problem = s.str();
  }
  if (!problem.empty()) {
    ++imu_skipped_;
    last_imu_problem_ = problem;
    ROS_ERROR_THROTTLE(5.0, "head_tf_publisher: %s; the head is not leaned by it", problem.c_str());
    return;
  }
  const ros::Time stamp = msg->header.stamp.isZero() ? ros::Time::now() : msg->header.stamp;
  torso_pitch_.emplace_back(stamp, world::pitchBelowHorizontal(q));
  // Readings more than the age window behind the newest cannot be the nearest to any new
  // joint_states within it; a reading stamped earlier than the newest (a bag's jump back) clears
  // the rest.
  if (torso_pitch_.size() > 1 && stamp < torso_pitch_[torso_pitch_.size() - 2].first)
    torso_pitch_.erase(torso_pitch_.begin(), torso_pitch_.end() - 1);
  while (!torso_pitch_.empty() &&
         (stamp - torso_pitch_.front().first).toSec() > 2.0 * torso_pitch_max_age_s_ + 1.0)
    torso_pitch_.pop_front();
}

void HeadTfNode::callback(const sensor_msgs::JointStateConstPtr& msg) {
  const auto skip = [&](const std::string& why) {
    ++skipped_;
    last_problem_ = why;
    ROS_ERROR_THROTTLE(5.0, "head_tf_publisher: joint_states skipped: %s", why.c_str());
  };
  if (msg->position.size() != msg->name.size()) {
    // A message of other joints only (no positions for them) is normal on a robot: only an
    // inconsistent one is an error.
    std::ostringstream s;
    s << msg->name.size() << " names but " << msg->position.size() << " positions";
    return skip(s.str());
  }
  int pan = -1, tilt = -1;
  for (std::size_t i = 0; i < msg->name.size(); ++i) {
    if (msg->name[i] == camera_.pan_joint) pan = static_cast<int>(i);
    if (msg->name[i] == camera_.tilt_joint) tilt = static_cast<int>(i);
  }
  if (pan < 0 && tilt < 0) return;  // a message about other joints
  if (pan < 0 || tilt < 0)
    return skip("'" + (pan < 0 ? camera_.pan_joint : camera_.tilt_joint) +
                "' is missing (the camera file " + camera_file_ + " names '" + camera_.pan_joint +
                "' and '" + camera_.tilt_joint + "')");
  const double pan_rad = msg->position[pan], tilt_rad = msg->position[tilt];
  if (!camera_.head.inJointRange(pan_rad, tilt_rad)) {
    std::ostringstream s;
    s << camera_.pan_joint << " = " << pan_rad << " rad (range [" << camera_.head.min_pan_rad
      << ", " << camera_.head.max_pan_rad << "]), " << camera_.tilt_joint << " = " << tilt_rad
      << " rad (range [" << camera_.head.min_tilt_rad << ", " << camera_.head.max_tilt_rad
      << "]): outside the camera file's joint range or not finite";
    return skip(s.str());
  }
  const ros::Time stamp = msg->header.stamp.isZero() ? ros::Time::now() : msg->header.stamp;
  double lean_rad = 0.0;
  const auto nearest =
      std::min_element(torso_pitch_.begin(), torso_pitch_.end(), [&](const auto& a, const auto& b) {
        return std::abs((a.first - stamp).toSec()) < std::abs((b.first - stamp).toSec());
      });
  if (nearest != torso_pitch_.end() &&
      std::abs((nearest->first - stamp).toSec()) <= torso_pitch_max_age_s_) {
    lean_rad = camera_.head.leanRad(nearest->second);
    ++leaned_;
  }
  broadcaster_.sendTransform(std::vector<geometry_msgs::TransformStamped>{
      ros_conv::toTransform(camera_.head.basePan(pan_rad, lean_rad), base_frame_, pan_frame_,
                            stamp),
      ros_conv::toTransform(camera_.head.panTilt(tilt_rad), pan_frame_, tilt_frame_, stamp)});
  ++published_;
  diagnostics_.tick();
  diagnostics_.update();
}

void HeadTfNode::check(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (skipped_ > 0 && published_ == 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR,
                 "every joint_states skipped: " + last_problem_);
  else if (skipped_ > 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 "some joint_states skipped: " + last_problem_);
  else if (lean_from_imu_ && published_ > 0 && leaned_ == 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 imu_skipped_ > 0 ? "the head is not leaned: " + last_imu_problem_
                                  : "the head is not leaned: no imu reading near the "
                                    "joint_states (a bag without imu, or another topic?)");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "publishing the head chain");
  stat.add("camera", camera_.name);
  stat.add("head transforms published", published_);
  stat.add("joint_states skipped", skipped_);
  if (lean_from_imu_) {
    stat.add("head transforms leaned by imu", leaned_);
    stat.add("imu messages skipped", imu_skipped_);
    if (imu_skipped_ > 0) stat.add("last imu problem", last_imu_problem_);
    if (!torso_pitch_.empty()) stat.add("torso pitch (rad)", torso_pitch_.back().second);
  }
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<HeadTfNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
