#pragma once
// The mirror test of the RBPF: which half of the field is the robot on?
//
// The field's lines are point-symmetric about the centre spot; only the goal and beacon colours
// tell the halves apart, and they are in view for a few frames only. After the particles have
// committed, every image scores the pose estimate and its point mirror side by side under one
// reference lighting, and sums the log-likelihood ratio (mirror minus estimate, tempered nats) over
// the images (a camera faster than 1 / view_interval_s counting as that rate), older images fading
// with time constant memory_s. The lines score alike for both, so
// the sum is the evidence of the goals and beacons alone. When it exceeds margin_nats, the caller
// moves the particles of the estimate's cluster to their mirrors (with the reference lighting).
//
// The reference lighting is a switching filter from the priors updated with the green and white
// means only, the colours that look alike from both poses: a particle's own lighting learns the
// colours under its own labels, so a particle on the mirror learns that its "cyan" beacon band is
// yellow, and then it explains the very pixels that should have told it apart. The memory lets new
// evidence overturn old within seconds: a kidnap that puts the robot near the mirror of where it
// was goes on fitting the lines, and a sum without fading held the particles on the wrong half.
//
// Contract: the evidence belongs to the hypothesis it was summed for. When the estimate moves to
// the mirror cluster on its own the sum changes sign; when it jumps anywhere else by more than
// 0.5 m, or the particles were placed anew (`restart`), it starts again.
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/localization/image_likelihood.h"
#include "adaptive_perception/localization/landmark_colours.h"

namespace adaptive_perception::localization {

struct MirrorTestConfig {
  double margin_nats = 3.0;  // 0 turns the test off
  double memory_s = 4.0;     // time constant of the evidence's fading
  // Images closer in time than this add their ratio times dt / view_interval_s: consecutive frames
  // of a 30 Hz camera are nearly one view, and counted as one each they summed the same small
  // preference 7.5 times per 0.25 s (a standing NAO's real images flipped to the wrong half after
  // 1.5 s). The simulated bags' 4 Hz images (0.25 s apart) count as one view each, as before.
  double view_interval_s = 0.25;
  // On a field whose two goals look alike (the SPL's), the landmarks' hues (landmark_colours.h)
  // add their evidence to each view's: there the landmarks alone break the symmetry, and the
  // likelihood weighs their few pixels by colour models that on a real camera come from other
  // venues (on the NAO development images it preferred the wrong half on two points of four, the
  // hues on none: docs/field_localization.md). Where the goals differ in colour, their hundreds
  // of pixels decide through the likelihood as before (the simulated four-legged field's figures
  // are unchanged; there the hues, untempered and judged at a lost track's pose, moved a
  // relocalizing track's cluster to its mirror: rbpf_test's relocalization draw).
  LandmarkColourConfig landmarks;
  /// Its parameters' names, ranges and docs; defined in rbpf_configs.cpp.
  static const config::Fields<MirrorTestConfig>& fields();
  void validate() const { fields().validate(*this); }
};

class MirrorTest {
 public:
  MirrorTest(const std::vector<color::LightingPrior>& priors, const color::ColorModelConfig& model,
             const color::SwitchingFilterConfig& switching, const MirrorTestConfig& config);

  /// Forgets the evidence and the reference lighting.
  void reset();

  struct Result {
    double evidence = 0.0;  // for the mirror of the estimate, after this image (0: not run)
    bool flip = false;      // the caller moves the estimate's cluster to its mirror
  };
  /// One image (`image` sampled with offsets for base_to_optical, `yuv` the whole image) and the
  /// particles' estimate after it; `restart`: the particles were placed anew since the last image.
  Result observe(const math::SE2& estimate, const math::SE2& odom_delta, double dt_s, bool restart,
                 const ImageLikelihood& likelihood, const SampledImage& image, const cv::Mat& yuv,
                 const Eigen::Isometry3d& base_to_optical);

  /// The reference lighting, which flipped particles take.
  const color::SwitchingColorFilter& lighting() const { return lighting_; }

 private:
  MirrorTestConfig config_;
  color::ColorModelConfig model_;
  bool have_pose_ = false;
  math::SE2 pose_;  // the estimate the evidence was last summed for
  double evidence_ = 0.0;
  color::SwitchingColorFilter lighting_;
};

}  // namespace adaptive_perception::localization
