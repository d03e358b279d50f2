// field_images_to_bag: single camera images of a robot standing on a field (the NAO development
// set, or a team's own pictures with the head angles they were taken at) written to a bag that the
// nodes replay as if the robot's camera ran: each image of the list is given again and again for
// --seconds_per_image at --rate_hz, with the camera's calibration and the head's joint angles, and
// odometry that does not move.
//
//   field_images_to_bag --list FILE --camera FILE --output BAG [--seconds_per_image S]
//   field_images_to_bag --help   (every option with its default, unit and range)
//
// --list: CSV `image,head_pitch_rad,head_yaw_rad[,x_m,y_m[,torso_pitch_rad]]`
// (io/head_image_list.h; scripts/nao_field_list.py writes one for the NAO development set; the true
// position, if given, is not written: the list gives no heading). --camera: a camera file
// (world/robot_camera.h, config/cameras/): the intrinsics for camera_info and the names of the pan
// and tilt joints. Every image must have the camera's size.
// Topics (DESIGN.md): camera/image_raw/compressed (sensor_msgs/CompressedImage: the file's own
// JPEG or PNG bytes, not re-encoded; replay with the nodes' ~image_transport compressed),
// camera/camera_info, joint_states (the camera file's pan_joint and tilt_joint), imu (where the
// list gives a torso pitch: the torso's orientation, pitched by it), odom and tf
// odom -> base_link (the identity: the robot stands). The head chain base_link -> camera is not
// written: head_tf_publisher makes it from joint_states, as on a NAO without a URDF. Frame ids:
// camera_optical_frame, odom, base_link. Consecutive images of the list follow each other with no
// gap, so a list of several places is a robot carried from one to the next.
// The bag is written to a temporary file beside BAG and renamed when complete; an existing BAG is
// kept unless --overwrite is given. Last line:
//   field_images_to_bag: output=.. images=.. frames=.. duration_s=.. bytes=..
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>

#include "adaptive_perception/io/head_image_list.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/robot_camera.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;
namespace fs = std::filesystem;

