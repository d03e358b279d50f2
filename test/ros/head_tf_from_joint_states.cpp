// head_tf_publisher against the camera file's own chain: base_link -> camera_optical_frame from tf
// at a joint_states stamp equals RobotCamera::baseToOptical at those angles; bad messages are
// skipped (no transform at their stamps) and a good one after them still gets through; the torso's
// pitch from imu leans the head.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <limits>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/world/robot_camera.h"

using namespace adaptive_perception;

namespace {

struct Fixture {
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  tf2_ros::Buffer buffer{ros::Duration(30.0)};
  tf2_ros::TransformListener listener{buffer};
  double t = 100.0;  // stamps far from each other, so tf never interpolates between them

  ros::Time send(const std::vector<std::string>& names, const std::vector<double>& positions) {
    sensor_msgs::JointState js;
    t += 1.0;
    js.header.stamp = ros::Time(t);
    js.name = names;
    js.position = positions;
    pub.publish(js);
    return js.header.stamp;
  }
  // The node subscribing is not the listener hearing /tf: a transform the node publishes before
  // the listener's connection is up is lost. Resends a warm-up message (stamps from `from_t` + 1,
  // far from the test's) until one arrives; false if none did within 20 s.
  bool warmUp(double from_t) {
    t = from_t;
    for (int attempt = 0; attempt < 40; ++attempt) {
      Eigen::Isometry3d warm;
      if (lookup(send({"HeadYaw", "HeadPitch"}, {0.0, 0.0}), 0.5, &warm)) return true;
    }
    return false;
  }
  // The transform at `stamp`, waiting up to `wait_s` for it (false: none came).
  bool lookup(const ros::Time& stamp, double wait_s, Eigen::Isometry3d* out) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(wait_s);
    while (ros::ok() && ros::WallTime::now() < end) {
      try {
        *out = ros_conv::toIsometry(
            buffer.lookupTransform("base_link", "camera_optical_frame", stamp).transform);
        return true;
      } catch (const tf2::TransformException&) {
        ros::WallDuration(0.05).sleep();
      }
    }
    return false;
  }
};

}  // namespace

TEST(HeadTfFromJointStates, ChainMatchesTheCameraFileAndBadMessagesAreSkipped) {
  Fixture f;
  const world::RobotCamera nao =
      world::RobotCamera::loadYaml(std::string(AP_SOURCE_DIR) + "/config/cameras/nao_v6_top.yaml");
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (f.pub.getNumSubscribers() == 0 && ros::WallTime::now() < end)
    ros::WallDuration(0.05).sleep();
  ASSERT_GT(f.pub.getNumSubscribers(), 0u) << "head_tf_publisher did not subscribe to joint_states";
  ASSERT_TRUE(f.warmUp(0.0)) << "no transform from head_tf_publisher within 20 s";
  f.t = 100.0;

  // A NAO's message: the head among other joints.
  const ros::Time good = f.send({"LShoulderPitch", "HeadYaw", "HeadPitch"}, {1.2, 0.3, -0.2});
  Eigen::Isometry3d got;
  ASSERT_TRUE(f.lookup(good, 10.0, &got)) << "no base_link -> camera_optical_frame";
  EXPECT_TRUE(got.isApprox(nao.baseToOptical(0.3, -0.2), 1e-6)) << got.matrix();

  // Skipped: the pitch missing, a NaN, a yaw beyond the joint's range, names without positions.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ros::Time missing = f.send({"HeadYaw"}, {0.1});
  const ros::Time not_finite = f.send({"HeadYaw", "HeadPitch"}, {nan, 0.0});
  const ros::Time out_of_range = f.send({"HeadYaw", "HeadPitch"}, {3.0, 0.0});
  const ros::Time no_positions = f.send({"HeadYaw", "HeadPitch"}, {});
  const ros::Time after = f.send({"HeadPitch", "HeadYaw"}, {0.25, -0.5});
  ASSERT_TRUE(f.lookup(after, 10.0, &got)) << "the node stopped after bad messages";
  EXPECT_TRUE(got.isApprox(nao.baseToOptical(-0.5, 0.25), 1e-6)) << got.matrix();
  for (const ros::Time& bad : {missing, not_finite, out_of_range, no_positions}) {
    // tf holds transforms at `good` and `after` only: a lookup at a skipped stamp interpolates
    // each joint's rotation about its fixed axis, which is the chain at the interpolated angles.
    Eigen::Isometry3d at;
    ASSERT_TRUE(f.lookup(bad, 1.0, &at));
    const double s = (bad - good).toSec() / (after - good).toSec();
    const Eigen::Isometry3d expected =
        nao.baseToOptical((1 - s) * 0.3 + s * -0.5, (1 - s) * -0.2 + s * 0.25);
    EXPECT_TRUE(at.isApprox(expected, 1e-6))
        << "a transform was published for a skipped message at t=" << bad.toSec();
  }
}

