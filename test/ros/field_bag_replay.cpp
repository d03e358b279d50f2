// rostest: a bundled simulator bag replayed through the foundation nodes is self-consistent.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <map>
#include <mutex>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/label_renderer.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;

namespace {

struct Collected {
  std::mutex mutex;
  std::vector<sensor_msgs::ImageConstPtr> images, labels;
  std::map<ros::Time, sensor_msgs::CameraInfoConstPtr> infos;
  std::map<ros::Time, geometry_msgs::PoseStampedConstPtr> truth;
  std::map<ros::Time, sensor_msgs::JointStateConstPtr> joints;
  size_t markers = 0;
};

class FieldBagReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    expected_frames_ = ros::NodeHandle("~").param("expected_frames", 33);
    keep<sensor_msgs::Image>(T::kCameraImage, 100, [this](auto m) { c_.images.push_back(m); });
    keep<sensor_msgs::Image>(T::kCameraLabels, 100, [this](auto m) { c_.labels.push_back(m); });
    keep<sensor_msgs::CameraInfo>(T::kCameraInfo, 100,
                                  [this](auto m) { c_.infos[m->header.stamp] = m; });
    keep<geometry_msgs::PoseStamped>(T::kGroundTruthPose, 1000,
                                     [this](auto m) { c_.truth[m->header.stamp] = m; });
    keep<sensor_msgs::JointState>(T::kJointStates, 1000,
                                  [this](auto m) { c_.joints[m->header.stamp] = m; });
    keep<visualization_msgs::MarkerArray>(T::kFieldMap, 1,
                                          [this](auto m) { c_.markers = m->markers.size(); });
    spinner_.start();
    // Wait (wall time) for the whole bag.
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> l(c_.mutex);
        if (static_cast<int>(c_.images.size()) >= expected_frames_ &&
            static_cast<int>(c_.labels.size()) >= expected_frames_)
          break;
      }
      ros::WallDuration(0.1).sleep();
    }
    ros::WallDuration(1.0).sleep();  // let the last tf arrive
  }

  /// Subscribes `topic`; `store` files each message under the collection's lock.
  template <class M, class F>
  void keep(const std::string& topic, uint32_t depth, F store) {
    subs_.push_back(
        nh_.subscribe<M>(topic, depth, [this, store](const boost::shared_ptr<M const>& m) {
          std::lock_guard<std::mutex> l(c_.mutex);
          store(m);
        }));
  }

  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  std::vector<ros::Subscriber> subs_;
  tf2_ros::Buffer tf_buffer_{ros::Duration(120.0)};
  tf2_ros::TransformListener tf_listener_{tf_buffer_};
  Collected c_;
  int expected_frames_ = 33;
};

TEST_F(FieldBagReplay, ImagesTfAndGroundTruthAreConsistent) {
  std::lock_guard<std::mutex> l(c_.mutex);
  ASSERT_EQ(static_cast<int>(c_.images.size()), expected_frames_) << "not every frame arrived";
  ASSERT_EQ(c_.labels.size(), c_.images.size());
  EXPECT_EQ(c_.markers, 35u) << "field_map markers";

  const world::FieldMap map;
  const world::HeadChain head;
  world::PinholeCamera camera;
  ros::Time prev;
  double label_agreement_sum = 0.0;
  for (size_t i = 0; i < c_.images.size(); ++i) {
    const auto& img = c_.images[i];
    const ros::Time stamp = img->header.stamp;
    SCOPED_TRACE("frame " + std::to_string(i) + " at " + std::to_string(stamp.toSec()));
    EXPECT_EQ(img->encoding, "yuv422");
    EXPECT_EQ(img->header.frame_id, T::kCameraOpticalFrame);
    EXPECT_EQ(img->width, 208u);
    EXPECT_EQ(img->height, 160u);
    EXPECT_GT(stamp, prev);
    prev = stamp;

    // Camera info and labels with the image's stamp and frame.
    ASSERT_TRUE(c_.infos.count(stamp));
    camera = ros_conv::fromCameraInfo(*c_.infos[stamp]);
    EXPECT_EQ(c_.infos[stamp]->header.frame_id, T::kCameraOpticalFrame);
    EXPECT_EQ(c_.labels[i]->header.stamp, stamp);
    EXPECT_EQ(c_.labels[i]->encoding, "mono8");

    // Ground truth and joint states exist at the image stamp.
    ASSERT_TRUE(c_.truth.count(stamp));
    ASSERT_TRUE(c_.joints.count(stamp));
    EXPECT_EQ(c_.truth[stamp]->header.frame_id, T::kMapFrame);

    // tf: map -> base_link (via ground_truth_tf_publisher's map -> odom) equals the ground truth.
    geometry_msgs::TransformStamped map_base, base_cam, map_cam;
    ASSERT_NO_THROW(map_base = tf_buffer_.lookupTransform(T::kMapFrame, T::kBaseFrame, stamp));
    const math::SE2 truth = ros_conv::toSE2(c_.truth[stamp]->pose);
    const math::SE2 from_tf =
        ros_conv::toSE2(ros_conv::toPose(ros_conv::toIsometry(map_base.transform)));
    EXPECT_NEAR(from_tf.x_m, truth.x_m, 1e-6);
    EXPECT_NEAR(from_tf.y_m, truth.y_m, 1e-6);
    EXPECT_NEAR(math::angleDiff(from_tf.yaw_rad, truth.yaw_rad), 0.0, 1e-6);

    // tf: base_link -> camera_optical_frame equals the head chain at the joint angles.
    ASSERT_NO_THROW(base_cam =
                        tf_buffer_.lookupTransform(T::kBaseFrame, T::kCameraOpticalFrame, stamp));
    const auto& js = *c_.joints[stamp];
    ASSERT_EQ(js.name.size(), 2u);
    const Eigen::Isometry3d expect = head.baseToOptical(js.position[0], js.position[1]);
    EXPECT_LT((ros_conv::toIsometry(base_cam.transform).matrix() - expect.matrix()).norm(), 1e-6);

    // The true labels agree with the map rendered from the tf camera pose (the gait shake of the
    // true camera, which tf does not carry, moves edges by a few pixels).
    ASSERT_NO_THROW(map_cam =
                        tf_buffer_.lookupTransform(T::kMapFrame, T::kCameraOpticalFrame, stamp));
    const world::LabelRenderer renderer(map, camera);
    std::vector<std::uint8_t> rendered(camera.width_px * camera.height_px);
    renderer.renderImage(ros_conv::toIsometry(map_cam.transform), rendered.data());
    const cv::Mat labels = ros_conv::imageToMono8(*c_.labels[i]);
    int same = 0;
    for (int k = 0; k < static_cast<int>(rendered.size()); ++k)
      same += labels.data[k] == rendered[k];
    label_agreement_sum += static_cast<double>(same) / rendered.size();
  }
  EXPECT_GT(label_agreement_sum / c_.images.size(), 0.9)
      << "labels vs map rendered at the tf camera pose";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "field_bag_replay");
  return RUN_ALL_TESTS();
}
