// evaluate_tracking: runs the tracker of papers/001 section 3 over a sequence and, side by side on
// the same frames, OpenCV's CamShift (the baseline most users would pick), and scores both
// against the ground truth.
//
//   evaluate_tracking (--bag FILE | --video FILE [--ground_truth CSV]) [--init x,y,w,h]
//       [--mode condensation|ellipse] [--samples 100] [--color_space rgb|opponent] [--bins 16]
//       [--dynamics FILE.yaml] [--seed 1] [--start_frame 0] [--max_frames N] [--output DIR]
//       [--video_out]
//
// A video's ground truth defaults to the CSV beside it (same name, .csv) when there is one.
// The target starts at --start_frame from --init, else from that frame's ground truth. Without any
// ground truth (a plain video) the IoU keys print nan; speed and lost frames are still measured.
// Per frame: IoU of the tracker's box (condensation: the contour's box; ellipse: the ellipse's box)
// and of CamShift's (hue histogram of the initial box, pixels with saturation > 60 and value
// in 32..255, as in OpenCV's sample) with the truth; a frame succeeds when IoU >= 0.5. The first
// frame (the initialisation) is not scored. CamShift's time is not in the tracker's. Writes
// DIR/frames.csv (frame, iou, camshift_iou, lost, confidence), DIR/iou.png (IoU over time, both
// trackers), DIR/strip.png (six frames: truth white, tracker green, CamShift magenta) and, with
// --video_out, DIR/overlay.avi. Last line: `evaluate_tracking: mode=.. mean_iou=.. success_rate=..
// lost_frames=.. fps=.. camshift_mean_iou=.. camshift_success_rate=.. camshift_fps=.. frames=..`.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>

#include "adaptive_perception/tracking/condensation_tracker.h"
#include "adaptive_perception/tracking/ellipse_tracker.h"
#include "tool_args.h"
#include "tracking_sequence.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

// OpenCV's CamShift on a hue histogram, as its camshiftdemo does.
class CamShiftBaseline {
 public:
  void init(const cv::Mat& bgr, const cv::Rect& box) {
    window_ = box & cv::Rect(0, 0, bgr.cols, bgr.rows);
    cv::Mat hue, mask;
    hueAndMask(bgr, &hue, &mask);
    const int channels[] = {0};
    const int size[] = {16};
    const float range[] = {0, 180};
    const float* ranges[] = {range};
    cv::Mat roi = hue(window_), m = mask(window_);
    cv::calcHist(&roi, 1, channels, m, hist_, 1, size, ranges);
    cv::normalize(hist_, hist_, 0, 255, cv::NORM_MINMAX);
  }
  cv::Rect2d track(const cv::Mat& bgr) {
    cv::Mat hue, mask, back;
    hueAndMask(bgr, &hue, &mask);
    const int channels[] = {0};
    const float range[] = {0, 180};
    const float* ranges[] = {range};
    cv::calcBackProject(&hue, 1, channels, hist_, back, ranges);
    back &= mask;
    if (window_.area() <= 0) window_ = cv::Rect(0, 0, bgr.cols, bgr.rows);  // as the demo
    const cv::RotatedRect r = cv::CamShift(
        back, window_, cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1));
    return cv::Rect2d(r.boundingRect2f()) & cv::Rect2d(0, 0, bgr.cols, bgr.rows);
  }

 private:
  static void hueAndMask(const cv::Mat& bgr, cv::Mat* hue, cv::Mat* mask) {
    cv::Mat hsv;
    cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
    cv::inRange(hsv, cv::Scalar(0, 60, 32), cv::Scalar(180, 255, 255), *mask);
    cv::extractChannel(hsv, *hue, 0);
  }
  cv::Mat hist_;
  cv::Rect window_;
};

