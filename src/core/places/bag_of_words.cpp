#include "adaptive_perception/places/bag_of_words.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/opencv_seed.h"

namespace adaptive_perception::places {
namespace {

void checkFeatures(const cv::Mat& f, const char* what) {
  if (f.empty()) return;
  if (f.type() != CV_32F || f.cols != 128)
    throw std::invalid_argument(std::string(what) +
                                ": SIFT descriptors must be N x 128 CV_32F, got " +
                                std::to_string(f.rows) + " x " + std::to_string(f.cols) +
                                " of type " + std::to_string(f.type()));
}

// k-means with OpenCV's generator seeded, and the caller's generator state left as it was.
cv::Mat kmeansCentres(const cv::Mat& sample, int k, int iterations) {
  const math::ScopedOpenCvSeed seed(0x5eed5eedULL);
  cv::Mat labels, centres;
  cv::kmeans(sample, k, labels, cv::TermCriteria(cv::TermCriteria::MAX_ITER, iterations, 0.0), 1,
             cv::KMEANS_PP_CENTERS, centres);
  return centres;
}

}  // namespace

void BagOfWordsConfig::validate() const {
  if (words < 2 || words > 100000)
    throw std::invalid_argument("words must be in 2..100000, got " + std::to_string(words));
  if (max_training_descriptors < words)
    throw std::invalid_argument("max_training_descriptors must be >= words (" +
                                std::to_string(words) + "), got " +
                                std::to_string(max_training_descriptors));
  if (kmeans_iterations < 1 || kmeans_iterations > 1000)
    throw std::invalid_argument("kmeans_iterations must be in 1..1000, got " +
                                std::to_string(kmeans_iterations));
}

BagOfWords::BagOfWords(const std::vector<cv::Mat>& reference_features, BagOfWordsConfig config)
    : config_(config) {
  config_.validate();
  long total = 0;
  for (const cv::Mat& f : reference_features) {
    checkFeatures(f, "BagOfWords");
    total += f.rows;
  }
  if (total == 0)
    throw std::invalid_argument("BagOfWords: the reference images have no SIFT feature");
  // An even draw of at most max_training_descriptors rows: every stride-th descriptor.
  const long stride = std::max(
      1L, (total + config_.max_training_descriptors - 1) / config_.max_training_descriptors);
  cv::Mat sample(0, 128, CV_32F);
  long n = 0;
  for (const cv::Mat& f : reference_features)
    for (int r = 0; r < f.rows; ++r, ++n)
      if (n % stride == 0) sample.push_back(f.row(r));
  vocabulary_ = sample.rows <= config_.words
                    ? sample.clone()
                    : kmeansCentres(sample, config_.words, config_.kmeans_iterations);
  // Document frequencies, then each reference's tf-idf vector.
  const int w = vocabulary_.rows;
  std::vector<int> holders(w, 0);
  std::vector<std::vector<int>> assigned;
  assigned.reserve(reference_features.size());
  for (const cv::Mat& f : reference_features) {
    assigned.push_back(assign(f));
    std::vector<char> seen(w, 0);
    for (int word : assigned.back()) seen[word] = 1;
    for (int i = 0; i < w; ++i) holders[i] += seen[i];
  }
  const double refs = static_cast<double>(reference_features.size());
  idf_.assign(w, 0.0f);
  for (int i = 0; i < w; ++i)
    if (holders[i] > 0) idf_[i] = static_cast<float>(std::log(refs / holders[i]));
  vectors_.create(static_cast<int>(reference_features.size()), w, CV_32F);
  for (size_t r = 0; r < assigned.size(); ++r) vectorOf(assigned[r]).copyTo(vectors_.row(r));
}

std::vector<int> BagOfWords::assign(const cv::Mat& features) const {
  checkFeatures(features, "BagOfWords::assign");
  std::vector<int> out;
  if (features.empty()) return out;
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_L2).match(features, vocabulary_, matches);
  out.reserve(matches.size());
  for (const cv::DMatch& m : matches) out.push_back(m.trainIdx);
  return out;
}

cv::Mat BagOfWords::vectorOf(const std::vector<int>& words) const {
  cv::Mat v = cv::Mat::zeros(1, this->words(), CV_32F);
  float* p = v.ptr<float>();
  for (int word : words) p[word] += idf_[word];  // count times idf
  const double norm = cv::norm(v);
  if (norm > 0.0) v /= norm;
  return v;
}

std::vector<float> BagOfWords::distances(const cv::Mat& query_features) const {
  const cv::Mat q = vectorOf(assign(query_features));
  cv::Mat sims;
  cv::gemm(vectors_, q, 1.0, cv::noArray(), 0.0, sims, cv::GEMM_2_T);  // size() x 1
  std::vector<float> out(size());
  for (int r = 0; r < size(); ++r) out[r] = std::clamp(1.0f - sims.at<float>(r), 0.0f, 1.0f);
  return out;
}

}  // namespace adaptive_perception::places
