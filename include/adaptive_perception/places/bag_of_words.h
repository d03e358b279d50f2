#pragma once
// Place recognition by a bag of SIFT words (Sivic and Zisserman, "Video Google", ICCV 2003), over
// the SIFT descriptors the appearance localizer extracts (feature_index.h):
//
// 1. Vocabulary: k-means (OpenCV's, k-means++ seeding, a fixed seed) over at most
//    max_training_descriptors descriptors drawn evenly from the reference images.
// 2. Each image becomes the counts of its descriptors' nearest words; the reference images'
//    counts are weighted tf-idf (term frequency times log(N / n_w), n_w the references that hold
//    word w) and normalised to unit length.
// 3. A query's distance to each reference is 1 - the cosine of the two tf-idf vectors, in [0, 1]
//    (0: the same words in the same proportions; 1: no word in common, or an image without
//    features).
//
// The references' vectors sit in one dense N x words matrix, so that a query is one
// matrix-vector product.
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::places {

struct BagOfWordsConfig {
  int words = 500;                       // vocabulary size, 2..100000
  int max_training_descriptors = 50000;  // k-means sample, >= words
  int kmeans_iterations = 10;            // Lloyd iterations, 1..1000
  void validate() const;                 // throws std::invalid_argument naming the bad field
};

class BagOfWords {
 public:
  /// Learns the vocabulary from the reference images' SIFT descriptors (N_i x 128 CV_32F each,
  /// possibly empty) and stores their tf-idf vectors. With fewer descriptors in all than words, the
  /// vocabulary is the descriptors themselves. Throws std::invalid_argument on a bad config, a
  /// matrix of another type or width, or no descriptor at all.
  BagOfWords(const std::vector<cv::Mat>& reference_features, BagOfWordsConfig config = {});

  int size() const { return vectors_.rows; }  // references
  int words() const { return vocabulary_.rows; }
  const cv::Mat& vocabulary() const { return vocabulary_; }  // words x 128 CV_32F

  /// The word of each descriptor (the nearest centre, L2).
  std::vector<int> assign(const cv::Mat& features) const;
  /// 1 - cosine of the query's tf-idf vector with every reference's (size() floats).
  std::vector<float> distances(const cv::Mat& query_features) const;

 private:
  // The tf-idf vector of an image's words: 1 x words CV_32F, unit length (all 0 without words).
  cv::Mat vectorOf(const std::vector<int>& words) const;

  BagOfWordsConfig config_;
  cv::Mat vocabulary_;
  std::vector<float> idf_;
  cv::Mat vectors_;  // size() x words CV_32F
};

}  // namespace adaptive_perception::places
