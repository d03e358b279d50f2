// evaluate_localization: runs the Rao-Blackwellised localizer offline over a field bag from a
// uniform (global) start, against ground_truth/pose and the bag's true labels.
//
//   evaluate_localization --help   (every option with its default, unit and range)
// Every parameter of rbpf_localizer's table (docs/nodes/rbpf_localizer.md) that comes from
// localization::RbpfConfig is an option of the same name, range and default (--help lists them).
//
// Converged: the first frame after which the position error stays below 0.3 m (for the rest of the
// run, or until a kidnap, a jump of the true pose over 0.5 m between frames, after which
// convergence is measured again: reconverged_after_kidnap_s). Errors are medians over converged
// frames. classification_rate: the best particle's lighting model (eq. 9, plain maximum likelihood)
// scored on the true labels. Writes OUTPUT/results.yaml, frames.csv, estimate.tum, truth.tum
// (scripts/plot_localization.py plots them). Last line:
//   evaluate_localization: median_position_error_m=.. median_heading_error_deg=..
//       converged_after_s=.. [reconverged_after_kidnap_s=..] classification_rate=.. frames_per_s=..
//       frames=N
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/ros/bag_frames.h"
#include "adaptive_perception/ros/params.h"
#include "command_line.h"
#include "progress.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

