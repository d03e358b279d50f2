// evaluate_tracking: runs the project's tracker over a sequence and, side by side on the same
// frames from the same first box, the trackers a user would pick instead: OpenCV's CSRT and KCF
// (opencv-contrib) and CamShift; scores all of them by the benchmarks' one-pass evaluation.
//
//   evaluate_tracking --help   (every option with its default, unit and range)
//
// --sequence reads an OTB or VOT folder as the benchmarks ship it (io/benchmark_sequence.h); what
// it skipped or cut is printed as `evaluate_tracking: note: ...`, and an image that cannot be read
// is skipped with a note. A video's ground truth defaults to the CSV beside it (same name, .csv).
// The trackers start at --start_frame from --init, else from that frame's true box, and are never
// re-initialised. Modes: box (the default: CONDENSATION over the target's region weighted by its
// colours against the background's and a grey template, tracking/box_condensation_tracker.h),
// condensation (the paper's: over the colour distribution, with the affine snake), ellipse (the
// head tracker). The trackers' settings are condensation_tracker's parameters, the same names and
// ranges (docs/nodes/condensation_tracker.md: --box_samples, --samples, --bins, --ellipse_*, ...);
// --color_space and --dynamics apply to condensation and ellipse.
//
// Scores (tracking/benchmark_metrics.h, OTB one-pass evaluation): every frame with a true box,
// the first included (its box is the start), IoU with the tracker's box: success rate (IoU >= 0.5),
// success AUC (21 thresholds), precision at 20 px centre error; a box is scored whatever the
// tracker says of it (lost frames are counted apart). Each tracker's time is its own; fps counts
// the frames it tracked (the first included) over its time, reading and drawing excluded.
// CSRT runs with OpenCV's defaults; KCF too, but for detect_thresh = 0 (as its authors' KCF, which
// never stops on a weak response). CamShift is set up as OpenCV's camshiftdemo: a hue-saturation
// histogram (30 x 32) of the first box over pixels with saturation >= 30 and value 10..255,
// back-projected and masked the same.
//
// Writes DIR/frames.csv (frame, each tracker's IoU, our lost flag and confidence), DIR/curves.csv
// (tracker, curve (success | precision), threshold, value; scripts/plot_tracking.py draws them),
// DIR/results.yaml (the summary), DIR/strip.png (six frames: truth white, ours green, CSRT blue,
// KCF cyan, CamShift magenta) and with --video_out DIR/overlay.avi. Last line:
// `evaluate_tracking: sequence=.. mode=.. success_rate=.. auc=.. precision_20px=.. mean_iou=..
// lost_frames=.. fps=.. csrt_success_rate=.. csrt_auc=.. csrt_precision_20px=.. csrt_fps=..
// kcf_... camshift_... camshift_mean_iou=.. frames=..` (a peer not run prints nan).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "adaptive_perception/io/benchmark_sequence.h"
#include "adaptive_perception/tracking/benchmark_metrics.h"
#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "adaptive_perception/tracking/condensation_tracker.h"
#include "adaptive_perception/tracking/ellipse_tracker.h"
#include "command_line.h"
#include "progress.h"
#include "tracking_sequence.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

/// One tracker under evaluation.
class Contender {
 public:
  virtual ~Contender() = default;
  virtual void init(const cv::Mat& bgr, const cv::Rect2d& box) = 0;
  /// This frame's box; *lost when the tracker says it lost the target.
  virtual cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                           tracking::Contour* contour) = 0;
};

class BoxContender : public Contender {
 public:
  BoxContender(const tracking::BoxTrackerConfig& c, std::uint64_t seed) : tracker_(c, seed) {}
  void init(const cv::Mat& bgr, const cv::Rect2d& box) override { tracker_.init(bgr, box); }
  cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                   tracking::Contour* contour) override {
    const tracking::BoxTrackResult r = tracker_.track(bgr);
    *lost = r.lost;
    *confidence = r.confidence;
    const cv::Rect2d& b = r.box;
    *contour = {
        {b.x, b.y}, {b.x + b.width, b.y}, {b.x + b.width, b.y + b.height}, {b.x, b.y + b.height}};
    return r.box;
  }

 private:
  tracking::BoxCondensationTracker tracker_;
};

