// evaluate_color_estimation: runs the colour estimator with known (ground-truth) camera poses over
// a bag and scores every pixel's classification against the bag's true labels (Schulz & Fox, Table
// 1, Fig. 6).
//
//   evaluate_color_estimation --help   (every option with its default, unit and range)
//
// switching: one mode per prior in --modes; single: one Kalman filter from the prior --single.
// independent: the same priors with every cross-colour covariance zeroed. --unobserved withholds
// that colour's observations from the filter (it is still scored). Pixels are classified as the
// node does: maximum likelihood over the map colours behind the "unknown" gate
// (--unknown_mahalanobis, default the node's; 1e9 gives the paper's plain maximum likelihood).
// background_rejected is the share of true background pixels the gate calls unknown. Writes
// OUTPUT/results.yaml, OUTPUT/frames.csv and OUTPUT/rates.png. Last line:
//   evaluate_color_estimation: overall=.. green=.. white=.. pink=.. yellow=.. cyan=.. frames=N
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "adaptive_perception/color/color_estimator.h"
#include "adaptive_perception/ros/bag_frames.h"
#include "adaptive_perception/ros/params.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_color_estimation",
                         "Runs the colour estimator with known camera poses over a bag and scores "
                         "every pixel's classification against the bag's true labels (Schulz & "
                         "Fox, Table 1, Fig. 6).");
  const std::string& bag = cli.inputBag("field bag with true labels");
  std::string filter = "switching";
  cli.option("filter", &filter, "one mode per prior in --modes, or one Kalman filter (--single)")
      ->oneOf({"switching", "single"});
  std::string prior_kind = "joint";
  cli.option("prior", &prior_kind, "the priors as learned, or with cross-colour covariances zeroed")
      ->oneOf({"joint", "independent"});
  std::string unobserved;
  cli.option("unobserved", &unobserved,
             "a colour whose observations are withheld from the filter (still scored)");
  std::string priors_dir = "config/color_priors";
  cli.option("priors_dir", &priors_dir, "folder of the lighting priors (<mode>.yaml)");
  std::string modes_arg = "dark,bright";
  cli.option("modes", &modes_arg, "the switching filter's modes (comma-separated prior names)");
  std::string single = "all";
  cli.option("single", &single, "the single filter's prior");
  std::string mixing = "best_mode";
  cli.option("mixing", &mixing, "mode mixing of the switching filter: best_mode or imm");
  const std::string& output = cli.resultsFolder("the results and plots");
  std::string name;
  cli.option("name", &name, "label of the run (empty: the bag's file name)");
  bool no_plot = false;
  cli.flag("no_plot", &no_plot, "skip the plots");
  // color_estimator's parameters (the same names and ranges). Scored as the node classifies:
  // maximum likelihood behind the "unknown" gate; --unknown_mahalanobis 1e9 gives the paper's
  // plain maximum likelihood over the map colours.
  color::ColorEstimatorConfig cfg;
  cli.fields(color::ColorEstimatorConfig::fields(), &cfg);
  cli.parse(argc, argv);
  if (name.empty()) name = fs::path(bag).stem().string();
  const bool plot = !no_plot;

  try {
    cfg.switching.mixing = color::parseModeMixing(mixing);
    if (!unobserved.empty()) {
      const auto c = world::parseColorClass(unobserved);
      if (!c || *c == world::kBackground)
        cli.fail("--unobserved: unknown colour '" + unobserved + "'");
      cfg.withheld_class = *c;
    }
    std::vector<std::string> mode_names;
    if (filter == "single") {
      mode_names = {single};
    } else {
      std::string s;
      for (std::stringstream ss(modes_arg); std::getline(ss, s, ',');) mode_names.push_back(s);
    }
    const std::string dir = ros_params::resolvePackagePath(priors_dir);
    std::vector<color::LightingPrior> priors;
    for (const auto& m : mode_names) {
      color::LightingPrior p =
          color::LightingPrior::loadYaml((fs::path(dir) / (m + ".yaml")).string());
      priors.push_back(prior_kind == "independent" ? p.independent() : p);
    }

    ros_bag::BagFrameReader reader(bag);
    const auto frames = reader.readAll();
    if (frames.empty()) throw std::runtime_error(bag + ": no readable camera frames");
    color::ColorEstimator est(world::FieldMap(), frames.front().camera, priors, cfg);
    const auto& classes = cfg.model.classes;
    const int m = static_cast<int>(classes.size());
    std::vector<long> correct(m, 0), total(m, 0);
    std::vector<std::array<long, 256>> confusion(m);  // [true colour][predicted class id]
    for (auto& row : confusion) row.fill(0);
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "frames.csv");
    csv << "t_s,overall";
    for (auto c : classes) csv << "," << world::colorClassName(c);
    csv << ",active_mode,condition\n";
    int used = 0, no_pose = 0, no_labels = 0;
    long background_total = 0, background_rejected = 0;
    // Withheld colour: distance (YUV levels) between the filter's estimate of its mean and its
    // actual mean in the image (true labels), over frames that show it: how well the model predicts
    // a colour it never observed (the point of the joint prior).
    const int withheld_k = cfg.withheld_class >= 0
                               ? cfg.model.colorIndex(static_cast<std::uint8_t>(cfg.withheld_class))
                               : -1;
    double unobserved_error_sum = 0.0;
    int unobserved_error_frames = 0;  // true background pixels, and those called unknown
    const double t0 = frames.front().stamp.toSec();
    for (const auto& f : frames) {
      if (!f.has_pose) {
        ++no_pose;
        continue;
      }
      if (f.true_labels.empty()) {
        ++no_labels;
        continue;
      }
      const auto r = est.process(f.stamp.toSec() - t0, f.yuv, f.map_to_optical);
      std::vector<long> fc(m, 0), ft(m, 0);
      for (int y = 0; y < f.true_labels.rows; ++y) {
        const std::uint8_t* t = f.true_labels.ptr<std::uint8_t>(y);
        const std::uint8_t* p = r.classified.ptr<std::uint8_t>(y);
        for (int x = 0; x < f.true_labels.cols; ++x) {
          const int k = cfg.model.colorIndex(t[x]);
          if (t[x] == world::kBackground) {
            ++background_total;
            background_rejected += p[x] == world::kBackground;
          }
          if (k < 0) continue;
          ++ft[k];
          fc[k] += p[x] == t[x];
          ++confusion[k][p[x]];
        }
      }
      if (withheld_k >= 0) {
        const color::ColorObservation truth_obs =
            color::computeColorObservation(f.yuv, f.true_labels, cfg.model);
        if (truth_obs.counts[withheld_k] >= cfg.model.min_pixels_per_color) {
          unobserved_error_sum +=
              (est.filter().active().colorMean(withheld_k) - truth_obs.means[withheld_k]).norm();
          ++unobserved_error_frames;
        }
      }
      long fca = 0, fta = 0;
      for (int k = 0; k < m; ++k) {
        correct[k] += fc[k];
        total[k] += ft[k];
        fca += fc[k];
        fta += ft[k];
      }
      csv << f.stamp.toSec() - t0 << "," << (fta ? double(fca) / fta : -1.0);
      for (int k = 0; k < m; ++k) csv << "," << (ft[k] ? double(fc[k]) / ft[k] : -1.0);
      csv << "," << est.filter().modeName(r.active_mode) << ","
          << (f.lighting_condition.empty() ? "-" : f.lighting_condition) << "\n";
      ++used;
    }
    csv.close();
    long ca = 0, ta = 0;
    for (int k = 0; k < m; ++k) {
      ca += correct[k];
      ta += total[k];
    }
    auto rate = [](long c, long t) { return t ? double(c) / t : -1.0; };
    std::ofstream yaml(fs::path(output) / "results.yaml");
    yaml << "bag: " << bag << "\nname: " << name << "\nfilter: " << filter
         << "\nprior: " << prior_kind << "\nmixing: " << mixing
         << "\nunobserved: " << (unobserved.empty() ? "none" : unobserved) << "\nframes: " << used
         << "\nframes_without_pose: " << no_pose << "\nframes_without_labels: " << no_labels
         << "\nlut_rebuilds: " << est.lutRebuilds() << "\nrates:\n  overall: " << rate(ca, ta)
         << "\n";
    for (int k = 0; k < m; ++k)
      yaml << "  " << world::colorClassName(classes[k]) << ": " << rate(correct[k], total[k])
           << "\n";
    const double unobserved_error =
        unobserved_error_frames ? unobserved_error_sum / unobserved_error_frames : -1.0;
    if (withheld_k >= 0)
      yaml << "unobserved_mean_error: " << unobserved_error << "  # YUV levels, over "
           << unobserved_error_frames << " frames showing the withheld colour\n";
    yaml << "background_rejected: " << rate(background_rejected, background_total)
         << "  # share of true background pixels classified unknown\n";
    yaml << "confusion:  # share of each true colour's pixels given each class\n";
    for (int k = 0; k < m; ++k) {
      yaml << "  " << world::colorClassName(classes[k]) << ": {";
      bool first = true;
      for (int c = 0; c < 256; ++c) {
        if (!confusion[k][c]) continue;
        yaml << (first ? "" : ", ") << world::colorClassName(static_cast<std::uint8_t>(c)) << ": "
             << rate(confusion[k][c], total[k]);
        first = false;
      }
      yaml << "}\n";
    }
    yaml << "pixels:\n";
    for (int k = 0; k < m; ++k)
      yaml << "  " << world::colorClassName(classes[k]) << ": " << total[k] << "\n";
    yaml.close();
    if (plot) {
      const std::string script = ros_params::resolvePackagePath("scripts/plot_color_rates.py");
      const std::string cmd = "PATH=/usr/bin:$PATH python3 '" + script + "' '" +
                              (fs::path(output) / "frames.csv").string() + "' '" +
                              (fs::path(output) / "rates.png").string() + "' '" + name + " (" +
                              filter + ", " + prior_kind + ")' > /dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "evaluate_color_estimation: warning: plot failed (%s)\n", cmd.c_str());
    }
    std::printf("evaluate_color_estimation: overall=%.3f", rate(ca, ta));
    for (int k = 0; k < m; ++k)
      std::printf(" %s=%.3f", world::colorClassName(classes[k]).c_str(),
                  rate(correct[k], total[k]));
    if (withheld_k >= 0) std::printf(" unobserved_error=%.1f", unobserved_error);
    std::printf(" background_rejected=%.3f frames=%d\n",
                rate(background_rejected, background_total), used);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_color_estimation: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
