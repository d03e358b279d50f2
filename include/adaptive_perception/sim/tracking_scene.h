#pragma once
// Synthetic tracking sequences with ground truth (papers/001 section 3.4, Figs 8 and 13):
//   circles               a circle moving around whose colour changes randomly (a random walk
//                         in RGB), among other moving circles of other colours (experiment 1);
//   lambertian_rectangle  a reddish Lambertian rectangle revolving around a light source: its
//                         brightness and shading follow its angle to the light, and it turns in
//                         the image as it goes round (experiment 2, Fig 8);
//   distractor            a circle whose colour drifts slowly, and a square of the same colour
//                         (another shape) crossing its path;
//   handheld              what real video does to a tracker, for tests that may not use the
//                         benchmarks' frames: a patterned card (its colours also in the
//                         background) wandering and growing and shrinking by a third, seen by a
//                         panning, shaking camera over a textured scene, in light that ramps from
//                         dim to bright and back (its colour warming as it dims), with motion blur
//                         along the camera's motion;
//   team                  a narrow upright player (14 x 48 px at 320 x 240) among three
//                         teammates in the same kit (only skin and hair differ a little), one of
//                         them crossing in front of the target in the run's middle half: the
//                         unseen benchmark sequences' collapse (a player among players);
//   sprint                runners in the same kit in neighbouring lanes, a little faster or
//                         slower than the target, passing it; the camera pans after the target
//                         (lagging, shaking, motion blur) over a scene four frames wide.
// All scenes have a cluttered static background (boxes and blobs of muted colours) and camera
// noise. The ground truth is the target's axis-aligned bounding box. The same seed gives the same
// frames.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::sim {

enum class TrackingScenario { kCircles, kLambertianRectangle, kDistractor, kHandheld, kTeam,
                              kSprint };
/// "circles" | "lambertian_rectangle" | "distractor" | "handheld" | "team" | "sprint"; throws
/// std::invalid_argument naming them.
const config::EnumNames<TrackingScenario>& trackingScenarios();
TrackingScenario parseTrackingScenario(const std::string& name);
std::string trackingScenarioName(TrackingScenario s);
std::vector<std::string> trackingScenarioNames();

struct TrackingSceneConfig {
  TrackingScenario scenario = TrackingScenario::kCircles;
  int width = 320, height = 240;  // pixels
  int frames = 300;
  double rate_hz = 30.0;  // frame rate
  double noise_sd = 4.0;  // camera noise, grey levels
  bool clutter = true;    // background boxes and blobs
  /// The numeric fields' names, ranges and docs (config/fields.h), as simulate_tracking's and
  /// bench_tracker's options name them; defined in sim_configs.cpp.
  static const config::Fields<TrackingSceneConfig>& fields();
  void validate() const { fields().validate(*this); }  // names the first field out of range
};

struct SceneFrame {
  cv::Mat bgr;       // bgr8
  cv::Rect2d truth;  // target's bounding box, pixels
};

class TrackingScene {
 public:
  TrackingScene(TrackingSceneConfig config, std::uint64_t seed);
  /// The next frame (frames are generated in order; at most config.frames of them).
  SceneFrame next();
  bool done() const { return index_ >= config_.frames; }
  int index() const { return index_; }
  const TrackingSceneConfig& config() const { return config_; }

 private:
  struct Mover {
    cv::Point2d pos, vel;
    double radius;
  };
  void move(Mover* m, double max_speed);
  /// A zero-mean Gaussian step in x and y with standard deviation `sd` on each axis.
  cv::Point2d drawPoint(double sd);
  TrackingSceneConfig config_;
  math::Rng rng_;
  cv::Mat background_;
  int index_ = 0;
  Mover target_;
  std::vector<Mover> others_;
  std::vector<cv::Scalar> other_colors_;
  cv::Vec3d target_rgb_;
  Mover distractor_;
  // handheld: the scene the camera pans over (larger than a frame), the card, the camera.
  cv::Mat world_, card_;
  cv::Point2d pan_, pan_vel_, shake_;
  SceneFrame handheld(int k);
  /// sprint: the runners move on, the camera pans after the target.
  SceneFrame sprint(int k);
  /// Motion blur along the camera's motion in the frame (0.8 of it: the exposure's share).
  static void blurAlong(cv::Mat* bgr, const cv::Point2d& camera_motion);
  /// team: one player of half height `half_height` centred at `centre`, legs at walking phase
  /// `phase` (rad); returns the player's bounding box.
  cv::Rect2d drawPlayer(cv::Mat* bgr, const cv::Point2d& centre, double half_height,
                        const cv::Scalar& skin, double phase);
  /// team, sprint: the target and the others, nearer (lower) ones over farther ones, seen from
  /// `view` (the camera's offset in the scene); returns the target's box.
  cv::Rect2d drawPlayers(cv::Mat* bgr, const cv::Point2d& view, double phase);
};

}  // namespace adaptive_perception::sim
