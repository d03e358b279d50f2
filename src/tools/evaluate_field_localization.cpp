// evaluate_field_localization: global localization of a robot from single real camera images: for
// each image of a list, rbpf_localizer's filter starts from nothing (uniform over the field, the
// lighting at its priors adapted to the image without a pose: adapt_priors_to_image, on here) and
// is given the same image again and again, as a robot standing still would see it; the estimate
// after --frames images is compared with the true position, if the list has one.
//
//   evaluate_field_localization --field FILE --camera FILE --list FILE [--output DIR]
//   evaluate_field_localization --help   (every option with its default, unit and range)
//
// --initial_pose X_M Y_M YAW_DEG starts each filter about that pose instead (a known start: does
// the filter hold the pose, or do its checks move it?).
//
// --camera: a camera file (world/robot_camera.h, config/cameras/): the intrinsics, and the head
// chain that turns each line's head_pitch_rad / head_yaw_rad into the camera's pose on the robot,
// leaned by the line's torso_pitch_rad where the file has a torso_pitch_reference_rad.
// --list: CSV `image,head_pitch_rad,head_yaw_rad,x_m,y_m,torso_pitch_rad` (io/head_image_list.h;
// the last three columns optional; scripts/nao_field_list.py writes one for the NAO development
// set). Every
// parameter of rbpf_localizer's table that comes from localization::RbpfConfig is an option of the
// same name, range and default. Writes OUTPUT/images.csv (one line per image, also printed) and
// OUTPUT/NAME.png (the image with the field's lines and landmarks drawn from the estimate). Last
// line:
//   evaluate_field_localization: images=.. median_position_error_m=.. within_0_5m=..
//       ms_per_image=..
// (the error and the count over the images with a true position; -1 when none has one).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/io/head_image_list.h"
#include "adaptive_perception/localization/goal_detection.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/world/label_renderer.h"
#include "adaptive_perception/world/robot_camera.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// The image with the map's colours drawn where the estimate says they are (background left as is).
cv::Mat drawEstimate(const cv::Mat& bgr, const world::FieldMap& map,
                     const world::PinholeCamera& camera, const Eigen::Isometry3d& map_to_optical) {
  const world::LabelRenderer renderer(map, camera);
  cv::Mat labels(camera.height_px, camera.width_px, CV_8UC1);
  renderer.renderImage(map_to_optical, labels.data);
  cv::Mat colours = color::colorizeLabels(labels), out = bgr.clone();
  const cv::Mat drawn = (labels != world::kBackground) & (labels != world::kGreen);
  cv::addWeighted(bgr, 0.4, colours, 0.6, 0.0, colours);
  colours.copyTo(out, drawn);
  return out;
}

// The goals the detector saw (the global search's proposals come from them): each post's box and
// the crossbar between the posts' tops; the best goal in magenta, the others in cyan.
void drawGoalSightings(const std::vector<localization::GoalSighting>& sightings, cv::Mat* image) {
  for (size_t i = 0; i < sightings.size(); ++i) {
    const cv::Scalar colour = i == 0 ? cv::Scalar(255, 0, 255) : cv::Scalar(255, 255, 0);
    const localization::GoalSighting& g = sightings[i];
    for (const localization::GoalPostSighting* p : {&g.left, &g.right})
      cv::rectangle(*image, cv::Point2d(p->u_px - 0.5 * p->width_px, p->foot_v_px - p->height_px),
                    cv::Point2d(p->u_px + 0.5 * p->width_px, p->foot_v_px), colour, 2);
    cv::line(*image, cv::Point2d(g.left.u_px, g.left.foot_v_px - g.left.height_px),
             cv::Point2d(g.right.u_px, g.right.foot_v_px - g.right.height_px), colour, 1);
  }
}