namespace {
void tum(std::ofstream& f, double t, const math::SE2& p) {
  f << std::fixed << t << " " << p.x_m << " " << p.y_m << " 0 0 0 " << std::sin(0.5 * p.yaw_rad)
    << " " << std::cos(0.5 * p.yaw_rad) << "\n";
}
double median(std::vector<double> v) {
  if (v.empty()) return -1.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  localization::RbpfConfig cfg;
  tools::CommandLine cli("evaluate_localization",
                         "Runs the Rao-Blackwellised localizer offline over a field bag from a "
                         "uniform (global) start, against ground_truth/pose and the bag's true "
                         "labels.");
  const std::string& bag = cli.inputBag("field bag with ground truth");
  std::string filter = "switching";
  cli.option("filter", &filter, "lighting filter: switching (one mode per prior) or single")
      ->oneOf({"switching", "single"});
  cli.option("threads", &cfg.threads, "threads (the result is the same for any count)");
  cli.seed(&cfg.seed);
  std::string init = "global";
  cli.option("init", &init, "start: uniform over the field (global) or at the true pose")
      ->oneOf({"global", "truth"});
  std::string priors_dir = "config/color_priors";
  cli.option("priors_dir", &priors_dir, "folder of the lighting priors");
  std::string field = "config/field_4legged.yaml";
  cli.option("field", &field, "the bag's field (YAML, docs/fields.md; relative: from the package)");
  const std::string& output = cli.resultsFolder("results.yaml, frames.csv and the trajectories");
  std::string name;
  cli.option("name", &name, "label of the run (empty: the bag's file name)");
  // Every parameter of rbpf_localizer's table that comes from the core config: the same name,
  // range and default.
  cli.fields(localization::RbpfConfig::fields(), &cfg);
  cli.parse(argc, argv);
  if (name.empty()) name = fs::path(bag).stem().string();
  try {
    const std::string dir = ros_params::resolvePackagePath(priors_dir);
    std::vector<color::LightingPrior> priors;
    for (const std::string& m : filter == "switching"
                                    ? ros_params::kDefaultSwitchingPriors
                                    : std::vector<std::string>{ros_params::kDefaultSinglePrior})
      priors.push_back(color::LightingPrior::loadYaml((fs::path(dir) / (m + ".yaml")).string()));
    ros_bag::BagFrameReader reader(bag);
    const auto frames = reader.readAll();
    if (frames.empty()) throw std::runtime_error(bag + ": no readable camera frames");
    const world::FieldMap map = world::FieldMap::loadYaml(ros_params::resolvePackagePath(field));
    localization::RbpfLocalizer rbpf(map, frames.front().camera, priors, cfg);
    if (init == "truth") {  // tracking: start around the first true pose (0.2 m, 10 degrees)
      for (const auto& f : frames)
        if (f.has_truth) {
          rbpf.initGaussian(world::isometryToPlanar(f.map_to_base),
                            Eigen::Vector3d(0.04, 0.04, 0.03).asDiagonal());
          break;
        }
    }
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "frames.csv"), est_tum(fs::path(output) / "estimate.tum"),
        truth_tum(fs::path(output) / "truth.tum");
    csv << "t_s,position_error_m,heading_error_deg,ess,classification_rate,"
           "mean_pixel_log_likelihood,relocalization_score,relocalized,second_draw,mirror_evidence,"
           "mirror_flipped\n";
    const double t0 = frames.front().stamp.toSec();
    bool have_prev = false;
    Eigen::Isometry3d prev_odom = Eigen::Isometry3d::Identity();
    double prev_t = 0.0, compute_s = 0.0;
    std::vector<double> t_s, pos_err, head_err;
    std::vector<int> kidnaps;  // frame indices where the true pose jumped (a kidnap)
    math::SE2 prev_truth;
    long correct = 0, total = 0;
    int used = 0;
    tools::Progress progress("evaluate_localization", static_cast<long>(frames.size()), "frames");
    for (const auto& f : frames) {
      progress.update(static_cast<long>(&f - frames.data()) + 1);
      if (!f.has_odom || !f.has_truth) continue;
      const double t = f.stamp.toSec() - t0;
      const math::SE2 delta =
          have_prev ? world::isometryToPlanar(prev_odom.inverse() * f.odom_to_base) : math::SE2();
      const auto c0 = std::chrono::steady_clock::now();
      const auto r = rbpf.step(delta, have_prev ? t - prev_t : 0.0, f.yuv, f.base_to_optical);
      compute_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      have_prev = true;
      prev_odom = f.odom_to_base;
      prev_t = t;
      const math::SE2 est = rbpf.estimate().pose, truth = world::isometryToPlanar(f.map_to_base);
      const double pe = std::hypot(est.x_m - truth.x_m, est.y_m - truth.y_m);
      const double he = std::fabs(math::radToDeg(math::angleDiff(est.yaw_rad, truth.yaw_rad)));
      double rate = -1.0;
      if (!f.true_labels.empty()) {
        color::ColorLut lut;
        color::ColorModelConfig gate_off = cfg.model;
        gate_off.unknown_mahalanobis = 1e9;
        const color::ColorFilter& a = rbpf.best().lighting.active();
        std::vector<Eigen::Vector3d> means;
        std::vector<Eigen::Matrix3d> covs;
        for (int k = 0; k < gate_off.numColors(); ++k) {
          means.push_back(a.colorMean(k));
          covs.push_back(a.colorCov(k) + Eigen::Matrix3d(a.pixelNoiseVar().asDiagonal()));
        }
        lut.build(
            color::PixelClassifier(means, covs, gate_off.classes, gate_off.unknown_mahalanobis));
        cv::Mat cls;
        lut.classifyYuv(f.yuv, &cls);
        long fc = 0, ft = 0;
        for (size_t k = 0; k < cls.total(); ++k) {
          const std::uint8_t tl = f.true_labels.data[k];
          if (gate_off.colorIndex(tl) < 0) continue;
          ++ft;
          fc += cls.data[k] == tl;
        }
        correct += fc;
        total += ft;
        rate = ft ? double(fc) / ft : -1.0;
      }
      csv << t << "," << pe << "," << he << "," << r.effective_sample_size << "," << rate << ","
          << r.mean_pixel_log_likelihood << ","
          << (std::isnan(r.relocalization_score) ? std::string()
                                                 : std::to_string(r.relocalization_score))
          << "," << int(r.relocalized) << "," << int(r.second_draw) << "," << r.mirror_evidence
          << "," << int(r.mirror_flipped) << "\n";
      tum(est_tum, f.stamp.toSec(), est);
      tum(truth_tum, f.stamp.toSec(), truth);
      if (!t_s.empty() && std::hypot(truth.x_m - prev_truth.x_m, truth.y_m - prev_truth.y_m) > 0.5)
        kidnaps.push_back(static_cast<int>(t_s.size()));
      prev_truth = truth;
      t_s.push_back(t);
      pos_err.push_back(pe);
      head_err.push_back(he);
      ++used;
    }
    if (used == 0) throw std::runtime_error(bag + ": no frame with odometry and ground truth");
    // Convergence per segment (the run, split at kidnaps): the first frame after which the error
    // stays below 0.3 m to the end of the segment; times from the segment's start.
    std::vector<int> bounds{0};
    bounds.insert(bounds.end(), kidnaps.begin(), kidnaps.end());
    bounds.push_back(static_cast<int>(pos_err.size()));
    std::vector<double> pe_c, he_c, converged_after_seg;
    for (size_t k = 0; k + 1 < bounds.size(); ++k) {
      int conv = bounds[k + 1];
      for (int i = bounds[k + 1] - 1; i >= bounds[k] && pos_err[i] < 0.3; --i) conv = i;
      pe_c.insert(pe_c.end(), pos_err.begin() + conv, pos_err.begin() + bounds[k + 1]);
      he_c.insert(he_c.end(), head_err.begin() + conv, head_err.begin() + bounds[k + 1]);
      converged_after_seg.push_back(conv < bounds[k + 1] ? t_s[conv] - t_s[bounds[k]] : -1.0);
    }
    const double converged_after = converged_after_seg.front();
    const double after_kidnap = converged_after_seg.size() > 1 ? converged_after_seg[1] : -1.0;
    const double fps = used / std::max(compute_s, 1e-9);
    std::ofstream yaml(fs::path(output) / "results.yaml");
    yaml << "bag: " << bag << "\nparticles: " << cfg.particles << "\nfilter: " << filter
         << "\nthreads: " << cfg.threads << "\npixel_stride: " << cfg.likelihood.pixel_stride
         << "\nframes: " << used << "\nconverged_after_s: " << converged_after
         << "\nkidnaps: " << kidnaps.size() << "\nreconverged_after_kidnap_s: " << after_kidnap
         << "\nmedian_position_error_m: " << median(pe_c)
         << "\nmedian_heading_error_deg: " << median(he_c)
         << "\nclassification_rate: " << (total ? double(correct) / total : -1.0)
         << "\nframes_per_s: " << fps << "\n";
    std::printf(
        "evaluate_localization: median_position_error_m=%.3f median_heading_error_deg=%.2f "
        "converged_after_s=%.2f%s classification_rate=%.3f frames_per_s=%.1f frames=%d\n",
        median(pe_c), median(he_c), converged_after,
        kidnaps.empty() ? ""
                        : (" reconverged_after_kidnap_s=" + std::to_string(after_kidnap)).c_str(),
        total ? double(correct) / total : -1.0, fps, used);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_localization: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