// The torso's pitch from imu leans the head by its difference from the camera file's reference
// (HeadChain::leanRad()); an orientation that is no rotation, or marked as not given, is skipped
// and leaves the last good one in place; a reading further than ~torso_pitch_max_age_s (0.5 s)
// from the joint_states leans nothing.
TEST(HeadTfFromJointStates, ImuLeansTheHeadAndBadImuIsSkipped) {
  Fixture f;
  ros::Publisher imu_pub = f.nh.advertise<sensor_msgs::Imu>("imu", 10);
  const world::RobotCamera nao =
      world::RobotCamera::loadYaml(std::string(AP_SOURCE_DIR) + "/config/cameras/nao_v6_top.yaml");
  ASSERT_TRUE(std::isfinite(nao.head.torso_pitch_reference_rad));
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while ((f.pub.getNumSubscribers() == 0 || imu_pub.getNumSubscribers() == 0) &&
         ros::WallTime::now() < end)
    ros::WallDuration(0.05).sleep();
  ASSERT_GT(imu_pub.getNumSubscribers(), 0u) << "head_tf_publisher did not subscribe to imu";
  ASSERT_TRUE(f.warmUp(150.0)) << "no transform from head_tf_publisher within 20 s";
  const auto sendImu = [&](double t, const Eigen::Quaterniond& q, bool given = true) {
    sensor_msgs::Imu imu;
    imu.header.stamp = ros::Time(t);
    imu.orientation.w = q.w(), imu.orientation.x = q.x(), imu.orientation.y = q.y(),
    imu.orientation.z = q.z();
    if (!given) imu.orientation_covariance[0] = -1.0;  // sensor_msgs/Imu: no orientation
    imu_pub.publish(imu);
    ros::WallDuration(0.5).sleep();  // heard before the joint_states that follow
  };
  const auto pitched = [](double pitch, double yaw) {  // the torso turned as it stands
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
  };
  // The development set's punt3 (torso -0.142 rad): 0.06 rad back from the reference.
  f.t = 199.0;  // send() stamps the next second: 200.0, the reading's own stamp
  sendImu(200.0, pitched(-0.142, 0.516));
  const ros::Time leaned = f.send({"HeadYaw", "HeadPitch"}, {0.1, -0.003});
  Eigen::Isometry3d got;
  ASSERT_TRUE(f.lookup(leaned, 10.0, &got)) << "no transform for the leaned head";
  EXPECT_TRUE(got.isApprox(nao.baseToOpticalAtTorsoPitch(0.1, -0.003, -0.142), 1e-6))
      << got.matrix();
  EXPECT_GT(got.linear().col(2).z(), nao.baseToOptical(0.1, -0.003).linear().col(2).z() + 0.05)
      << "leaning back must raise the optical axis";

  // A good reading, then one that is no rotation and one marked as no orientation: the good one
  // stays.
  f.t = 299.1;  // 300.1: 0.1 s after the good reading
  sendImu(300.0, pitched(0.008, -1.8));
  sendImu(300.05, Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0));
  sendImu(300.08, pitched(0.3, 0.0), false);
  const ros::Time after_bad = f.send({"HeadYaw", "HeadPitch"}, {0.0, -0.13});
  ASSERT_TRUE(f.lookup(after_bad, 10.0, &got)) << "the node stopped after a bad imu message";
  EXPECT_TRUE(got.isApprox(nao.baseToOpticalAtTorsoPitch(0.0, -0.13, 0.008), 1e-6)) << got.matrix();

  // 100 s after the last reading: no lean.
  f.t = 399.0;
  const ros::Time stale = f.send({"HeadYaw", "HeadPitch"}, {0.0, -0.13});
  ASSERT_TRUE(f.lookup(stale, 10.0, &got));
  EXPECT_TRUE(got.isApprox(nao.baseToOptical(0.0, -0.13), 1e-6)) << got.matrix();
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "head_tf_from_joint_states");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
