// evaluate_field_segmentation: pose-free field segmentation (color/field_segmentation.h) of every
// image of a folder, scored against its mask, beside a simple per-image baseline on the same
// images.
//
//   evaluate_field_segmentation --images DIR --masks DIR [--output DIR]
//   evaluate_field_segmentation --help   (every option with its default, unit and range)
//
// Masks (io/label_mask.h): the file of the same stem in --masks; 0 background, 2 field line,
// 3 field (the carpet inside the boundary and whatever stands on it); other values count as
// neither. A mask of another size is scaled to its image by nearest neighbour (aspect ratios within
// 10%). Scores: per image the intersection over union of the field (label 3) and of the lines
// (label 2); an image whose mask and prediction both lack a class scores 1 for it.
// Baseline (the same tool, the same images): field = excess green 2G-R-B above its Otsu threshold;
// lines = pixels inside the convex hull of that field brighter (HSV value) and paler (saturation)
// than the field's medians.
// Prints one CSV line per image (image, field_iou, line_iou, line_precision, line_recall,
// baseline_field_iou, baseline_line_iou, ms)
// and writes it to OUTPUT/images.csv with OUTPUT/NAME.png (image | segmentation | mask). Last line:
//   evaluate_field_segmentation: images=.. field_iou=.. line_iou=.. baseline_field_iou=..
//   baseline_line_iou=.. masks_scaled=.. ms_per_image=..
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/io/label_mask.h"
#include "adaptive_perception/world/color_class.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kMaskLine = 2, kMaskField = 3;

double iou(const cv::Mat& predicted, const cv::Mat& truth) {
  const double inter = cv::countNonZero(predicted & truth);
  const double uni = cv::countNonZero(predicted | truth);
  return uni > 0 ? inter / uni : 1.0;
}

// The README's per-image baseline: excess green by Otsu; lines brighter and paler than the field.
void baseline(const cv::Mat& bgr, cv::Mat* field, cv::Mat* line) {
  cv::Mat ch[3], exg;
  cv::split(bgr, ch);
  cv::Mat b, g, r;
  ch[0].convertTo(b, CV_32F), ch[1].convertTo(g, CV_32F), ch[2].convertTo(r, CV_32F);
  cv::Mat e = 2 * g - r - b;
  e.convertTo(exg, CV_8U);  // saturates: negative excess green is 0
  cv::threshold(exg, *field, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  *line = cv::Mat::zeros(bgr.size(), CV_8U);
  std::vector<cv::Point> pts;
  cv::findNonZero(*field, pts);
  if (pts.size() < 3) return;
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  std::vector<int> s, v;
  for (const cv::Point& p : pts) {
    const cv::Vec3b& h = hsv.at<cv::Vec3b>(p);
    s.push_back(h[1]), v.push_back(h[2]);
  }
  std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  const int s_med = s[s.size() / 2], v_med = v[v.size() / 2];
  std::vector<cv::Point> hull;
  cv::convexHull(pts, hull);
  cv::Mat inside = cv::Mat::zeros(bgr.size(), CV_8U);
  cv::fillConvexPoly(inside, hull, 255);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b& h = hsv.at<cv::Vec3b>(y, x);
      if (inside.at<std::uint8_t>(y, x) && h[2] > v_med && h[1] < s_med)
        line->at<std::uint8_t>(y, x) = 255;
    }
}

}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_field_segmentation",
                         "Pose-free field segmentation of every image of a folder, scored "
                         "against its mask (field and line IoU), beside a per-image excess-green "
                         "baseline on the same images.");
  std::string images_dir, masks_dir;
  cli.option("images", &images_dir, "folder of camera images")->required();
  cli.option("masks", &masks_dir,
             "folder of masks of the same names (0 background, 2 line, 3 field)")
      ->required();
  color::FieldSegmentationConfig cfg;
  cli.fields(color::FieldSegmentationConfig::fields(), &cfg);
  const std::string& output = cli.resultsFolder("images.csv and one drawing per image");
  cli.parse(argc, argv);
  try {
    const std::vector<io::MaskedImage> pairs = io::pairImagesWithMasks(images_dir, masks_dir);
    fs::create_directories(output);
    std::ofstream csv(output + "/images.csv");
    const std::string header = "image,field_iou,line_iou,line_precision,line_recall,baseline_field_iou,baseline_line_iou,ms";
    csv << header << "\n";
    std::cout << header << "\n";
    double sum[4] = {0, 0, 0, 0}, ms_total = 0.0;
    int scaled_count = 0;
    for (const io::MaskedImage& p : pairs) {
      const cv::Mat bgr = cv::imread(p.image_path, cv::IMREAD_COLOR);
      if (bgr.empty()) throw std::runtime_error(p.image_path + ": cannot read the image");
      bool scaled = false;
      const cv::Mat mask = io::readLabelMask(p.mask_path, bgr.size(), &scaled);
      if (scaled) {
        ++scaled_count;
        std::cerr << p.mask_path << ": scaled to its image's " << bgr.cols << " x " << bgr.rows
                  << " by nearest neighbour\n";
      }
      const auto t0 = Clock::now();
      const color::FieldSegmentation seg = color::segmentField(bgr, cfg);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      ms_total += ms;
      cv::Mat base_field, base_line;
      baseline(bgr, &base_field, &base_line);
      const cv::Mat true_field = mask == kMaskField, true_line = mask == kMaskLine;
      const cv::Mat our_line = seg.labels == world::kWhite;
      const double s[4] = {iou(seg.labels == world::kGreen, true_field), iou(our_line, true_line),
                           iou(base_field, true_field), iou(base_line, true_line)};
      for (int i = 0; i < 4; ++i) sum[i] += s[i];
      const double hit = cv::countNonZero(our_line & true_line);
      const double precision = hit / std::max(1, cv::countNonZero(our_line)),
                   recall = hit / std::max(1, cv::countNonZero(true_line));
      char line[512];
      std::snprintf(line, sizeof line, "%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.1f",
                    fs::path(p.image_path).filename().c_str(), s[0], s[1], precision, recall, s[2],
                    s[3], ms);
      std::cout << line << std::endl;
      csv << line << "\n";
      // image | segmentation | mask, in the classes' display colours.
      cv::Mat truth(mask.size(), CV_8U, cv::Scalar(world::kBackground));
      truth.setTo(world::kGreen, true_field);
      truth.setTo(world::kWhite, true_line);
      cv::Mat row;
      cv::hconcat(std::vector<cv::Mat>{bgr, color::colorizeLabels(seg.labels),
                                       color::colorizeLabels(truth)},
                  row);
      cv::imwrite(output + "/" + fs::path(p.image_path).stem().string() + ".png", row);
    }
    const double n = static_cast<double>(pairs.size());
    std::printf(
        "evaluate_field_segmentation: images=%zu field_iou=%.3f line_iou=%.3f "
        "baseline_field_iou=%.3f baseline_line_iou=%.3f masks_scaled=%d ms_per_image=%.1f\n",
        pairs.size(), sum[0] / n, sum[1] / n, sum[2] / n, sum[3] / n, scaled_count, ms_total / n);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_field_segmentation: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
