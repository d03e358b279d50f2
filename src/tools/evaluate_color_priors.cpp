// evaluate_color_priors: the paper's Table 1 question on real images: at a venue the priors never
// saw, how well is each colour classified when the priors were learnt jointly (eq. 10, the colours'
// means correlated across venues) versus independently (the same prior, cross-colour blocks zero)?
//
//   evaluate_color_priors --images DIR --masks DIR [--output DIR]
//   evaluate_color_priors --help   (every option with its default, unit and range)
//
// Each image with its mask (io/label_mask.h: 2 field line, 3 field) gives the mean YUV of its
// field pixels (green) and of its line pixels (white); images whose names differ only in a
// trailing frame number are one venue (venueOf below). Leave one venue out: a prior over the two
// colours' means is learnt from the other venues (color/prior_learning.h, learnPrior; each venue
// one data set of its images); at each image of the venue left out the robot sees its carpet
// without a pose (the pixels the pose-free segmentation, color/field_segmentation.h, calls
// carpet, not the mask's) and updates the prior's filter with that colour alone (eqs. 3-5); the
// line paint it did not observe is then what the prior predicts from the carpet: jointly, the
// carpet's offset from the venues' mean moves the paint's mean by their learnt covariance;
// independently, the paint stays at the prior mean. Scores per image: the predicted paint mean's
// distance to the mask's line pixels' mean (YUV levels), and each colour's recall over its mask
// pixels (the share the posterior's classifier, eq. 9 with the unknown threshold, gives that
// colour), with the line's precision among the field and line pixels. Rows: the prior alone (no
// observation), the independent prior after the carpet, the joint prior after the carpet, and
// both colours observed from the mask (the bound). Prints one CSV line per image and row, writes
// it to OUTPUT/images.csv, and ends with one line per row:
//   evaluate_color_priors: prior=joint images=.. venues=.. white_mean_error=.. green_recall=..
//       white_recall=.. white_precision=..
#include <Eigen/Core>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <opencv2/imgcodecs.hpp>

#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/color/prior_learning.h"
#include "adaptive_perception/io/label_mask.h"
#include "adaptive_perception/world/color_class.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

