// BoxCondensationTracker's colour model (box_condensation_tracker.h, steps 2 and 4): the image
// binned into colour histograms, the target's and its surroundings', the per-bin object likelihood
// P(O | c), and the distractors whose colours count against the target's.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "box_regions.h"

namespace adaptive_perception::tracking {

using namespace box_regions;

void BoxCondensationTracker::binImage(const cv::Mat& image, const cv::Rect& region,
                                      cv::Mat* bins) const {
  int shift = 0;
  while ((256 >> shift) > config_.bins_per_channel) ++shift;
  const int b = config_.bins_per_channel;
  bins->create(region.height, region.width, CV_16U);
  for (int y = 0; y < region.height; ++y) {
    std::uint16_t* out = bins->ptr<std::uint16_t>(y);
    if (image.channels() == 1) {
      const std::uint8_t* in = image.ptr<std::uint8_t>(region.y + y) + region.x;
      for (int x = 0; x < region.width; ++x) {
        if (config_.chroma) {  // as a colour pixel (v, v, v)
          const int s = 3 * in[x], c = in[x] * b / (s + 1);
          out[x] = static_cast<std::uint16_t>((c * b + c) * 4 + s * 4 / 766);
        } else {
          const int v = in[x] >> shift;
          out[x] = static_cast<std::uint16_t>((v * b + v) * b + v);
        }
      }
    } else if (config_.chroma) {
      // Normalised chromaticity (r, g) on b x b bins and 4 brightness levels.
      const cv::Vec3b* in = image.ptr<cv::Vec3b>(region.y + y) + region.x;
      for (int x = 0; x < region.width; ++x) {
        const int s = in[x][0] + in[x][1] + in[x][2];
        const int r = in[x][2] * b / (s + 1), g = in[x][1] * b / (s + 1);
        out[x] = static_cast<std::uint16_t>((r * b + g) * 4 + s * 4 / 766);
      }
    } else {
      const cv::Vec3b* in = image.ptr<cv::Vec3b>(region.y + y) + region.x;
      for (int x = 0; x < region.width; ++x)
        out[x] = static_cast<std::uint16_t>(((in[x][0] >> shift) * b + (in[x][1] >> shift)) * b +
                                            (in[x][2] >> shift));
    }
  }
}

void BoxCondensationTracker::histograms(const cv::Mat& image, const cv::Rect2d& box,
                                        std::vector<float>* object,
                                        std::vector<float>* surround) const {
  const cv::Rect bounds(0, 0, image.cols, image.rows);
  const cv::Rect outer = covering(grown(box, config_.surround_scale), bounds);
  const cv::Rect inner = covering(box, bounds);
  const int n = config_.bins_per_channel * config_.bins_per_channel *
                (config_.chroma ? 4 : config_.bins_per_channel);
  object->assign(n, 0.0f);
  surround->assign(n, 0.0f);
  if (outer.empty()) return;
  cv::Mat bins;
  binImage(image, outer, &bins);
  for (int y = 0; y < outer.height; ++y) {
    const std::uint16_t* row = bins.ptr<std::uint16_t>(y);
    for (int x = 0; x < outer.width; ++x) {
      const bool in = inner.contains(cv::Point(outer.x + x, outer.y + y));
      ((in ? *object : *surround)[row[x]]) += 1.0f;
    }
  }
  normalize(object);
  normalize(surround);
}

std::vector<float> BoxCondensationTracker::objectLikelihood() const {
  const int nb = static_cast<int>(h_object_.size());
  std::vector<float> lut(nb);
  for (int b = 0; b < nb; ++b) {
    const float o = h_object_[b], s = h_surround_[b];
    lut[b] = o + s > 0.0f ? o / (o + s) : 0.5f;  // a colour seen in neither: no evidence
    if (!h_distractor_.empty()) {
      const float d = h_distractor_[b];
      lut[b] = 0.5f * (lut[b] + (o + d > 0.0f ? o / (o + d) : 0.5f));
    }
  }
  return lut;
}

void BoxCondensationTracker::learnDistractors(const cv::Mat& image, const cv::Rect2d& box,
                                              const std::vector<float>& lut) {
  out_distractors_.clear();
  const cv::Rect bounds(0, 0, image.cols, image.rows);
  const cv::Rect region =
      covering(grown(box, config_.distractor_scale + config_.ring_scale - 1.0), bounds);
  if (region.width < 2 || region.height < 2) return;
  cv::Mat bins;
  binImage(image, region, &bins);
  cv::Mat sat;
  cv::integral(lookUp(bins, lut), sat, CV_64F);
  // A box's mean P(O | c) inside it (no ring: a look-alike beside the target has the target in
  // its ring).
  const cv::Rect local(0, 0, region.width, region.height);
  auto inside = [&](const cv::Rect2d& b) {
    const cv::Rect in = covering(cv::Rect2d(b.x - region.x, b.y - region.y, b.width, b.height),
                                 local);
    return in.area() > 0 ? areaSum(sat, in.x, in.y, in.x + in.width, in.y + in.height) / in.area()
                         : 0.0;
  };
  const double own = inside(box);
  // Boxes of the estimate's size on a grid of half its sides within distractor_scale of it, at
  // least a side away from it, their mean at least distractor_ratio of its; the best first, each at
  // least a side from those taken, at most kMaxDistractors.
  constexpr int kMaxDistractors = 3;
  std::vector<std::pair<double, cv::Rect2d>> found;
  if (own > 0.0) {
    const double reach_x = 0.5 * (config_.distractor_scale - 1.0) * box.width;
    const double reach_y = 0.5 * (config_.distractor_scale - 1.0) * box.height;
    for (double dy = -reach_y; dy <= reach_y + 1e-9; dy += 0.5 * box.height)
      for (double dx = -reach_x; dx <= reach_x + 1e-9; dx += 0.5 * box.width) {
        if (std::fabs(dx) < box.width && std::fabs(dy) < box.height) continue;
        const cv::Rect2d b(box.x + dx, box.y + dy, box.width, box.height);
        if ((b & cv::Rect2d(region)).area() < 0.5 * b.area()) continue;
        const double sc = inside(b);
        if (sc >= config_.distractor_ratio * own) found.emplace_back(sc, b);
      }
  }
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<float> d(h_object_.size(), 0.0f);
  for (const auto& [sc, b] : found) {
    if (static_cast<int>(out_distractors_.size()) >= kMaxDistractors) break;
    bool apart = true;
    for (const cv::Rect2d& t : out_distractors_)
      apart = apart && (std::fabs(t.x - b.x) >= b.width || std::fabs(t.y - b.y) >= b.height);
    if (!apart) continue;
    out_distractors_.push_back(b);
    const cv::Rect in = covering(b, region) - region.tl();
    for (int y = in.y; y < in.y + in.height; ++y) {
      const std::uint16_t* row = bins.ptr<std::uint16_t>(y);
      for (int x = in.x; x < in.x + in.width; ++x) d[row[x]] += 1.0f;
    }
  }
  const float a = static_cast<float>(config_.learning_rate);
  if (out_distractors_.empty()) {
    for (float& v : h_distractor_) v *= 1.0f - a;  // fades while none is seen
    return;
  }
  normalize(&d);
  if (h_distractor_.empty()) {
    h_distractor_ = d;
    return;
  }
  for (std::size_t k = 0; k < d.size(); ++k)
    h_distractor_[k] = (1.0f - a) * h_distractor_[k] + a * d[k];
}

}  // namespace adaptive_perception::tracking
