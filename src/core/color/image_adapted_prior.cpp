#include "adaptive_perception/color/image_adapted_prior.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

namespace {

// The innovation's squared Mahalanobis distance under the prior widened by `widening`; *dim its
// dimension (0: nothing observed).
double innovationMahalanobis2(const LightingPrior& prior, const ColorObservation& obs,
                              const ColorModelConfig& model, double widening, int* dim) {
  const ColorFilter probe(prior, model);
  std::vector<int> idx;
  Eigen::VectorXd z;
  Eigen::MatrixXd noise;
  probe.observationOf(obs, &idx, &z, &noise);
  *dim = static_cast<int>(idx.size());
  if (idx.empty()) return 0.0;
  const int k = *dim;
  Eigen::VectorXd y(k);
  Eigen::MatrixXd s(k, k);
  for (int i = 0; i < k; ++i) {
    y[i] = z[i] - prior.mean[idx[i]];
    for (int j = 0; j < k; ++j) s(i, j) = widening * prior.cov(idx[i], idx[j]) + noise(i, j);
  }
  return y.dot(s.ldlt().solve(y));
}

}  // namespace

double priorWidening(const LightingPrior& prior, const ColorObservation& obs,
                     const ColorModelConfig& model) {
  int dim = 0;
  if (innovationMahalanobis2(prior, obs, model, 1.0, &dim) <= dim) return 1.0;
  // d2 falls as the prior widens: bisection on log(widening) between 1 and kMaxWidening.
  constexpr double kMaxWidening = 1e6;
  if (innovationMahalanobis2(prior, obs, model, kMaxWidening, &dim) > dim) return kMaxWidening;
  double lo = 0.0, hi = std::log(kMaxWidening);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (innovationMahalanobis2(prior, obs, model, std::exp(mid), &dim) > dim ? lo : hi) = mid;
  }
  return std::exp(hi);
}

std::vector<LightingPrior> adaptPriorsToImage(const std::vector<LightingPrior>& priors,
                                              const cv::Mat& yuv,
                                              const FieldSegmentation& segmentation,
                                              const ColorModelConfig& model) {
  if (yuv.type() != CV_8UC3 || segmentation.labels.size() != yuv.size())
    throw std::invalid_argument(
        "adaptPriorsToImage: the image (CV_8UC3) and its segmentation differ in size or type");
  // Only the carpet and the paint: the segmentation's background is not a modelled colour.
  cv::Mat labels(segmentation.labels.size(), CV_8UC1, cv::Scalar(world::kBackground));
  labels.setTo(world::kGreen, segmentation.labels == world::kGreen);
  labels.setTo(world::kWhite, segmentation.labels == world::kWhite);
  const ColorObservation obs = computeColorObservation(yuv, labels, model);
  const int green = model.colorIndex(world::kGreen);
  std::vector<LightingPrior> out;
  out.reserve(priors.size());
  for (const LightingPrior& prior : priors) {
    prior.validate(model);
    const double widening = priorWidening(prior, obs, model);
    LightingPrior widened = prior;
    widened.cov *= widening;
    ColorFilter filter(widened, model);
    filter.update(obs);
    LightingPrior adapted = prior;
    adapted.mean = filter.mean();
    adapted.cov = 0.5 * (filter.cov() + filter.cov().transpose());
    if (green >= 0 && obs.counts[green] >= model.min_pixels_per_color)
      adapted.pixel_noise_var = prior.pixel_noise_var.cwiseMax(obs.variances[green]);
    out.push_back(adapted);
  }
  return out;
}

}  // namespace adaptive_perception::color
