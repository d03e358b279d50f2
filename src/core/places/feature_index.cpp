#include "adaptive_perception/places/feature_index.h"

#include <algorithm>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>

namespace adaptive_perception::places {

void SiftConfig::validate() const {
  if (max_features < 10 || max_features > 5000)
    throw std::invalid_argument("max_features must be in 10..5000");
  if (!(contrast_threshold > 0.0 && contrast_threshold < 1.0))
    throw std::invalid_argument("contrast_threshold must be in (0, 1)");
}

void FeatureIndexConfig::validate() const {
  if (!(ratio > 0.0 && ratio <= 1.0)) throw std::invalid_argument("ratio must be in (0, 1]");
  if (knn < 1 || knn > 100) throw std::invalid_argument("knn must be in 1..100");
  if (candidates < 1) throw std::invalid_argument("candidates must be >= 1");
  if (trees < 1 || trees > 32) throw std::invalid_argument("trees must be in 1..32");
  if (checks < 1) throw std::invalid_argument("checks must be >= 1");
}

cv::Mat extractSift(const cv::Mat& bgr8, const SiftConfig& config) {
  config.validate();
  if (bgr8.type() != CV_8UC3) throw std::invalid_argument("extractSift expects a bgr8 image");
  cv::Mat grey;
  cv::cvtColor(bgr8, grey, cv::COLOR_BGR2GRAY);
  const cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(config.max_features, 3, config.contrast_threshold);
  std::vector<cv::KeyPoint> kp;
  cv::Mat desc;
  sift->detectAndCompute(grey, cv::noArray(), kp, desc);
  if (desc.empty()) return cv::Mat(0, 128, CV_32F);
  return desc;
}

double frameSimilarity(const cv::Mat& query, const cv::Mat& frame, double ratio) {
  if (query.empty() || frame.rows < 2) return 0.0;
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(query, frame, knn, 2);
  int good = 0;
  for (const auto& k : knn)
    if (k.size() == 2 && k[0].distance < ratio * k[1].distance) ++good;
  return static_cast<double>(good) / query.rows;
}

FeatureIndex::FeatureIndex(FeatureIndexConfig config) : config_(config) { config_.validate(); }

int FeatureIndex::addFrame(const cv::Mat& descriptors) {
  if (!descriptors.empty() && (descriptors.cols != 128 || descriptors.type() != CV_32F))
    throw std::invalid_argument("FeatureIndex::addFrame expects N x 128 CV_32F descriptors");
  frames_.push_back(descriptors.empty() ? cv::Mat(0, 128, CV_32F) : descriptors.clone());
  index_.reset();
  built_ = false;
  return numFrames() - 1;
}

void FeatureIndex::build() {
  int rows = 0;
  for (const cv::Mat& f : frames_) rows += f.rows;
  all_.create(rows, 128, CV_32F);
  owner_.assign(rows, -1);
  int r = 0;
  for (size_t i = 0; i < frames_.size(); ++i) {
    if (frames_[i].rows == 0) continue;
    frames_[i].copyTo(all_.rowRange(r, r + frames_[i].rows));
    std::fill(owner_.begin() + r, owner_.begin() + r + frames_[i].rows, static_cast<int>(i));
    r += frames_[i].rows;
  }
  if (rows > 0)
    index_ = std::make_unique<cv::flann::Index>(all_, cv::flann::KDTreeIndexParams(config_.trees));
  built_ = true;
}

std::vector<FrameMatch> FeatureIndex::topFrames(const cv::Mat& query, int n) const {
  if (!built_ && numFrames() > 0) throw std::logic_error("FeatureIndex::topFrames before build()");
  if (query.empty() || all_.empty() || n <= 0) return {};
  const int k = std::min(config_.knn, all_.rows);
  cv::Mat idx, dist;
  index_->knnSearch(query, idx, dist, k, cv::flann::SearchParams(config_.checks));
  // Each test descriptor gives one vote to every frame among its k nearest descriptors.
  std::unordered_map<int, int> votes;
  for (int q = 0; q < idx.rows; ++q) {
    const int* row = idx.ptr<int>(q);
    int seen[100];
    int nseen = 0;
    for (int j = 0; j < k; ++j) {
      if (row[j] < 0) continue;
      const int f = owner_[row[j]];
      if (std::find(seen, seen + nseen, f) != seen + nseen) continue;
      seen[nseen++] = f;
      ++votes[f];
    }
  }
  std::vector<std::pair<int, int>> ranked(votes.begin(), votes.end());
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  if (static_cast<int>(ranked.size()) > config_.candidates) ranked.resize(config_.candidates);
  std::vector<FrameMatch> out;
  for (const auto& [f, v] : ranked)
    out.push_back({f, frameSimilarity(query, frames_[f], config_.ratio)});
  std::sort(out.begin(), out.end(), [](const FrameMatch& a, const FrameMatch& b) {
    return a.similarity != b.similarity ? a.similarity > b.similarity : a.frame < b.frame;
  });
  if (static_cast<int>(out.size()) > n) out.resize(n);
  return out;
}

std::vector<FrameMatch> FeatureIndex::bruteForce(const cv::Mat& query, int n) const {
  std::vector<FrameMatch> out;
  for (int f = 0; f < numFrames(); ++f)
    out.push_back({f, frameSimilarity(query, frames_[f], config_.ratio)});
  std::sort(out.begin(), out.end(), [](const FrameMatch& a, const FrameMatch& b) {
    return a.similarity != b.similarity ? a.similarity > b.similarity : a.frame < b.frame;
  });
  if (static_cast<int>(out.size()) > n) out.resize(std::max(0, n));
  return out;
}

RoomVote voteRooms(const std::vector<FrameMatch>& best, const std::vector<int>& frame_room,
                   int num_rooms, double min_share) {
  RoomVote v;
  v.sums.assign(std::max(0, num_rooms), 0.0);
  double total = 0.0;
  for (const FrameMatch& m : best) {
    if (m.frame < 0 || m.frame >= static_cast<int>(frame_room.size()))
      throw std::invalid_argument("voteRooms: frame " + std::to_string(m.frame) + " has no room");
    const int room = frame_room[m.frame];
    if (room < 0 || room >= num_rooms)
      throw std::invalid_argument("voteRooms: room " + std::to_string(room) + " out of range");
    v.sums[room] += m.similarity;
    total += m.similarity;
  }
  if (total <= 0.0) return v;
  const int lead =
      static_cast<int>(std::max_element(v.sums.begin(), v.sums.end()) - v.sums.begin());
  v.share = v.sums[lead] / total;
  if (v.share > min_share) v.room = lead;
  return v;
}

}  // namespace adaptive_perception::places