namespace {

std::string slash(const char* topic) { return std::string("/") + topic; }

// The file's bytes and the format string of ROS's compressed transport for them ("bgr8; jpeg
// compressed bgr8"), checked to decode to the camera's size. `where` names the list line.
sensor_msgs::CompressedImage readCompressed(const std::string& path, const std::string& where,
                                            const world::RobotCamera& camera) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(where + path + ": cannot open the image");
  sensor_msgs::CompressedImage msg;
  msg.data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const bool jpeg = msg.data.size() > 3 && msg.data[0] == 0xFF && msg.data[1] == 0xD8;
  const bool png = msg.data.size() > 8 && msg.data[0] == 0x89 && msg.data[1] == 'P' &&
                   msg.data[2] == 'N' && msg.data[3] == 'G';
  if (!jpeg && !png)
    throw std::runtime_error(where + path + ": not a JPEG or PNG file (the compressed transport "
                                            "carries only those)");
  const cv::Mat decoded = cv::imdecode(msg.data, cv::IMREAD_COLOR);
  if (decoded.empty()) throw std::runtime_error(where + path + ": the image does not decode");
  if (decoded.cols != camera.camera.width_px || decoded.rows != camera.camera.height_px)
    throw std::runtime_error(where + path + " is " + std::to_string(decoded.cols) + "x" +
                             std::to_string(decoded.rows) + " but the camera (" + camera.name +
                             ") is " + std::to_string(camera.camera.width_px) + "x" +
                             std::to_string(camera.camera.height_px));
  msg.format = std::string("bgr8; ") + (jpeg ? "jpeg" : "png") + " compressed bgr8";
  return msg;
}

}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("field_images_to_bag",
                         "Single camera images of a robot standing on a field, each given again "
                         "and again as its camera would, with camera_info, the head's joint "
                         "angles and still odometry, written to a bag.");
  const std::string& output = cli.outputFile("the bag to write", "the bag");
  std::string camera_file, list_file;
  cli.option("camera", &camera_file,
             "the camera file (config/cameras/; relative: from the package)")
      ->required();
  cli.option("list", &list_file,
             "CSV image,head_pitch_rad,head_yaw_rad[,x_m,y_m[,torso_pitch_rad]]")
      ->required();
  double seconds_per_image = 3.0;
  cli.option("seconds_per_image", &seconds_per_image, config::closed(0.1, 3600.0),
             "how long each image is shown, s");
  double rate_hz = 30.0;
  cli.option("rate_hz", &rate_hz, config::closed(0.1, 1000.0),
             "camera frames per second (a NAO's camera: 30)");
  double start_time_s = 1.6e9;
  cli.option("start_time_s", &start_time_s, config::closed(1, 4e9), "the bag's first stamp, s");
  cli.parse(argc, argv);
  try {
    const world::RobotCamera camera =
        world::RobotCamera::loadYaml(ros_params::resolvePackagePath(camera_file));
    const std::vector<io::HeadImage> list = io::readHeadImageList(list_file);
    if (list.empty()) throw std::runtime_error(list_file + ": no images");
    // Every image is read and checked before the bag is opened: a bad list leaves no bag behind.
    std::vector<sensor_msgs::CompressedImage> images;
    for (const io::HeadImage& item : list) {
      const std::string where = list_file + ":" + std::to_string(item.line) + ": ";
      if (!camera.head.inJointRange(item.head_yaw_rad, item.head_pitch_rad))
        throw std::runtime_error(where + "head angles (pitch " +
                                 std::to_string(item.head_pitch_rad) + ", yaw " +
                                 std::to_string(item.head_yaw_rad) +
                                 " rad) outside the joint ranges of " + camera.name);
      images.push_back(readCompressed(item.path, where, camera));
    }
    const int frames_per_image = std::max(1, static_cast<int>(std::lround(seconds_per_image *
                                                                           rate_hz)));
    ros::Time::init();
    ros_bag::BagWriter bag(output, cli.overwriteGiven());
    const ros::Time t0(start_time_s);
    std::uint32_t seq = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      for (int k = 0; k < frames_per_image; ++k, ++seq) {
        const ros::Time stamp = t0 + ros::Duration(seq / rate_hz);
        tf2_msgs::TFMessage tf;
        tf.transforms.push_back(ros_conv::toTransform(Eigen::Isometry3d::Identity(),
                                                      T::kOdomFrame, T::kBaseFrame, stamp));
        bag.write("/tf", stamp, tf);
        nav_msgs::Odometry odom;
        odom.header.stamp = stamp;
        odom.header.seq = seq;
        odom.header.frame_id = T::kOdomFrame;
        odom.child_frame_id = T::kBaseFrame;
        odom.pose.pose.orientation.w = 1.0;
        bag.write(slash(T::kOdom), stamp, odom);
        // The torso first: head_tf_publisher leans each joint_states by the reading nearest it.
        if (list[i].torso_pitch_rad) {
          sensor_msgs::Imu imu;  // the torso's orientation only: pitched, level otherwise
          imu.header.stamp = stamp;
          imu.header.seq = seq;
          imu.header.frame_id = T::kBaseFrame;
          const Eigen::Quaterniond q(
              Eigen::AngleAxisd(*list[i].torso_pitch_rad, Eigen::Vector3d::UnitY()));
          imu.orientation.w = q.w(), imu.orientation.x = q.x(), imu.orientation.y = q.y(),
          imu.orientation.z = q.z();
          imu.angular_velocity_covariance[0] = -1.0;  // not given (sensor_msgs/Imu)
          imu.linear_acceleration_covariance[0] = -1.0;
          bag.write(slash(T::kImu), stamp, imu);
        }
        sensor_msgs::JointState joints;
        joints.header.stamp = stamp;
        joints.header.seq = seq;
        joints.name = {camera.pan_joint, camera.tilt_joint};
        joints.position = {list[i].head_yaw_rad, list[i].head_pitch_rad};
        bag.write(slash(T::kJointStates), stamp, joints);
        std_msgs::Header h;
        h.stamp = stamp;
        h.seq = seq;
        h.frame_id = T::kCameraOpticalFrame;
        sensor_msgs::CompressedImage image = images[i];
        image.header = h;
        bag.write(slash(T::kCameraImage) + "/compressed", stamp, image);
        bag.write(slash(T::kCameraInfo), stamp, ros_conv::toCameraInfo(camera.camera, h));
      }
    }
    const auto bytes = bag.close();
    std::printf("field_images_to_bag: output=%s images=%zu frames=%u duration_s=%.1f bytes=%llu\n",
                output.c_str(), list.size(), seq, seq / rate_hz,
                static_cast<unsigned long long>(bytes));
  } catch (const std::exception& e) {
    std::cerr << "field_images_to_bag: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