cv::Mat plotIou(const std::vector<int>& frames, const std::vector<double>& a,
                const std::vector<double>& b, const std::string& title) {
  const int w = 800, h = 300, l = 50, r = 20, t = 30, bt = 40;
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  const double fmax = frames.empty() ? 1 : std::max(1, frames.back());
  auto px = [&](double f, double v) {
    return cv::Point(static_cast<int>(l + (w - l - r) * f / fmax),
                     static_cast<int>(h - bt - (h - t - bt) * v));
  };
  cv::rectangle(img, px(0, 0), px(fmax, 1), cv::Scalar(0, 0, 0));
  for (double v : {0.0, 0.5, 1.0}) {
    cv::line(img, px(0, v), px(fmax, v), cv::Scalar(210, 210, 210));
    cv::putText(img, cv::format("%.1f", v), px(0, v) + cv::Point(-35, 5), cv::FONT_HERSHEY_SIMPLEX,
                0.4, cv::Scalar(0, 0, 0));
  }
  for (int k = 0; k <= 4; ++k)
    cv::putText(img, std::to_string(static_cast<int>(fmax * k / 4)),
                px(fmax * k / 4, 0) + cv::Point(-10, 18), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(0, 0, 0));
  const cv::Scalar ca(0, 150, 0), cb(200, 0, 200);
  for (size_t i = 1; i < frames.size(); ++i) {
    cv::line(img, px(frames[i - 1], b[i - 1]), px(frames[i], b[i]), cb, 1, cv::LINE_AA);
    cv::line(img, px(frames[i - 1], a[i - 1]), px(frames[i], a[i]), ca, 2, cv::LINE_AA);
  }
  cv::putText(img, title, {l, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
  cv::putText(img, "tracker", {w - 190, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, ca);
  cv::putText(img, "CamShift", {w - 110, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cb);
  cv::putText(img, "frame", {w / 2, h - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0));
  cv::putText(img, "IoU", {5, t + 10}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0));
  return img;
}

}  // namespace

int main(int argc, char** argv) {
  tools::Args args(argc, argv,
                   "evaluate_tracking (--bag FILE | --video FILE [--ground_truth CSV]) "
                   "[--init x,y,w,h] [--mode condensation|ellipse] [--samples N] "
                   "[--color_space rgb|opponent] [--bins N] [--dynamics FILE.yaml] [--seed N] "
                   "[--start_frame N] [--max_frames N] [--output DIR] [--video_out]");
  const std::string bag = args.get("bag", "");
  const std::string video = args.get("video", "");
  std::string truth_csv = args.get("ground_truth", "");
  const std::string init_arg = args.get("init", "");
  const std::string mode = args.get("mode", "condensation");
  const long samples = args.getInt("samples", 100);
  const std::string space = args.get("color_space", "opponent");
  const long bins = args.getInt("bins", 16);
  const std::string dynamics = args.get("dynamics", "");
  const auto seed = static_cast<std::uint64_t>(args.getInt("seed", 1));
  const long start_frame = args.getInt("start_frame", 0);
  const long max_frames = args.getInt("max_frames", 0);
  const std::string output = args.get("output", "results/evaluate_tracking");
  const bool video_out = args.has("video_out");
  args.finish();
  if (bag.empty() == video.empty()) args.fail("give exactly one of --bag FILE and --video FILE");
  if (start_frame < 0) args.fail("--start_frame must be >= 0");
  if (!video.empty() && truth_csv.empty()) {  // simulate_tracking's CSV beside the video
    const fs::path beside = fs::path(video).replace_extension(".csv");
    if (fs::exists(beside)) truth_csv = beside.string();
  }
  if (mode != "condensation" && mode != "ellipse")
    args.fail("--mode must be condensation or ellipse, got " + mode);
  std::optional<cv::Rect2d> init;
  if (!init_arg.empty()) {
    double x, y, w, h;
    char c1, c2, c3;
    std::istringstream s(init_arg);
    if (!(s >> x >> c1 >> y >> c2 >> w >> c3 >> h) || c1 != ',' || c2 != ',' || c3 != ',' ||
        !(w >= 4 && h >= 4))
      args.fail("--init must be x,y,w,h with w, h >= 4 pixels, got '" + init_arg + "'");
    init = cv::Rect2d(x, y, w, h);
  }
  try {
    tracking::CondensationConfig cc;
    cc.samples = static_cast<int>(samples);
    cc.quantizer.space = tracking::parseColorSpace(space);
    cc.quantizer.bins = static_cast<int>(bins);
    if (!dynamics.empty()) cc.dynamics = tracking::Ar2Model::loadYaml(dynamics);
    cc.validate();
    tracking::EllipseTrackerConfig ec;
    ec.quantizer.space = cc.quantizer.space;
    std::unique_ptr<tracking::CondensationTracker> cond;
    std::unique_ptr<tracking::EllipseTracker> ell;
    if (mode == "condensation")
      cond = std::make_unique<tracking::CondensationTracker>(cc, seed);
    else
      ell = std::make_unique<tracking::EllipseTracker>(ec);
    CamShiftBaseline camshift;
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "frames.csv");
    csv << "frame,iou,camshift_iou,lost,confidence\n";
    std::unique_ptr<cv::VideoWriter> overlay_video;
    double busy = 0.0, cam_busy = 0.0, iou_sum = 0.0, cam_sum = 0.0;
    long scored = 0, success = 0, cam_success = 0, lost = 0, frames = 0;
    std::vector<int> plot_f;
    std::vector<double> plot_a, plot_b;
    std::vector<cv::Mat> overlays;
    const int total = tools::forEachTrackingFrame(
        bag, video, truth_csv, max_frames > 0 ? static_cast<int>(start_frame + max_frames) : 0,
        [&](const tools::TrackingFrameIn& f) {
          if (f.index < start_frame) return;
          ++frames;
          if (f.index == start_frame) {
            const std::optional<cv::Rect2d> start = init ? init : f.truth;
            if (!start)
              throw std::runtime_error("no --init and no ground truth on the first frame");
            const auto t0 = Clock::now();
            if (cond) cond->init(f.bgr, cv::Rect(*start));
            if (ell) ell->init(f.bgr, tracking::Ellipse::inscribed(*start));
            busy += std::chrono::duration<double>(Clock::now() - t0).count();
            camshift.init(f.bgr, cv::Rect(*start));
            return;
          }
          auto t0 = Clock::now();
          cv::Rect2d box;
          bool is_lost = false;
          double confidence = 0.0;
          tracking::Contour contour;
          if (cond) {
            const tracking::TrackingResult r = cond->track(f.bgr);
            box = r.box;
            is_lost = r.lost;
            confidence = r.best.weight;
            contour = r.contour;
          } else {
            const tracking::EllipseResult r = ell->track(f.bgr);
            box = r.ellipse.box();
            is_lost = r.lost;
            confidence = r.intersection;
            contour = tracking::ellipseContour(r.ellipse.cx, r.ellipse.cy, r.ellipse.ax,
                                               r.ellipse.ay, 48);
          }
          busy += std::chrono::duration<double>(Clock::now() - t0).count();
          t0 = Clock::now();
          const cv::Rect2d cam = camshift.track(f.bgr);
          cam_busy += std::chrono::duration<double>(Clock::now() - t0).count();
          lost += is_lost;
          double a = -1, b = -1;
          if (f.truth) {
            a = is_lost ? 0.0 : iou(box, *f.truth);
            b = iou(cam, *f.truth);
            iou_sum += a;
            cam_sum += b;
            success += a >= 0.5;
            cam_success += b >= 0.5;
            ++scored;
            plot_f.push_back(f.index);
            plot_a.push_back(a);
            plot_b.push_back(b);
          }
          csv << f.index << "," << a << "," << b << "," << is_lost << "," << confidence << "\n";
          cv::Mat over = f.bgr.clone();
          if (f.truth) cv::rectangle(over, cv::Rect(*f.truth), cv::Scalar(255, 255, 255), 1);
          cv::rectangle(over, cv::Rect(cam), cv::Scalar(200, 0, 200), 1);
          std::vector<cv::Point> poly;
          for (const auto& p : contour)
            poly.emplace_back(static_cast<int>(std::lround(p.x())),
                              static_cast<int>(std::lround(p.y())));
          if (!poly.empty())
            cv::polylines(over, poly, true, is_lost ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 220, 0),
                          2);
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
          if (overlays.size() > 2000) overlays.erase(overlays.begin() + 1);  // bound memory
        });
    (void)total;
    if (frames < 2) throw std::runtime_error("fewer than two frames from --start_frame on");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double scored_d = scored > 0 ? static_cast<double>(scored) : nan;
    // Six frames evenly over the run.
    std::vector<cv::Mat> picks;
    for (int k = 0; k < 6 && !overlays.empty(); ++k)
      picks.push_back(overlays[std::min(overlays.size() - 1, k * (overlays.size() - 1) / 5)]);
    cv::Mat strip, top, bottom;
    if (picks.size() == 6) {
      cv::hconcat(std::vector<cv::Mat>(picks.begin(), picks.begin() + 3), top);
      cv::hconcat(std::vector<cv::Mat>(picks.begin() + 3, picks.end()), bottom);
      cv::vconcat(top, bottom, strip);
      cv::imwrite((fs::path(output) / "strip.png").string(), strip);
    }
    cv::imwrite((fs::path(output) / "iou.png").string(),
                plotIou(plot_f, plot_a, plot_b,
                        (bag.empty() ? fs::path(video) : fs::path(bag)).filename().string() + " (" +
                            mode + ")"));
    const double fps = (frames) / std::max(busy, 1e-9);
    const double cam_fps = (frames - 1) / std::max(cam_busy, 1e-9);
    std::printf(
        "evaluate_tracking: mode=%s mean_iou=%.3f success_rate=%.3f lost_frames=%ld fps=%.1f "
        "camshift_mean_iou=%.3f camshift_success_rate=%.3f camshift_fps=%.1f frames=%ld\n",
        mode.c_str(), iou_sum / scored_d, success / scored_d, lost, fps, cam_sum / scored_d,
        cam_success / scored_d, cam_fps, frames);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_tracking: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
