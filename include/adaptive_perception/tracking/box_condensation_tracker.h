#pragma once
// CONDENSATION over the target's image region, weighted by its colour distribution against the
// background's: the tracker for real video (papers/001 section 3 keeps its frame: factored
// sampling, a colour model of the target that follows the light by a gated update, eq. 29).
//
// The paper's tracker samples the colour distribution's parameters and lets a snake find the
// region; on real video the snake locks onto any blob of similar colour and the target is lost
// within frames. Here the samples are regions and the colours decide between them:
//
//  1. State of a sample: the box centre (x, y) in pixels, its log scale and log aspect (relative
//     to the first box). Each frame the set is resampled by weight (systematic), moved by the
//     estimate's last displacement times `velocity_gain`, and spread by Gaussian noise of
//     `position_noise` box sides, `scale_noise` and `aspect_noise` (log) per frame.
//  2. Observation: a per-pixel object likelihood P(O | c) = H_O(c) / (H_O(c) + H_S(c)) from the
//     target's colour histogram H_O and that of its surroundings H_S (RGB, bins_per_channel^3 bins;
//     both normalised), over the region the samples span. A sample's score is the mean of P inside
//     its box minus the mean in the ring around it (the box grown by `ring_scale`): the target's
//     own box scores highest, a box inside the target or one spilling over the background lower,
//     so position and scale are both measured. Summed-area tables make a sample O(1).
//     Its weight is exp(score_gain * score + template_gain * NCC of a grey template + filter_gain *
//     the correlation filter's response at its centre and scale; see `filter` below).
//  3. Estimate: the weighted mean of the samples within half a box side of the best one, its
//     scale then set by the filter (`filter_scale_share`) and the scale filter (`scale_filter_share`).
//     Confidence = the estimate's log-weight / score_gain (colour score + the appearance cues'
//     share); below `lost_score` the target is lost, and the next frames' samples spread over a
//     region growing by `lost_growth` a frame (re-detection). The filter's response says more:
//     a frame whose response peak or sharpness (APCE) and colour score fall well below their
//     means so far (reliable_peak_ratio, reliable_apce_ratio) is unreliable and reported lost,
//     although the estimate still follows the samples.
//  4. Model update (eq. 29): while confident (score >= update_min_score), H_O and H_S move towards
//     the histograms of the estimated box and its surroundings by `learning_rate` (and the template
//     and the filter by theirs), so the model follows the light but does not learn the background
//     when the target is doubtful.
// On the development sequences (docs/tracking_real_video.md) the filter, the samples drawn at its
// peak and its scale carry most of the gain: mean success 0.52 without them, 0.84 with.
#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/tracking/correlation_filter.h"
#include "adaptive_perception/tracking/scale_filter.h"