class CondensationContender : public Contender {
 public:
  CondensationContender(const tracking::CondensationConfig& c, std::uint64_t seed)
      : tracker_(c, seed) {}
  void init(const cv::Mat& bgr, const cv::Rect2d& box) override {
    tracker_.init(bgr, cv::Rect(box));
  }
  cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                   tracking::Contour* contour) override {
    const tracking::TrackingResult r = tracker_.track(bgr);
    *lost = r.lost;
    *confidence = r.best.weight;
    *contour = r.contour;
    return r.box;
  }

 private:
  tracking::CondensationTracker tracker_;
};

class EllipseContender : public Contender {
 public:
  explicit EllipseContender(const tracking::EllipseTrackerConfig& c) : tracker_(c) {}
  void init(const cv::Mat& bgr, const cv::Rect2d& box) override {
    tracker_.init(bgr, tracking::Ellipse::inscribed(box));
  }
  cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                   tracking::Contour* contour) override {
    const tracking::EllipseResult r = tracker_.track(bgr);
    *lost = r.lost;
    *confidence = r.intersection;
    *contour = tracking::ellipseContour(r.ellipse.cx, r.ellipse.cy, r.ellipse.ax, r.ellipse.ay, 48);
    return r.ellipse.box();
  }

 private:
  tracking::EllipseTracker tracker_;
};

/// OpenCV's CSRT (default parameters) or KCF (default parameters but detect_thresh, see init).
class OpenCvContender : public Contender {
 public:
  explicit OpenCvContender(bool csrt) : csrt_(csrt) {}
  void init(const cv::Mat& bgr, const cv::Rect2d& box) override {
    if (csrt_) {
      tracker_ = cv::TrackerCSRT::create();
    } else {
      // KCF as Henriques et al. run it: the peak of the response is taken every frame. OpenCV's
      // own addition, a peak below detect_thresh (0.5) declaring a failure and freezing the box,
      // froze it on 110 of Crossing's 120 frames.
      cv::TrackerKCF::Params p;
      p.detect_thresh = 0.0f;
      tracker_ = cv::TrackerKCF::create(p);
    }
    box_ = box;
    tracker_->init(bgr, cv::Rect(box));
  }
  cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                   tracking::Contour*) override {
    cv::Rect r;
    *lost = !tracker_->update(bgr, r);
    *confidence = *lost ? 0.0 : 1.0;
    if (!*lost) box_ = cv::Rect2d(r);  // on a failure the last box stands
    return box_;
  }

 private:
  bool csrt_;
  cv::Ptr<cv::Tracker> tracker_;
  cv::Rect2d box_;
};

/// CamShift as OpenCV's camshiftdemo sets it up, with a hue-saturation histogram.
class CamShiftContender : public Contender {
 public:
  void init(const cv::Mat& bgr, const cv::Rect2d& box) override {
    window_ = cv::Rect(box) & cv::Rect(0, 0, bgr.cols, bgr.rows);
    cv::Mat hsv, mask;
    hsvAndMask(bgr, &hsv, &mask);
    const int channels[] = {0, 1};
    const int size[] = {30, 32};
    const float h_range[] = {0, 180}, s_range[] = {0, 256};
    const float* ranges[] = {h_range, s_range};
    cv::Mat roi = hsv(window_), m = mask(window_);
    cv::calcHist(&roi, 1, channels, m, hist_, 2, size, ranges);
    cv::normalize(hist_, hist_, 0, 255, cv::NORM_MINMAX);
  }
  cv::Rect2d track(const cv::Mat& bgr, bool* lost, double* confidence,
                   tracking::Contour*) override {
    cv::Mat hsv, mask, back;
    hsvAndMask(bgr, &hsv, &mask);
    const int channels[] = {0, 1};
    const float h_range[] = {0, 180}, s_range[] = {0, 256};
    const float* ranges[] = {h_range, s_range};
    cv::calcBackProject(&hsv, 1, channels, hist_, back, ranges);
    back &= mask;
    // The demo's recovery: a collapsed window restarts around where it was.
    if (window_.area() <= 1) {
      const int c = std::max(5, (std::min(bgr.cols, bgr.rows) + 5) / 6);
      window_ =
          cv::Rect(window_.x - c, window_.y - c, window_.width + 2 * c, window_.height + 2 * c) &
          cv::Rect(0, 0, bgr.cols, bgr.rows);
    }
    const cv::RotatedRect r = cv::CamShift(
        back, window_, cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1));
    *lost = window_.area() <= 1;
    *confidence = *lost ? 0.0 : 1.0;
    return cv::Rect2d(r.boundingRect2f()) & cv::Rect2d(0, 0, bgr.cols, bgr.rows);
  }

 private:
  static void hsvAndMask(const cv::Mat& bgr, cv::Mat* hsv, cv::Mat* mask) {
    cv::cvtColor(bgr, *hsv, cv::COLOR_BGR2HSV);
    cv::inRange(*hsv, cv::Scalar(0, 30, 10), cv::Scalar(180, 256, 256), *mask);
  }
  cv::Mat hist_;
  cv::Rect window_;
};

