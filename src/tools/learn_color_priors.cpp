// learn_color_priors: learns K lighting priors (eq. 10) from bags recorded in earlier environments.
//
//   learn_color_priors --help   (every option with its default, unit and range)
//
// Each bag in DIR is one data set (one environment under one lighting). Pixel labels come from the
// bag's camera/labels (the simulator's true labels, standing in for the paper's hand-labelled
// images) or, when absent, from the field map rendered at the bag's ground-truth camera pose. The
// data sets are clustered into K groups by k-means on their per-colour mean luminance (cluster 0 =
// darkest), and one prior is learnt per group, plus one from all data sets (`--all_name`, for the
// single-filter baseline). Last line: `learn_color_priors: datasets=N k=K sizes=a,b frames=F`.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/color/prior_learning.h"
#include "adaptive_perception/ros/bag_frames.h"
#include "adaptive_perception/world/label_renderer.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("learn_color_priors",
                         "Learns K lighting priors (eq. 10) from bags recorded in earlier "
                         "environments.");
  std::string bag_dir;
  cli.option("bag_dir", &bag_dir, "folder of the training bags")->required();
  int k = 2;
  cli.option("k", &k, config::closed(1, 100), "lighting modes K");
  std::string out_dir = "config/color_priors";
  cli.option("output_dir", &out_dir, "folder of the priors written (<name>.yaml)");
  std::string names_arg;
  cli.option("names", &names_arg,
             "the modes' names, comma-separated (empty: dark,bright for K = 2, else mode_N)");
  const std::uint64_t& seed = cli.seed();
  std::string all_name = "all";
  cli.option("all_name", &all_name, "name of the one prior learned from every bag");
  cli.overwrite("a prior");
  cli.parse(argc, argv);
  if (names_arg.empty() && k == 2) names_arg = "dark,bright";
  std::vector<std::string> names;
  for (std::stringstream ss(names_arg); std::getline(ss, names_arg, ',');)
    names.push_back(names_arg);
  while (static_cast<int>(names.size()) < k)
    names.push_back("mode_" + std::to_string(names.size()));
  if (static_cast<int>(names.size()) != k) cli.fail("--names needs exactly K names");

  try {
    std::vector<std::string> bags;
    for (const auto& e : fs::directory_iterator(bag_dir))
      if (e.path().extension() == ".bag") bags.push_back(e.path().string());
    std::sort(bags.begin(), bags.end());
    if (static_cast<int>(bags.size()) < k)
      throw std::runtime_error(bag_dir + ": " + std::to_string(bags.size()) +
                               " bags for k = " + std::to_string(k));

    const color::ColorModelConfig model;
    const world::FieldMap map;
    std::vector<color::LightingDataSet> sets;
    long frames = 0;
    for (const auto& b : bags) {
      ros_bag::BagFrameReader reader(b);
      color::LightingDataSet set;
      set.name = fs::path(b).stem().string();
      std::unique_ptr<world::LabelRenderer> renderer;
      for (const auto& f : reader.readAll()) {
        cv::Mat labels = f.true_labels;
        if (labels.empty()) {
          if (!f.has_pose) continue;
          if (!renderer) renderer = std::make_unique<world::LabelRenderer>(map, f.camera);
          labels.create(f.yuv.size(), CV_8UC1);
          renderer->renderImage(f.map_to_optical, labels.ptr<std::uint8_t>(0));
        }
        set.frames.push_back(color::computeColorObservation(f.yuv, labels, model));
      }
      frames += static_cast<long>(set.frames.size());
      std::printf("  %-32s %zu frames\n", set.name.c_str(), set.frames.size());
      sets.push_back(std::move(set));
    }
    const Eigen::MatrixXd features = color::lumaFeatures(sets, model);
    const std::vector<int> cluster = color::kMeans(features, k, seed);
    fs::create_directories(out_dir);
    const color::PriorLearningConfig lc;
    auto write = [&](const color::LightingPrior& p) {
      const std::string path = (fs::path(out_dir) / (p.name + ".yaml")).string();
      cli.refuseExisting(path);
      p.saveYaml(path);
      std::printf("  wrote %s (green Y %.1f +- %.1f, white Y %.1f +- %.1f)\n", path.c_str(),
                  p.mean[0], std::sqrt(p.cov(0, 0)), p.mean[3], std::sqrt(p.cov(3, 3)));
    };
    std::ostringstream sizes;
    for (int c = 0; c < k; ++c) {
      std::vector<color::LightingDataSet> group;
      for (size_t j = 0; j < sets.size(); ++j)
        if (cluster[j] == c) group.push_back(sets[j]);
      sizes << (c ? "," : "") << group.size();
      write(color::learnPrior(group, model, lc, names[c]));
    }
    if (!all_name.empty()) write(color::learnPrior(sets, model, lc, all_name));
    std::printf("learn_color_priors: datasets=%zu k=%d sizes=%s frames=%ld\n", sets.size(), k,
                sizes.str().c_str(), frames);
  } catch (const std::exception& e) {
    std::cerr << "learn_color_priors: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
