#pragma once
// Lighting priors adapted to one image without a camera pose: how a robot at a venue its priors
// never saw starts its colour model before it has localized (the localizer's global start, the
// colour estimator's pose-free mode).
//
// The pose-free segmentation (field_segmentation.h) labels the image's carpet and line paint; each
// prior is updated with those two colours' means (eqs. 3-5, the colour filter's own update), and
// the prior's joint covariance carries the change to the colours the segmentation does not label
// (a landmark's bands, the goals): under a joint prior, a carpet that came out darker and redder
// than the priors expected moves the other colours the way the venues the priors were learnt from
// moved them together (the paper's eq. 10 and Table 1).
//
// A venue the priors never saw can lie far outside them (the simulated venues' carpets are 20
// levels bluer than a real one, 5 prior standard deviations): an update would then stop part way,
// and the model would call the real carpet and paint outliers. So the prior's covariance is first
// widened by the factor that makes the image's colours a typical draw from it (covariance matching:
// the innovation's squared Mahalanobis distance equals its dimension, where it was larger).
// Scaling the whole covariance keeps each unobserved colour's regression on the observed ones, and
// leaves the unobserved colours as uncertain as the venue is new. The pixel noise nu becomes the
// larger of the prior's and the carpet's own per-channel variance in this image (a real carpet's
// texture and a compressed image's blocks spread its pixels more than the priors' venues did).
//
// Contract: returns one prior per given prior, named as it, with the posterior mean and covariance
// (after the widening);
// a colour with fewer than the model's min_pixels_per_color labelled pixels is not observed (the
// prior stays as it was when neither is); deterministic.
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/color/field_segmentation.h"

namespace adaptive_perception::color {

/// The factor (>= 1, at most 1e6) the prior's covariance is widened by for this observation: 1 when
/// the innovation's squared Mahalanobis distance is at most its dimension, else the factor that
/// makes it equal.
double priorWidening(const LightingPrior& prior, const ColorObservation& observation,
                     const ColorModelConfig& model);

/// `yuv`: CV_8UC3 (Y, U, V); `segmentation`: segmentFieldYuv's result for it. Throws
/// std::invalid_argument when the sizes differ or a prior does not fit `model`.
std::vector<LightingPrior> adaptPriorsToImage(const std::vector<LightingPrior>& priors,
                                              const cv::Mat& yuv,
                                              const FieldSegmentation& segmentation,
                                              const ColorModelConfig& model);

}  // namespace adaptive_perception::color