namespace adaptive_perception::tracking {

struct BoxTrackerConfig {
  int samples = 300;          // N, 10..100000
  int bins_per_channel = 16;  // of the RGB histograms, 2..64 (a power of two)
  // The histograms' colours: RGB (bins_per_channel^3), or normalised chromaticity r, g
  // (bins_per_channel^2) with 4 brightness levels (true), which a change of light that scales the
  // three channels leaves alone; RGB by default: chromaticity lost more targets on the development
  // sequences (mean success 0.37 against 0.47 over five seeds) and cannot tell grey levels apart.
  bool chroma = false;
  double position_noise = 0.15;  // sd of a sample's move per frame, in box sides, > 0
  double scale_noise = 0.04;     // sd of a sample's log-scale change per frame, >= 0
  double aspect_noise = 0.02;    // sd of a sample's log-aspect change per frame, >= 0
  double velocity_gain = 0.5;    // share of the last displacement carried on, [0, 1]
  // A share of the samples moves with wide_noise box sides instead, for a target that changes its
  // course abruptly (a bouncing ball, a jump). Off: on the development sequences such samples
  // found a distractor more often than they caught an abrupt move.
  double wide_fraction = 0.0;      // [0, 1)
  double wide_noise = 0.8;         // box sides, > 0
  double ring_scale = 1.6;         // the scoring ring: the box grown by this (side factor), > 1
  double surround_scale = 2.2;     // H_S: the box grown by this, minus the box, > 1
  double score_gain = 50.0;        // weight = exp(gain * score), > 0
  double learning_rate = 0.05;     // of the model update, [0, 1]
  double update_min_score = 0.25;  // update only at a confidence this high, [-1, 1]
  double lost_score = 0.05;        // below: lost, [-1, 1]
  double lost_growth = 1.5;        // noise factor per lost frame (re-detection), >= 1
  double min_side_px = 4.0;        // smallest box side, > 0
  int template_cells = 16;         // appearance template: grid of this many cells a side, 0 = off
  double template_gain = 10.0;     // weight += gain * NCC of the grey template, >= 0
  double template_rate = 0.05;     // template update per confident frame, [0, 1]
  // The estimate's scale can then be chosen by the template alone among 2 * scale_search_steps + 1
  // scales scale_step (log) apart about the samples' (colour prefers a box that takes in
  // neighbouring pixels of the target's colours: hair, neck). Off (0) by default: over five seeds
  // of the development sequences it shrank fast or blurred targets (ball1 success 0.68 -> 0.45) and
  // did not raise the mean AUC (0.456 without, 0.452 with).
  int scale_search_steps = 0;  // 0..20
  double scale_step = 0.03;    // > 0
  // The appearance cue that carries the target through clutter and blur: a correlation filter
  // over gradient cells (tracking/correlation_filter.h), answered about the predicted centre at
  // 2 * filter_scales + 1 scales filter_scale_step (log) apart about the estimate's. A sample's
  // weight gains filter_gain times the response at its centre in the map of its nearest scale,
  // and peak_fraction of the samples are drawn about the best response's peak (an importance
  // proposal, as in ICONDENSATION: a fast target is found where the prior's spread does not
  // reach). The filter learns (its learning_rate) on the frames the colour model learns on.
  CorrelationFilterConfig filter;
  double filter_gain = 60.0;        // 0 = off, >= 0
  int filter_scales = 2;            // 0..5
  double filter_scale_step = 0.03;  // > 0
  double peak_fraction = 0.2;       // [0, 1)
  // The estimate's log scale moves this share of the way from the samples' towards the filter's
  // best scale at the estimate's centre. All the way by default: over three seeds of the
  // development sequences started at a third of their length, mean success 0.711 -> 0.848 and
  // AUC 0.534 -> 0.635 (the colours' preference for a box that takes in the neighbouring pixels
  // of the target's colours no longer sets its size); from the first frame 0.827 -> 0.840.
  double filter_scale_share = 1.0;  // [0, 1]
  // Then this share of the way towards the scale filter's answer (tracking/scale_filter.h, DSST:
  // 33 scales 2% apart about the estimate's, at its centre), learnt on the frames the filter
  // learns on. Off (0) by default: docs/tracking_real_video.md.
  double scale_filter_share = 0.0;  // [0, 1]
  ScaleFilterConfig scale;
  // Knowing when the estimate is not the target (hidden, or another object in its place): each
  // frame's response map at the best scale gives its peak F_max and its average
  // peak-to-correlation energy APCE = (F_max - F_min)^2 / mean((F - F_min)^2) (Wang et al.,
  // "Large margin object tracking with circulant feature maps", CVPR 2017, whose ratios 0.7 and
  // 0.45 these are). A frame is unreliable, and reported lost, when F_max is below
  // reliable_peak_ratio of its mean over the frames so far or APCE below reliable_apce_ratio of
  // theirs, and the estimate's colour score is also below reliable_peak_ratio of its mean: the
  // response alone drops whenever the target turns or blurs (the toy, the diver), both drop when
  // it is hidden or lost. Development sequences: docs/tracking_real_video.md. 0 turns it off.
  double reliable_peak_ratio = 0.7;   // [0, 1]
  double reliable_apce_ratio = 0.45;  // [0, 1]
  // Distractors of the target's colours (Possegger et al., "In defense of color-based model-free
  // tracking", CVPR 2015): at each model update, boxes of the estimate's size around it (on a grid
  // of half its sides, within distractor_scale times its size, at least a side away) whose mean
  // P(O | c) reaches distractor_ratio of the estimate's are distractors (at most three, a side
  // apart); their colours make a histogram H_D, learnt at learning_rate (fading while none is
  // seen), and P(O | c) becomes the mean of H_O / (H_O + H_S) and H_O / (H_O + H_D), so that the
  // colours a look-alike shares with the target count for less. Off (0) by default: on the
  // development sequences (one seed) 0.5 gave mean success 0.796 and AUC 0.619, 0.7 gave 0.742 /
  // 0.576, against 0.806 / 0.621 without (docs/tracking_real_video.md); they hold no player
  // among players in the same kit, which is what it is for.
  double distractor_ratio = 0.0;  // [0, 1]
  double distractor_scale = 3.0;  // > 1
  // Whether the models (colours, template, filter) stop learning on an unreliable frame. Off: on
  // the development sequences it lost the turning toy and the jumping deer (mean success 0.806
  // -> 0.782; docs/tracking_real_video.md).
  bool unreliable_stops_learning = false;
  // Re-detection: after this many frames in a row reported lost, the whole frame is searched, each
  // frame, until the target is back. The redetect_places best places of the target's colours
  // (tracking/redetection.h, at the target's size when last followed, farther than a box side
  // from the estimate) are each
  // given to the correlation filter (a window about the place at the target's scale when last
  // followed), and the target jumps to the best answer only where both cues agree: the filter's
  // response is as sharp as it was while the target was followed (APCE at least
  // reliable_apce_ratio of its mean then) with a higher peak than at the estimate, and the colour
  // score at that peak reaches reliable_peak_ratio of its mean then and beats the estimate's. The
  // search ends there, or when the estimate's own peak and colours reach reliable_peak_ratio of
  // those means again; while it runs, the models do not learn, and a target taken back starts its
  // means again from those. 0 turns it off. 5 on the development sequences (mean success 0.806 ->
  // 0.807, AUC 0.621 -> 0.626; 2 searched on false alarms, 0.792 / 0.613; 10 the same AUC, 20
  // nothing; left out one at a time 0.806 / 0.624: docs/tracking_real_video.md).
  int redetect_after_frames = 5;  // 0..1000
  int redetect_places = 5;        // 1..100
  /// The fields condensation_tracker sets (config/fields.h: ~box_samples, ~box_filter_gain,
  /// ~box_peak_fraction, ~box_lost_score); defined in tracker_configs.cpp.
  static const config::Fields<BoxTrackerConfig>& fields();
  void validate() const;       // throws std::invalid_argument naming the field
};

struct BoxTrackResult {
  cv::Rect2d box;
  double confidence = 0.0;  // score of the estimate: mean P inside minus mean P in the ring
  bool lost = false;        // the colours lost the target, or the filter's response is unreliable
  bool unreliable = false;  // response and colours both weak (reliable_peak_ratio, ..._apce_ratio)
  bool redetected = false;  // the whole-frame search moved the target (redetect_after_frames)
  double response_peak = 0.0, response_apce = 0.0;  // the filter's F_max and APCE (0 when off)
  std::vector<cv::Rect2d> distractors;  // found at this frame's model update (distractor_ratio)
  cv::Rect search;  // region the samples spanned (clipped to the image)
  cv::Mat likelihood;  // P(O | c) over `search` (CV_32F, 0..1): the target's colours against the surroundings
  std::vector<cv::Rect2d> samples;
  std::vector<double> weights;  // normalised
};

class BoxCondensationTracker {
 public:
  explicit BoxCondensationTracker(BoxTrackerConfig config = {}, std::uint64_t seed = 1);
  /// Starts on `box` of a bgr8 (or mono8) frame. Throws std::invalid_argument when the box is
  /// smaller than min_side_px or does not overlap the image.
  void init(const cv::Mat& image, const cv::Rect2d& box);
  BoxTrackResult track(const cv::Mat& image);
  bool initialized() const { return initialized_; }
  const BoxTrackerConfig& config() const { return config_; }