namespace {

constexpr int kMaskLine = 2, kMaskField = 3;

// The venue of an image: its name without the extension, a trailing "_copy" and the trailing frame
// number (digits, '_' and '-'), so that frames of one recording share it ("opx_frame005575" and
// "opx_frame005620" -> "opx_frame"); a name that is all number is its own venue.
std::string venueOf(const std::string& file_name) {
  std::string v = fs::path(file_name).stem().string();
  if (v.size() > 5 && v.compare(v.size() - 5, 5, "_copy") == 0) v.resize(v.size() - 5);
  std::size_t end = v.size();
  while (end > 0 && (std::isdigit(static_cast<unsigned char>(v[end - 1])) || v[end - 1] == '_' ||
                     v[end - 1] == '-'))
    --end;
  return end > 0 ? v.substr(0, end) : fs::path(file_name).stem().string();
}

struct Venue {
  std::string name, venue;
  cv::Mat yuv, labels;             // labels: the mask's field and line as world::kGreen / kWhite
  color::ColorObservation truth;   // both colours from the mask
  color::ColorObservation carpet;  // green alone, from the pose-free segmentation
};

struct Scores {
  double white_mean_error = 0.0, green_recall = 0.0, white_recall = 0.0, white_precision = 0.0;
};

Scores score(const color::ColorFilter& filter, const Venue& v, const color::ColorModelConfig& m) {
  Scores s;
  const int white = m.colorIndex(world::kWhite);
  s.white_mean_error = (filter.colorMean(white) - v.truth.means[white]).norm();
  color::ColorLut lut;
  lut.build(filter.classifier());
  cv::Mat got;
  lut.classifyYuv(v.yuv, &got);
  const cv::Mat is_field = v.labels == world::kGreen, is_line = v.labels == world::kWhite;
  const cv::Mat said_white = (got == world::kWhite) & (is_field | is_line);
  s.green_recall = static_cast<double>(cv::countNonZero((got == world::kGreen) & is_field)) /
                   std::max(1, cv::countNonZero(is_field));
  s.white_recall = static_cast<double>(cv::countNonZero(said_white & is_line)) /
                   std::max(1, cv::countNonZero(is_line));
  s.white_precision = static_cast<double>(cv::countNonZero(said_white & is_line)) /
                      std::max(1, cv::countNonZero(said_white));
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_color_priors",
                         "Colour priors learnt jointly versus independently, at a venue left out "
                         "(images with their masks; names that differ only in a trailing frame "
                         "number are one venue): the line paint's colour predicted from the "
                         "carpet, and each colour's classification.");
  std::string images_dir, masks_dir;
  cli.option("images", &images_dir, "folder of camera images")->required();
  cli.option("masks", &masks_dir,
             "folder of masks of the same names (2 line, 3 field; the rest is not scored)")
      ->required();
  const std::string& output = cli.resultsFolder("images.csv");
  cli.parse(argc, argv);
  try {
    color::ColorModelConfig model;
    model.classes = {world::kGreen, world::kWhite};  // the colours the masks give
    const int green = model.colorIndex(world::kGreen);
    const int white = model.colorIndex(world::kWhite);
    std::vector<Venue> venues;
    for (const io::MaskedImage& p : io::pairImagesWithMasks(images_dir, masks_dir)) {
      const cv::Mat bgr = cv::imread(p.image_path, cv::IMREAD_COLOR);
      if (bgr.empty()) throw std::runtime_error(p.image_path + ": cannot read the image");
      const cv::Mat mask = io::readLabelMask(p.mask_path, bgr.size());
      Venue v;
      v.name = fs::path(p.image_path).filename().string();
      v.venue = venueOf(v.name);
      v.yuv = color::bgrToYuv(bgr);
      v.labels = cv::Mat(mask.size(), CV_8UC1, cv::Scalar(world::kBackground));
      v.labels.setTo(world::kGreen, mask == kMaskField);
      v.labels.setTo(world::kWhite, mask == kMaskLine);
      v.truth = color::computeColorObservation(v.yuv, v.labels, model);
      if (v.truth.counts[green] < model.min_pixels_per_color ||
          v.truth.counts[white] < model.min_pixels_per_color)
        throw std::runtime_error(p.mask_path + ": fewer than " +
                                 std::to_string(model.min_pixels_per_color) +
                                 " field or line pixels");
      const color::FieldSegmentation seg =
          color::segmentFieldYuv(v.yuv, color::FieldSegmentationConfig());
      v.carpet = color::computeColorObservation(v.yuv, seg.labels, model);
      v.carpet.counts[white] = 0;  // the paint is what the prior has to predict
      venues.push_back(std::move(v));
    }
    std::set<std::string> names;
    for (const Venue& v : venues) names.insert(v.venue);
    if (names.size() < 3)
      throw std::runtime_error(images_dir + ": " + std::to_string(names.size()) +
                               " venues; leaving one out needs at least 3");
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "images.csv");
    const std::string header =
        "image,prior,white_mean_error,green_recall,white_recall,white_precision";
    csv << header << "\n";
    std::cout << header << "\n";
    const char* rows[] = {"prior_alone", "independent", "joint", "both_observed"};
    std::vector<Scores> sums(4);
    for (std::size_t i = 0; i < venues.size(); ++i) {
      // The other venues, each one data set of its images (the hierarchical model's environments).
      std::map<std::string, color::LightingDataSet> by_venue;
      for (const Venue& v : venues)
        if (v.venue != venues[i].venue) {
          by_venue[v.venue].name = v.venue;
          by_venue[v.venue].frames.push_back(v.truth);
        }
      std::vector<color::LightingDataSet> others;
      for (auto& [name, set] : by_venue) others.push_back(std::move(set));
      const color::LightingPrior joint =
          color::learnPrior(others, model, color::PriorLearningConfig(), "joint");
      color::ColorFilter filters[4] = {
          color::ColorFilter(joint, model), color::ColorFilter(joint.independent(), model),
          color::ColorFilter(joint, model), color::ColorFilter(joint, model)};
      filters[1].update(venues[i].carpet);
      filters[2].update(venues[i].carpet);
      filters[3].update(venues[i].truth);
      for (int r = 0; r < 4; ++r) {
        const Scores s = score(filters[r], venues[i], model);
        sums[r].white_mean_error += s.white_mean_error;
        sums[r].green_recall += s.green_recall;
        sums[r].white_recall += s.white_recall;
        sums[r].white_precision += s.white_precision;
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%.2f,%.4f,%.4f,%.4f", venues[i].name.c_str(),
                      rows[r], s.white_mean_error, s.green_recall, s.white_recall,
                      s.white_precision);
        std::cout << line << "\n";
        csv << line << "\n";
      }
    }
    const double n = static_cast<double>(venues.size());
    for (int r = 0; r < 4; ++r)
      std::printf(
          "evaluate_color_priors: prior=%s images=%zu venues=%zu white_mean_error=%.2f "
          "green_recall=%.3f white_recall=%.3f white_precision=%.3f\n",
          rows[r], venues.size(), names.size(), sums[r].white_mean_error / n,
          sums[r].green_recall / n, sums[r].white_recall / n, sums[r].white_precision / n);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_color_priors: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