struct Run {
  Run(std::string n, std::unique_ptr<Contender> t, cv::Scalar c)
      : name(std::move(n)), tracker(std::move(t)), colour(c) {}
  std::string name;  // "ours", "csrt", "kcf", "camshift"
  std::unique_ptr<Contender> tracker;
  cv::Scalar colour;
  double busy_s = 0.0;
  long frames = 0, lost = 0;
  std::vector<std::optional<cv::Rect2d>> boxes;
};

std::optional<cv::Rect2d> parseBox(const std::string& s) {
  double x, y, w, h;
  char c1, c2, c3;
  std::istringstream in(s);
  if (!(in >> x >> c1 >> y >> c2 >> w >> c3 >> h) || c1 != ',' || c2 != ',' || c3 != ',' ||
      !(w >= 4 && h >= 4))
    return std::nullopt;
  return cv::Rect2d(x, y, w, h);
}

}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_tracking",
                         "Runs the project's tracker over a sequence and, on the same frames from "
                         "the same first box, OpenCV's CSRT, KCF and CamShift; scores all of them "
                         "by the benchmarks' one-pass evaluation.");
  std::string sequence;
  cli.option("sequence", &sequence, "OTB or VOT sequence folder");
  tools::TrackingSource source;
  source.addOptions(cli);
  std::string init_arg;
  cli.option("init", &init_arg, "first box x,y,w,h in px (empty: the ground truth's)");
  std::string mode = "box";
  cli.option("mode", &mode, "our tracker")
      ->oneOf({"box", "condensation", "ellipse"});
  std::string peers_arg = "csrt,kcf,camshift";
  cli.option("peers", &peers_arg, "peers run beside it: comma-separated, or none");
  std::string dynamics;
  cli.option("dynamics", &dynamics, "learned AR(2) dynamics (YAML, learn_tracking_dynamics)");
  const std::uint64_t& seed = cli.seed();
  long start_frame = 0;
  cli.option("start_frame", &start_frame, config::closed(0, 1e9), "first frame tracked");
  long max_frames = 0;
  cli.option("max_frames", &max_frames, config::closed(0, 1e9), "frames tracked (0: all)");
  const std::string& output = cli.resultsFolder("the results");
  bool video_out = false;
  cli.flag("video_out", &video_out, "also writes a video of the boxes");
  // condensation_tracker's parameters (the same names and ranges).
  tracking::BoxTrackerConfig bc;
  tracking::CondensationConfig cc;
  tracking::EllipseTrackerConfig ec;
  cli.fields(tracking::BoxTrackerConfig::fields(), &bc);
  cli.fields(tracking::CondensationConfig::fields(), &cc);
  cli.fields(tracking::EllipseTrackerConfig::fields(), &ec);
  cli.word("color_space", &cc.quantizer.space, tracking::colorSpaces(),
           "colour space of the histograms");
  cli.parse(argc, argv);
  if (sequence.empty() + source.bag.empty() + source.video.empty() != 2)
    cli.fail("give exactly one of --sequence DIR, --bag FILE and --video FILE");
  source.findGroundTruth();
  std::vector<std::string> peers;
  if (peers_arg != "none") {
    std::stringstream ss(peers_arg);
    for (std::string p; std::getline(ss, p, ',');) {
      if (p != "csrt" && p != "kcf" && p != "camshift")
        cli.fail("--peers: unknown tracker '" + p + "' (csrt, kcf, camshift or none)");
      peers.push_back(p);
    }
  }
  std::optional<cv::Rect2d> init;
  if (!init_arg.empty() && !(init = parseBox(init_arg)))
    cli.fail("--init must be x,y,w,h with w, h >= 4 pixels, got '" + init_arg + "'");
  try {
    if (!dynamics.empty()) cc.dynamics = tracking::Ar2Model::loadYaml(dynamics);
    cc.validate();
    ec.quantizer = cc.quantizer;

    std::vector<Run> runs;
    runs.emplace_back("ours", nullptr, cv::Scalar(0, 220, 0));
    if (mode == "box")
      runs.back().tracker = std::make_unique<BoxContender>(bc, seed);
    else if (mode == "condensation")
      runs.back().tracker = std::make_unique<CondensationContender>(cc, seed);
    else
      runs.back().tracker = std::make_unique<EllipseContender>(ec);
    for (const std::string& p : peers) {
      if (p == "csrt")
        runs.emplace_back(p, std::make_unique<OpenCvContender>(true), cv::Scalar(255, 80, 0));
      if (p == "kcf")
        runs.emplace_back(p, std::make_unique<OpenCvContender>(false), cv::Scalar(255, 255, 0));
      if (p == "camshift")
        runs.emplace_back(p, std::make_unique<CamShiftContender>(), cv::Scalar(200, 0, 200));
    }

    // The frames: a benchmark folder, or a bag / video.
    std::string name;
    std::vector<std::string> notes;
    io::BenchmarkSequence seq;
    if (!sequence.empty()) {
      seq = io::readBenchmarkSequence(sequence);
      name = seq.name;
      notes = seq.notes;
    } else {
      name = source.name();
    }
    for (const std::string& n : notes) std::printf("evaluate_tracking: note: %s\n", n.c_str());

    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "frames.csv");
    csv << "frame";
    for (const Run& r : runs) csv << "," << r.name << "_iou";
    csv << ",lost,confidence\n";
    std::unique_ptr<cv::VideoWriter> overlay_video;
    std::vector<std::optional<cv::Rect2d>> truth;
    std::vector<cv::Mat> overlays;
    long frames = 0;
    const long last_frame = max_frames > 0 ? start_frame + max_frames : 0;
    tools::Progress progress("evaluate_tracking", max_frames, "frames");
    auto onFrame = [&](const tools::TrackingFrameIn& f) {
      if (f.index < start_frame) return;
      ++frames;
      progress.update(frames);
      truth.push_back(f.truth);
      cv::Mat over = f.bgr.clone();
      if (f.truth) cv::rectangle(over, cv::Rect(*f.truth), cv::Scalar(255, 255, 255), 1);
      csv << f.index;
      bool our_lost = false;
      double our_confidence = 0.0;
      for (Run& r : runs) {
        const auto t0 = Clock::now();
        cv::Rect2d box;
        bool lost = false;
        double confidence = 1.0;
        tracking::Contour contour;
        if (f.index == start_frame) {
          const std::optional<cv::Rect2d> start = init ? init : f.truth;
          if (!start) throw std::runtime_error("no --init and no true box on the first frame");
          r.tracker->init(f.bgr, *start);
          box = *start;
        } else {
          box = r.tracker->track(f.bgr, &lost, &confidence, &contour);
        }
        r.busy_s += std::chrono::duration<double>(Clock::now() - t0).count();
        ++r.frames;
        r.lost += lost;
        r.boxes.push_back(box);
        const double iou = f.truth ? tracking::boxIou(box, *f.truth) : -1.0;
        csv << "," << iou;
        if (&r == &runs.front()) {
          our_lost = lost;
          our_confidence = confidence;
          std::vector<cv::Point> poly;
          for (const auto& p : contour)
            poly.emplace_back(static_cast<int>(std::lround(p.x())),
                              static_cast<int>(std::lround(p.y())));
          if (poly.size() > 2)
            cv::polylines(over, poly, true, lost ? cv::Scalar(0, 0, 255) : r.colour, 2);
          else
            cv::rectangle(over, cv::Rect(box), r.colour, 2);
        } else {
          cv::rectangle(over, cv::Rect(box), r.colour, 1);
        }
      }
      csv << "," << our_lost << "," << our_confidence << "\n";
      cv::putText(over, std::to_string(f.index), {5, 15}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                  cv::Scalar(255, 255, 255));
      if (video_out) {
        if (!overlay_video)
          overlay_video = std::make_unique<cv::VideoWriter>(
              (fs::path(output) / "overlay.avi").string(), cv::CAP_OPENCV_MJPEG,
              cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30.0, over.size());
        overlay_video->write(over);
      }
      overlays.push_back(over);
      if (overlays.size() > 600) overlays.erase(overlays.begin() + 1);  // bound memory
    };
    if (!sequence.empty()) {
      int index = 0;
      for (std::size_t i = 0; i < seq.frames.size(); ++i) {
        if (last_frame > 0 && static_cast<long>(i) >= last_frame) break;
        tools::TrackingFrameIn f;
        f.bgr = cv::imread(seq.frames[i], cv::IMREAD_COLOR);  // grey images come as 3 channels
        if (f.bgr.empty()) {
          std::printf("evaluate_tracking: note: %s cannot be read as an image: skipped\n",
                      seq.frames[i].c_str());
          continue;
        }
        f.index = index++;
        f.truth = seq.truth[i];
        onFrame(f);
      }
    } else {
      tools::forEachTrackingFrame(source, static_cast<int>(last_frame), onFrame);
    }
    progress.finish();
    if (frames < 2) throw std::runtime_error("fewer than two frames from --start_frame on");

    // Scores, curves, summary.
    std::ofstream curves(fs::path(output) / "curves.csv");
    curves << "tracker,curve,threshold,value\n";
    std::ostringstream summary, yaml;
    summary << "evaluate_tracking: sequence=" << name << " mode=" << mode;
    yaml << "sequence: " << name << "\nmode: " << mode << "\nframes: " << frames << "\n";
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::map<std::string, tracking::TrackScores> scores;
    std::map<std::string, double> fps;
    for (const Run& r : runs) {
      const tracking::TrackScores s = tracking::scoreTrack(r.boxes, truth);
      scores[r.name] = s;
      fps[r.name] = r.frames / std::max(r.busy_s, 1e-9);
      for (std::size_t k = 0; k < s.success_curve.size(); ++k)
        curves << r.name << ",success," << 0.05 * k << "," << s.success_curve[k] << "\n";
      for (std::size_t k = 0; k < s.precision_curve.size(); ++k)
        curves << r.name << ",precision," << k << "," << s.precision_curve[k] << "\n";
      yaml << r.name << ":\n  success_rate: " << s.success_rate << "\n  auc: " << s.auc
           << "\n  precision_20px: " << s.precision_20px << "\n  mean_iou: " << s.mean_iou
           << "\n  fps: " << fps[r.name] << "\n  lost_frames: " << r.lost
           << "\n  frames_scored: " << s.frames_scored << "\n";
    }
    auto value = [&](const std::string& tracker, double tracking::TrackScores::*field) {
      const auto it = scores.find(tracker);
      return it == scores.end() || it->second.frames_scored == 0 ? nan : it->second.*field;
    };
    char buf[160];
    std::snprintf(buf, sizeof(buf),
                  " success_rate=%.3f auc=%.3f precision_20px=%.3f mean_iou=%.3f lost_frames=%ld "
                  "fps=%.1f",
                  value("ours", &tracking::TrackScores::success_rate),
                  value("ours", &tracking::TrackScores::auc),
                  value("ours", &tracking::TrackScores::precision_20px),
                  value("ours", &tracking::TrackScores::mean_iou), runs.front().lost, fps["ours"]);
    summary << buf;
    for (const std::string p : {"csrt", "kcf", "camshift"}) {
      std::snprintf(
          buf, sizeof(buf), " %s_success_rate=%.3f %s_auc=%.3f %s_precision_20px=%.3f %s_fps=%.1f",
          p.c_str(), value(p, &tracking::TrackScores::success_rate), p.c_str(),
          value(p, &tracking::TrackScores::auc), p.c_str(),
          value(p, &tracking::TrackScores::precision_20px), p.c_str(), fps.count(p) ? fps[p] : nan);
      summary << buf;
    }
    std::snprintf(buf, sizeof(buf), " camshift_mean_iou=%.3f frames=%ld",
                  value("camshift", &tracking::TrackScores::mean_iou), frames);
    summary << buf;
    std::ofstream(fs::path(output) / "results.yaml") << yaml.str();

    // Six frames evenly over the run.
    std::vector<cv::Mat> picks;
    for (int k = 0; k < 6 && !overlays.empty(); ++k)
      picks.push_back(overlays[std::min(overlays.size() - 1, k * (overlays.size() - 1) / 5)]);
    if (picks.size() == 6) {
      cv::Mat strip, top, bottom;
      cv::hconcat(std::vector<cv::Mat>(picks.begin(), picks.begin() + 3), top);
      cv::hconcat(std::vector<cv::Mat>(picks.begin() + 3, picks.end()), bottom);
      cv::vconcat(top, bottom, strip);
      cv::imwrite((fs::path(output) / "strip.png").string(), strip);
    }
    std::printf("%s\n", summary.str().c_str());
  } catch (const std::exception& e) {
    std::cerr << "evaluate_tracking: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