 private:
  struct Sample {
    double x, y, log_scale, log_aspect;  // width = w0 e^(s + a/2), height = h0 e^(s - a/2)
  };
  cv::Rect2d boxOf(const Sample& s) const;
  void histograms(const cv::Mat& bins, const cv::Rect2d& box, std::vector<float>* object,
                  std::vector<float>* surround) const;
  void binImage(const cv::Mat& image, const cv::Rect& region, cv::Mat* bins) const;
  /// P(O | c) per bin from H_O, H_S and, once distractors were seen, H_D.
  std::vector<float> objectLikelihood() const;
  /// Finds the distractors around `box` under `lut` and updates H_D (distractor_ratio).
  void learnDistractors(const cv::Mat& image, const cv::Rect2d& box,
                        const std::vector<float>& lut);

  BoxTrackerConfig config_;
  math::Rng rng_;
  bool initialized_ = false;
  double w0_ = 0.0, h0_ = 0.0;  // first box size (scale 1)
  Sample estimate_{0, 0, 0, 0};
  double vx_ = 0.0, vy_ = 0.0;
  std::vector<Sample> samples_;
  std::vector<double> weights_;
  std::vector<float> h_object_, h_surround_;
  std::vector<float> h_distractor_;        // empty until a distractor is seen
  std::vector<cv::Rect2d> out_distractors_;  // the last update's
  std::vector<float> template_;  // zero mean, unit norm; empty when off
  CorrelationFilter filter_;
  ScaleFilter scale_filter_;
  /// The filter's response maps about `centre` at the estimate's scale times
  /// exp(k filter_scale_step), k = -filter_scales..filter_scales.
  struct FilterMaps {
    cv::Point2d centre;
    double log_scale = 0.0;  // the estimate's
    std::vector<cv::Mat> maps;
    /// The response a box centred at (x, y) of log scale `log_scale` gets (0 outside the maps).
    double at(const CorrelationFilter& f, double step, double x, double y, double log_scale) const;
  };
  /// The grey values of `box` on a template_cells^2 grid, zero mean and unit norm (empty when the
  /// box is flat), from `grey` (CV_32F, smoothed) whose origin lies at `origin` in the image.
  std::vector<float> patch(const cv::Mat& grey, const cv::Point& origin,
                           const cv::Rect2d& box) const;
  void smoothedGrey(const cv::Mat& image, const cv::Rect& region, double box_side,
                    cv::Mat* grey) const;
  int lost_frames_ = 0;
  int lost_run_ = 0;  // frames in a row reported lost (re-detection)
  bool searching_ = false;  // the whole-frame search runs each frame until the target is back
  // The cues' means, the scale and the aspect when the target was last followed.
  double reference_peak_ = 0.0, reference_colour_ = 0.0, reference_apce_ = 0.0;
  double reference_log_scale_ = 0.0, reference_log_aspect_ = 0.0;
  /// The whole-frame search (redetect_after_frames): the best place where the filter and the
  /// colours under `lut` both answer, better than `peak_now` and `colour_now`; false when none.
  bool redetect(const cv::Mat& image, const cv::Mat& grey, const std::vector<float>& lut,
                double peak_now, double colour_now, Sample* found) const;
  // The means of F_max, APCE and the estimate's colour score over the frames so far, and how
  // many there were.
  double mean_peak_ = 0.0, mean_apce_ = 0.0, mean_colour_ = 0.0;
  long response_frames_ = 0;
};

}  // namespace adaptive_perception::tracking