// The image as under another light: channels (0..1) raised to `gamma`, then scaled by the R, G, B
// gains (none: 1), rounded and clipped.
cv::Mat relight(const cv::Mat& bgr, const std::vector<double>& gains_rgb, double gamma) {
  cv::Mat f;
  bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
  if (gamma != 1.0) cv::pow(f, gamma, f);
  if (!gains_rgb.empty()) f = f.mul(cv::Scalar(gains_rgb[2], gains_rgb[1], gains_rgb[0]));
  cv::Mat out;
  f.convertTo(out, CV_8UC3, 255.0);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  localization::RbpfConfig cfg;
  tools::CommandLine cli("evaluate_field_localization",
                         "Global localization from single real camera images: the localizer "
                         "starts from nothing on each image, given it again and again as a robot "
                         "standing still sees it, and its estimate is compared with the true "
                         "position.");
  std::string field, camera_file, list_file;
  cli.option("field", &field, "the field (YAML, docs/fields.md; relative: from the package)")
      ->required();
  cli.option("camera", &camera_file,
             "the camera file (config/cameras/; relative: from the package)")
      ->required();
  cli.option("list", &list_file,
             "CSV image,head_pitch_rad,head_yaw_rad[,x_m,y_m[,torso_pitch_rad]]")
      ->required();
  int frames = 30;
  cli.option("frames", &frames, config::closed(1, 1000),
             "times each image is given to the filter (one second of a 30 Hz camera)");
  std::string priors_dir = "config/color_priors";
  cli.option("priors_dir", &priors_dir, "folder of the lighting priors");
  std::vector<double> initial_pose;
  cli.option("initial_pose", &initial_pose,
             "X_M Y_M YAW_DEG: start every image's filter from this pose (particles spread 0.05 m "
             "and 0.05 rad about it), not from nothing: does the filter hold a pose it is given?");
  std::vector<double> light_rgb;
  cli.option("light_rgb", &light_rgb,
             "R G B: each image as under another light, its channels scaled by these gains "
             "(after light_gamma; rounded and clipped to 0..255): does the localization hold "
             "when the light changes?");
  double light_gamma = 1.0;
  cli.option("light_gamma", &light_gamma, config::closed(0.1, 10),
             "each image's channels (0..1) raised to this power before light_rgb (above 1: "
             "darker, shadows more than highlights)");
  // Real images: the shipped priors are of simulated venues (RbpfConfig::adapt_priors_to_image).
  cfg.adapt_priors_to_image = true;
  cli.option("threads", &cfg.threads, "threads (the result is the same for any count)");
  cli.seed(&cfg.seed);
  const std::string& output = cli.resultsFolder("images.csv and one drawing per image");
  cli.fields(localization::RbpfConfig::fields(), &cfg);
  cli.parse(argc, argv);
  if (!initial_pose.empty() &&
      (initial_pose.size() != 3 || !std::all_of(initial_pose.begin(), initial_pose.end(),
                                                [](double v) { return std::isfinite(v); })))
    cli.fail("--initial_pose takes three finite numbers (x_m y_m yaw_deg)");
  if (!light_rgb.empty() &&
      (light_rgb.size() != 3 || !std::all_of(light_rgb.begin(), light_rgb.end(), [](double v) {
         return std::isfinite(v) && v > 0.0 && v <= 10.0;
       })))
    cli.fail("--light_rgb takes three gains in (0, 10] (R G B)");
  try {
    const world::FieldMap map = world::FieldMap::loadYaml(ros_params::resolvePackagePath(field));
    const world::RobotCamera camera =
        world::RobotCamera::loadYaml(ros_params::resolvePackagePath(camera_file));
    std::vector<color::LightingPrior> priors;
    const std::string dir = ros_params::resolvePackagePath(priors_dir);
    for (const std::string& m : ros_params::kDefaultSwitchingPriors)
      priors.push_back(color::LightingPrior::loadYaml((fs::path(dir) / (m + ".yaml")).string()));
    const std::vector<io::HeadImage> list = io::readHeadImageList(list_file);
    if (list.empty()) throw std::runtime_error(list_file + ": no images");
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "images.csv");
    const std::string header =
        "image,x_m,y_m,heading_deg,spread_m,cluster_weight,true_x_m,true_y_m,position_error_m,ms,"
        "goals_seen,camera_pitch_offset_rad,mirror_evidence,checks,relocalizations,"
        "max_check_score,white_gain_r,white_gain_g,white_gain_b,paint_luma_seen";
    csv << header << "\n";
    std::cout << header << "\n";
    std::vector<double> errors;
    double ms_total = 0.0;
    for (const io::HeadImage& item : list) {
      const std::string where = list_file + ":" + std::to_string(item.line) + ": ";
      cv::Mat bgr = cv::imread(item.path, cv::IMREAD_COLOR);
      if (bgr.empty()) throw std::runtime_error(where + item.path + ": cannot read the image");
      if (!light_rgb.empty() || light_gamma != 1.0) bgr = relight(bgr, light_rgb, light_gamma);
      if (bgr.cols != camera.camera.width_px || bgr.rows != camera.camera.height_px)
        throw std::runtime_error(where + item.path + " is " + std::to_string(bgr.cols) + "x" +
                                 std::to_string(bgr.rows) + " but the camera (" + camera.name +
                                 ") is " + std::to_string(camera.camera.width_px) + "x" +
                                 std::to_string(camera.camera.height_px));
      const cv::Mat yuv = color::bgrToYuv(bgr);
      const Eigen::Isometry3d base_to_optical = camera.baseToOpticalAtTorsoPitch(
          item.head_yaw_rad, item.head_pitch_rad, item.torso_pitch_rad.value_or(std::nan("")));
      const auto t0 = Clock::now();
      localization::RbpfLocalizer rbpf(map, camera.camera, priors, cfg);
      if (initial_pose.empty()) {
        rbpf.initUniform();
      } else {
        const double sd_m = 0.05, sd_rad = 0.05;
        rbpf.initGaussian(
            math::SE2(initial_pose[0], initial_pose[1], math::degToRad(initial_pose[2])),
            Eigen::Vector3d(sd_m * sd_m, sd_m * sd_m, sd_rad * sd_rad).asDiagonal());
      }
      int goals = -1;
      double pitch_offset = 0.0, mirror_evidence = 0.0;
      color::WhiteBalance balance;  // the last the images were read under
      // The relocalization checks that ended, how many found the particles lost, and the largest
      // margin a pose of a check's pool had over them (nan: no check ended).
      int checks = 0, relocalizations = 0;
      double max_check_score = std::numeric_limits<double>::quiet_NaN();
      for (int k = 0; k < frames; ++k) {
        const auto r = rbpf.step(math::SE2(), k == 0 ? 0.0 : 1.0 / 30.0, yuv, base_to_optical);
        if (r.goal_sightings >= 0) goals = r.goal_sightings;
        mirror_evidence = r.mirror_evidence;
        // (A restart inside a step forgets the balance until the next image sets it again.)
        if (!rbpf.whiteBalance().identity) balance = rbpf.whiteBalance();
        pitch_offset = r.camera_pitch_offset_rad;
        if (r.relocalization_checked) {
          ++checks;
          relocalizations += r.relocalized;
          if (!(r.relocalization_score <= max_check_score))
            max_check_score = r.relocalization_score;
        }
      }
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      ms_total += ms;
      const localization::PoseEstimate est = rbpf.estimate();
      double error = -1.0;
      if (item.truth_xy_m) {
        error =
            std::hypot(est.pose.x_m - item.truth_xy_m->x(), est.pose.y_m - item.truth_xy_m->y());
        errors.push_back(error);
      }
      const std::string name = fs::path(item.path).parent_path().filename().string() + "_" +
                               fs::path(item.path).stem().string();
      const Eigen::Vector3d& gains = balance.gains_rgb;
      char line[640];
      std::snprintf(
          line, sizeof line,
          "%s,%.3f,%.3f,%.1f,%.3f,%.3f,%s,%s,%.3f,%.0f,%d,%.4f,%.2f,%d,%d,%.2f,%.3f,%.3f,%.3f,%.1f",
          item.path.c_str(), est.pose.x_m, est.pose.y_m, math::radToDeg(est.pose.yaw_rad),
          est.spread_m, est.cluster_weight,
          item.truth_xy_m ? std::to_string(item.truth_xy_m->x()).c_str() : "",
          item.truth_xy_m ? std::to_string(item.truth_xy_m->y()).c_str() : "", error, ms, goals,
          pitch_offset, mirror_evidence, checks, relocalizations, max_check_score, gains[0],
          gains[1], gains[2], balance.white_yuv[0]);
      std::cout << line << std::endl;
      csv << line << "\n";
      cv::Mat drawing = drawEstimate(bgr, map, camera.camera,
                                     world::planarToIsometry(est.pose) *
                                         localization::leanCamera(base_to_optical, pitch_offset));
      const cv::Mat balanced = balance.apply(yuv);  // as the localizer read it
      drawGoalSightings(
          localization::detectGoals(
              balanced, color::segmentFieldYuv(balanced, color::FieldSegmentationConfig()),
              camera.camera, base_to_optical, map, cfg.goals),
          &drawing);
      cv::imwrite((fs::path(output) / (name + ".png")).string(), drawing);
    }
    double median = -1.0;
    int within = 0;
    if (!errors.empty()) {
      std::vector<double> e = errors;
      std::sort(e.begin(), e.end());
      median = e.size() % 2 ? e[e.size() / 2] : 0.5 * (e[e.size() / 2 - 1] + e[e.size() / 2]);
      within =
          static_cast<int>(std::count_if(e.begin(), e.end(), [](double v) { return v <= 0.5; }));
    }
    std::printf(
        "evaluate_field_localization: images=%zu median_position_error_m=%.3f within_0_5m=%d "
        "ms_per_image=%.0f\n",
        list.size(), median, errors.empty() ? -1 : within, ms_total / list.size());
  } catch (const std::exception& e) {
    std::cerr << "evaluate_field_localization: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
