// simulate_indoor: a robot with a camera driving once through the indoor building
// (config/worlds/indoor_building.yaml) under one lighting condition, written to a bag and/or PNGs.
//
//   simulate_indoor --help   (every option with its default, unit and range)
//
// Topics: camera/image_raw (bgr8; frame camera_link, x forward), camera/camera_info (perspective
// only), odom + tf odom -> base_link, tf_static base_link -> camera_link, ground_truth/pose
// (PoseStamped in map), ground_truth/place (std_msgs/String, the place the robot is in, at each
// image's stamp; images outside every place are labelled "none"). --images_out writes
// DIR/NNNNN.png and DIR/images.csv (`image_path,place`, paths relative to the CSV) for image-list
// workflows (train_places / evaluate_places --list). Either --output or --images_out is needed.
// Deterministic for a seed: the seed draws the lighting (intensities, colour temperatures, sun
// direction), the odometry noise and the camera noise; the building is always the same.
// Last line: `simulate_indoor: output=FILE images=N places=P duration_s=S lighting=L camera=C`.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/sim/indoor_renderer.h"
#include "adaptive_perception/sim/indoor_route.h"
#include "adaptive_perception/world/camera_model.h"
#include "progress.h"
#include "tick_schedule.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("simulate_indoor",
                         "A robot with a camera driving once through the indoor building under one "
                         "lighting condition, written to a bag and/or PNGs.");
  std::string world_path = "config/worlds/indoor_building.yaml";
  cli.option("world", &world_path, "the building (YAML; relative: from the package)");
  sim::IndoorLightingKind kind = sim::IndoorLightingKind::kCloudy;
  cli.word("lighting", &kind, sim::indoorLightings(), "the lighting condition");
  const std::uint64_t& seed = cli.seed();
  std::string output;
  cli.option("output", &output, "the bag to write");
  std::string images_out;
  cli.option("images_out", &images_out, "folder for PNGs and images.csv");
  std::string camera_name = "perspective";
  cli.option("camera", &camera_name, "camera model")
      ->oneOf({"perspective", "omni"});
  double camera_rate = 2.0;
  cli.option("camera_rate_hz", &camera_rate, config::aboveZero(30), "camera rate, Hz");
  double odom_rate = 20.0;
  cli.option("odom_rate_hz", &odom_rate, "odometry rate, Hz, in [camera_rate_hz, 1000]");
  double duration_arg = -1.0;
  cli.option("duration_s", &duration_arg, "simulated time, s (<= 0: the whole route)");
  const bool& overwrite = cli.overwrite("the bag and images.csv");
  long width = 0, height = 0;
  cli.option("width_px", &width, "image width, px, in 8..4096 (0: the camera's own)");
  cli.option("height_px", &height, "image height, px, in 8..4096 (0: the camera's own)");
  cli.parse(argc, argv);
  if (output.empty() && images_out.empty()) cli.fail("--output FILE.bag or --images_out DIR");
  if (!(odom_rate >= camera_rate && odom_rate <= 1000.0))
    cli.fail("--odom_rate_hz must be in [camera_rate_hz, 1000]");
  if (!output.empty()) cli.refuseExisting(output);
  if (!images_out.empty()) cli.refuseExisting((fs::path(images_out) / "images.csv").string());
  try {
    const sim::IndoorWorld world =
        sim::IndoorWorld::loadYaml(ros_params::resolvePackagePath(world_path));
    sim::IndoorCameraConfig cam;
    cam.omni = camera_name == "omni";
    if (width > 0 || height > 0) {
      if (width < 8 || height < 8 || width > 4096 || height > 4096)
        cli.fail("--width_px and --height_px must both be in 8..4096");
      if (cam.omni) {
        // Scale the donut with the image.
        const double k = std::min(width / 320.0, height / 240.0);
        cam.omni_width_px = static_cast<int>(width);
        cam.omni_height_px = static_cast<int>(height);
        cam.inner_radius_px *= k;
        cam.outer_radius_px *= k;
      } else {
        cam.width_px = static_cast<int>(width);
        cam.height_px = static_cast<int>(height);
      }
    }
    const sim::IndoorRenderer renderer(world, cam);
    math::Rng rng(seed * 7919 + 17);
    const sim::IndoorLighting lighting = sim::IndoorLighting::sample(kind, rng);
    sim::IndoorRoute robot(world, rng.split());
    math::Rng camera_rng(rng.split());
    const double duration = duration_arg > 0.0
                                ? std::min(duration_arg, sim::IndoorRoute::duration(world))
                                : sim::IndoorRoute::duration(world);

    std::unique_ptr<ros_bag::BagWriter> bag;
    if (!output.empty()) bag = std::make_unique<ros_bag::BagWriter>(output, overwrite);
    std::ostringstream csv;  // written atomically at the end (io::writeTextFileAtomically)
    if (!images_out.empty()) {
      fs::create_directories(images_out);
      csv << "image_path,place\n";
    }
    const ros::Time t0(1.6e9);
    // Camera 0.1 m ahead of the body centre at the configured height, looking forward.
    const Eigen::Isometry3d base_to_camera =
        Eigen::Translation3d(0.1, 0.0, cam.height_m) * Eigen::Isometry3d::Identity();
    if (bag) {
      tf2_msgs::TFMessage st;
      st.transforms.push_back(
          ros_conv::toTransform(base_to_camera, T::kBaseFrame, T::kCameraFrame, t0));
      bag->writeLatched("/tf_static", t0, st, "/simulate_indoor");
    }
    sensor_msgs::CameraInfo info;
    if (!cam.omni) {
      const world::PinholeCamera pin = world::PinholeCamera::fromFieldOfView(
          cam.width_px, cam.height_px, cam.hfov_deg * M_PI / 180.0,
          2.0 * std::atan(std::tan(0.5 * cam.hfov_deg * M_PI / 180.0) * cam.height_px /
                          cam.width_px));
      std_msgs::Header h;
      h.frame_id = T::kCameraOpticalFrame;
      info = ros_conv::toCameraInfo(pin, h);
    }

    const std::set<std::int64_t> odom_ticks = tools::tickTimesNs(odom_rate, duration);
    const std::set<std::int64_t> cam_ticks = tools::tickTimesNs(camera_rate, duration);
    std::set<std::int64_t> events = odom_ticks;
    events.insert(cam_ticks.begin(), cam_ticks.end());
    double t_prev = 0.0;
    long images = 0;
    std::map<std::string, int> per_place;
    tools::Progress progress("simulate_indoor", static_cast<long>(events.size()), "steps");
    long step = 0;
    for (std::int64_t ns : events) {
      progress.update(++step);
      const double t = ns * 1e-9;
      robot.step(t - t_prev);
      t_prev = t;
      const ros::Time stamp = t0 + ros::Duration(t);
      if (bag) {
        nav_msgs::Odometry o;
        o.header.stamp = stamp;
        o.header.frame_id = T::kOdomFrame;
        o.child_frame_id = T::kBaseFrame;
        o.pose.pose = ros_conv::toPose(robot.odomPose());
        bag->write("/" + std::string(T::kOdom), stamp, o);
        tf2_msgs::TFMessage tf;
        tf.transforms.push_back(ros_conv::toTransform(world::planarToIsometry(robot.odomPose()),
                                                      T::kOdomFrame, T::kBaseFrame, stamp));
        bag->write("/tf", stamp, tf);
        geometry_msgs::PoseStamped truth;
        truth.header.stamp = stamp;
        truth.header.frame_id = T::kMapFrame;
        truth.pose = ros_conv::toPose(robot.truePose());
        bag->write("/" + std::string(T::kGroundTruthPose), stamp, truth);
      }
      if (!cam_ticks.count(ns)) continue;
      const math::SE2 camera_pose = robot.truePose() * math::SE2(0.1, 0.0, 0.0);
      const cv::Mat image = renderer.render(camera_pose, lighting, camera_rng);
      const int place = world.placeAt({robot.truePose().x_m, robot.truePose().y_m});
      const std::string place_name = place >= 0 ? world.places[place].name : "none";
      ++per_place[place_name];
      std_msgs::Header header;
      header.stamp = stamp;
      header.seq = static_cast<std::uint32_t>(images);
      header.frame_id = T::kCameraFrame;
      if (bag) {
        bag->write("/" + std::string(T::kCameraImage), stamp, ros_conv::bgr8ToImage(image, header));
        if (!cam.omni) {
          info.header = header;
          info.header.frame_id = T::kCameraOpticalFrame;
          bag->write("/" + std::string(T::kCameraInfo), stamp, info);
        }
        std_msgs::String label;
        label.data = place_name;
        bag->write("/" + std::string(T::kGroundTruthPlace), stamp, label);
      }
      if (!images_out.empty()) {
        char name[32];
        std::snprintf(name, sizeof(name), "%05ld.png", images);
        if (!cv::imwrite((fs::path(images_out) / name).string(), image))
          throw std::runtime_error(images_out + ": cannot write " + name);
        csv << name << "," << place_name << "\n";
      }
      ++images;
    }
    if (!images_out.empty()) {
      io::writeTextFileAtomically((fs::path(images_out) / "images.csv").string(), csv.str());
    }
    if (bag) bag->close();
    std::string counts;
    for (const auto& [p, n] : per_place)
      counts += (counts.empty() ? "" : ",") + p + ":" + std::to_string(n);
    std::cerr << "simulate_indoor: images per place " << counts << "\n";
    std::printf(
        "simulate_indoor: output=%s images=%ld places=%zu duration_s=%.1f lighting=%s "
        "camera=%s\n",
        output.empty() ? images_out.c_str() : output.c_str(), images, world.places.size(), duration,
        sim::indoorLightingName(kind).c_str(), camera_name.c_str());
  } catch (const std::exception& e) {
    std::cerr << "simulate_indoor: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
