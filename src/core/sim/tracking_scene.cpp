#include "adaptive_perception/sim/tracking_scene.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::sim {

const config::EnumNames<TrackingScenario>& trackingScenarios() {
  static const config::EnumNames<TrackingScenario> names(
      "scenario", {{TrackingScenario::kCircles, "circles"},
                   {TrackingScenario::kLambertianRectangle, "lambertian_rectangle"},
                   {TrackingScenario::kDistractor, "distractor"},
                   {TrackingScenario::kHandheld, "handheld"},
                   {TrackingScenario::kTeam, "team"},
                   {TrackingScenario::kSprint, "sprint"}});
  return names;
}

TrackingScenario parseTrackingScenario(const std::string& name) {
  return trackingScenarios().parse(name);
}
std::string trackingScenarioName(TrackingScenario s) { return trackingScenarios().name(s); }
std::vector<std::string> trackingScenarioNames() { return trackingScenarios().names(); }

TrackingScene::TrackingScene(TrackingSceneConfig config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
  const int w = config_.width, h = config_.height;
  const double s = std::min(w, h) / 240.0;  // sizes scale with the image
  // Background: a soft vertical gradient and, with clutter, muted boxes and blobs.
  background_.create(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    background_.row(y).setTo(cv::Scalar(70 + 40.0 * y / h, 80 + 20.0 * y / h, 75));
  if (config_.clutter) {
    for (int i = 0; i < 40; ++i) {
      // One draw per statement: the order of arguments is the compiler's, a statement's is not.
      // (Each statement draws in the order the scenes behind the figures were made in.)
      const double c2 = rng_.uniform(40, 150), c1 = rng_.uniform(60, 180),
                   c0 = rng_.uniform(40, 200);
      const cv::Scalar c(c0, c1, c2);
      const int py = rng_.uniformInt(0, h - 1), px = rng_.uniformInt(0, w - 1);
      const cv::Point p(px, py);
      const int a = static_cast<int>(rng_.uniform(5, 30) * s),
                b = static_cast<int>(rng_.uniform(5, 30) * s);
      if (rng_.bernoulli(0.5))
        cv::rectangle(background_, cv::Rect(p.x, p.y, a, b), c, cv::FILLED);
      else
        cv::ellipse(background_, p, cv::Size(a / 2 + 1, b / 2 + 1), rng_.uniform(0, 180), 0, 360, c,
                    cv::FILLED);
    }
    cv::GaussianBlur(background_, background_, cv::Size(3, 3), 0);
  }
  const double r = 22 * s;
  target_ = {{w * 0.3, h * 0.5}, {rng_.uniform(-2, 2) * s, rng_.uniform(-2, 2) * s}, r};
  target_rgb_ = {200, 60, 50};  // reddish to start
  if (config_.scenario == TrackingScenario::kCircles) {
    const cv::Scalar colors[3] = {{200, 120, 40}, {60, 180, 60}, {180, 180, 190}};  // bgr
    for (int i = 0; i < 3; ++i) {
      others_.push_back({{rng_.uniform(0.2, 0.8) * w, rng_.uniform(0.2, 0.8) * h},
                         {rng_.uniform(-2, 2) * s, rng_.uniform(-2, 2) * s},
                         rng_.uniform(14, 24) * s});
      other_colors_.push_back(colors[i]);
    }
  }
  if (config_.scenario == TrackingScenario::kDistractor) {
    // The square enters from the right and crosses the whole image in the run's middle half.
    const double speed = (w + 4 * r) / (0.5 * config_.frames);
    distractor_ = {{w + 2 * r - speed * (-0.25 * config_.frames), h * 0.5}, {-speed, 0.0}, r * 0.9};
  }
  if (config_.scenario == TrackingScenario::kTeam) {
    // A narrow player (14 x 48 px at 320 x 240) and three teammates in the same kit; only the
    // skin and hair differ a little. The first teammate crosses the whole image in the run's
    // middle half, in front of the target; the others wander.
    const double half_height = 24 * s;
    target_ = {{w * 0.3, h * 0.6}, {rng_.uniform(-1, 1) * s, 0.0}, half_height};
    target_rgb_ = {170, 125, 95};  // the target's skin (r, g, b)
    const double speed = (w + 4 * half_height) / (0.5 * config_.frames);
    others_.push_back(
        {{w + 2 * half_height + speed * 0.25 * config_.frames, h * 0.6}, {-speed, 0.0},
         half_height});
    for (int i = 0; i < 2; ++i) {
      const double x = rng_.uniform(0.5, 0.9) * w;
      const double y = rng_.uniform(0.4, 0.8) * h;
      others_.push_back({{x, y}, {rng_.uniform(-1, 1) * s, 0.0}, half_height});
    }
    for (int i = 0; i < 3; ++i) {
      const double r = rng_.uniform(150, 190);
      other_colors_.push_back(cv::Scalar(r * 0.55, r * 0.72, r));  // skin (b, g, r)
    }
  }
  if (config_.scenario == TrackingScenario::kSprint) {
    // The scene the camera pans along: the background and its mirror image, four frames wide.
    cv::Mat flipped;
    cv::flip(background_, flipped, 1);
    cv::hconcat(std::vector<cv::Mat>{background_, flipped, background_, flipped}, world_);
    const double half_height = 24 * s;
    const double speed = 3.5 * s;  // px a frame: 105 px/s at 30 Hz
    target_ = {{w * 0.5, h * 0.6}, {speed, 0.0}, half_height};
    target_rgb_ = {170, 125, 95};
    // Three runners in the next lanes, a little faster or slower: they pass and are passed.
    const double lane[3] = {-14, 12, -26}, start[3] = {-60, 40, -120}, pace[3] = {1.08, 0.94, 1.12};
    for (int i = 0; i < 3; ++i) {
      others_.push_back({{target_.pos.x + start[i] * s, target_.pos.y + lane[i] * s},
                         {speed * pace[i], 0.0}, half_height});
      const double r = rng_.uniform(150, 190);
      other_colors_.push_back(cv::Scalar(r * 0.55, r * 0.72, r));
    }
    pan_ = {target_.pos.x - 0.5 * w, 0.0};
    pan_vel_ = {0, 0};
    shake_ = {0, 0};
  }
  if (config_.scenario == TrackingScenario::kHandheld) {
    // A textured scene twice the frame: fine blurred noise under blobs of a small palette that
    // the card shares, so that its colours alone do not single it out.
    const cv::Scalar palette[4] = {{60, 70, 170}, {150, 120, 60}, {90, 160, 150}, {200, 200, 190}};
    world_.create(2 * h, 2 * w, CV_8UC3);
    cv::Mat noise(world_.size(), CV_8UC3);
    cv::RNG cv_rng(rng_.split());
    cv_rng.fill(noise, cv::RNG::UNIFORM, 40, 200);
    cv::GaussianBlur(noise, world_, cv::Size(), 1.5 * s);
    for (int i = 0; i < 160; ++i) {
      const int py = rng_.uniformInt(0, 2 * h - 1), px = rng_.uniformInt(0, 2 * w - 1);
      const int ah = static_cast<int>(rng_.uniform(4, 26) * s),
                aw = static_cast<int>(rng_.uniform(4, 26) * s);
      const int colour = rng_.uniformInt(0, 3);
      const double angle_deg = rng_.uniform(0, 180);
      cv::ellipse(world_, {px, py}, {aw, ah}, angle_deg, 0, 360, palette[colour], cv::FILLED,
                  cv::LINE_AA);
    }
    // The card: two of the palette's colours in stripes and spots, with a dark border.
    card_.create(static_cast<int>(44 * s), static_cast<int>(60 * s), CV_8UC3);
    card_.setTo(palette[0]);
    for (int x = 0; x < card_.cols; x += std::max(1, static_cast<int>(12 * s)))
      cv::rectangle(card_, cv::Rect(x, 0, std::max(1, static_cast<int>(5 * s)), card_.rows),
                    palette[3], cv::FILLED);
    for (int i = 0; i < 6; ++i)
      cv::circle(card_, {rng_.uniformInt(0, card_.cols - 1), rng_.uniformInt(0, card_.rows - 1)},
                 static_cast<int>(5 * s), palette[1], cv::FILLED, cv::LINE_AA);
    cv::rectangle(card_, cv::Rect(0, 0, card_.cols, card_.rows), cv::Scalar(30, 30, 30),
                  std::max(1, static_cast<int>(2 * s)));
    // Its radius keeps the largest card (4/3 of 60 px wide) and the shake inside the image.
    target_ = {{w * 0.5, h * 0.5}, {rng_.uniform(-1, 1) * s, rng_.uniform(-1, 1) * s}, 46 * s};
    pan_ = {0.5 * w, 0.5 * h};
    pan_vel_ = {0, 0};
    shake_ = {0, 0};
  }
}

SceneFrame TrackingScene::handheld(int k) {
  const int w = config_.width, h = config_.height;
  const double s = std::min(w, h) / 240.0;
  // The camera: a slow wandering pan and a hand's shake (a stiff random walk about 0).
  const cv::Point2d before = pan_ + shake_;
  pan_vel_ += drawPoint(0.25 * s);
  pan_vel_ *= std::min(1.0, 3.0 * s / std::max(1e-9, std::hypot(pan_vel_.x, pan_vel_.y)));
  pan_ += pan_vel_;
  if (pan_.x < 0 || pan_.x > w) pan_vel_.x = -pan_vel_.x;
  if (pan_.y < 0 || pan_.y > h) pan_vel_.y = -pan_vel_.y;
  pan_.x = std::clamp(pan_.x, 0.0, static_cast<double>(w));
  pan_.y = std::clamp(pan_.y, 0.0, static_cast<double>(h));
  shake_ = 0.6 * shake_ + drawPoint(2.0 * s);
  const cv::Point2d view = pan_ + shake_;
  const cv::Point2d camera_motion = view - before;
  SceneFrame f;
  const cv::Matx23d m(1, 0, -view.x, 0, 1, -view.y);
  cv::warpAffine(world_, f.bgr, cv::Mat(m), cv::Size(w, h), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  // The card wanders in the image (its own motion and the shake), its size swinging by a third.
  move(&target_, 3.0 * s);
  const double size = 1.0 + 0.33 * std::sin(2 * M_PI * k / 200.0);
  const cv::Size card(std::max(4, static_cast<int>(card_.cols * size)),
                      std::max(4, static_cast<int>(card_.rows * size)));
  const cv::Point2d centre = target_.pos + shake_;
  const cv::Rect at(static_cast<int>(std::lround(centre.x - card.width / 2.0)),
                    static_cast<int>(std::lround(centre.y - card.height / 2.0)), card.width,
                    card.height);
  cv::Mat scaled;
  cv::resize(card_, scaled, card, 0, 0, cv::INTER_AREA);
  const cv::Rect inside = at & cv::Rect(0, 0, w, h);
  if (!inside.empty()) scaled(inside - at.tl()).copyTo(f.bgr(inside));
  f.truth = cv::Rect2d(at);
  blurAlong(&f.bgr, camera_motion);
  // The light: from 0.4 of full up to 1.15 and back over the run, warmer (less blue) when dim.
  const double light = 0.4 + 0.75 * (0.5 - 0.5 * std::cos(2 * M_PI * k / config_.frames));
  const double warm = 1.0 - light;
  f.bgr.convertTo(f.bgr, CV_8UC3);
  std::vector<cv::Mat> ch;
  cv::split(f.bgr, ch);
  ch[0].convertTo(ch[0], CV_8U, light * (1.0 - 0.35 * warm));  // blue
  ch[1].convertTo(ch[1], CV_8U, light * (1.0 - 0.1 * warm));
  ch[2].convertTo(ch[2], CV_8U, light);
  cv::merge(ch, f.bgr);
  return f;
}

void TrackingScene::blurAlong(cv::Mat* bgr, const cv::Point2d& camera_motion) {
  // Motion blur along the camera's motion this frame (the exposure's share of it).
  const double length = 0.8 * std::hypot(camera_motion.x, camera_motion.y);
  if (length <= 1.5) return;
  const int n = static_cast<int>(std::ceil(length)) | 1;
  cv::Mat kernel = cv::Mat::zeros(n, n, CV_32F);
  const double a = std::atan2(camera_motion.y, camera_motion.x);
  cv::line(kernel,
           cv::Point(static_cast<int>(n / 2 - std::cos(a) * n / 2),
                     static_cast<int>(n / 2 - std::sin(a) * n / 2)),
           cv::Point(static_cast<int>(n / 2 + std::cos(a) * n / 2),
                     static_cast<int>(n / 2 + std::sin(a) * n / 2)),
           cv::Scalar(1.0));
  kernel /= std::max(1e-9, cv::sum(kernel)[0]);
  cv::filter2D(*bgr, *bgr, -1, kernel, cv::Point(-1, -1), 0, cv::BORDER_REFLECT);
}

SceneFrame TrackingScene::sprint(int k) {
  const int w = config_.width, h = config_.height;
  const double s = std::min(w, h) / 240.0;
  // The runners: steady paces with a little jitter, no turning back.
  target_.pos += target_.vel + drawPoint(0.3 * s);
  target_.pos.y = std::clamp(target_.pos.y, 0.45 * h, 0.75 * h);
  for (Mover& m : others_) {
    m.pos += m.vel + drawPoint(0.3 * s);
    m.pos.y = std::clamp(m.pos.y, 0.35 * h, 0.8 * h);
  }
  // The camera pans after the target, lagging, with a hand's shake.
  const cv::Point2d before = pan_ + shake_;
  pan_.x += 0.15 * (target_.pos.x - 0.5 * w - pan_.x);
  pan_.x = std::clamp(pan_.x, 0.0, static_cast<double>(world_.cols - w));
  shake_ = 0.6 * shake_ + drawPoint(1.0 * s);
  const cv::Point2d view = pan_ + shake_;
  SceneFrame f;
  const cv::Matx23d m(1, 0, -view.x, 0, 1, -view.y);
  cv::warpAffine(world_, f.bgr, cv::Mat(m), cv::Size(w, h), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  f.truth = drawPlayers(&f.bgr, view, 0.6 * k);  // a runner's stride
  blurAlong(&f.bgr, view - before);
  return f;
}

cv::Rect2d TrackingScene::drawPlayers(cv::Mat* bgr, const cv::Point2d& view, double phase) {
  // Nearer players (lower in the image) are drawn last, over the others.
  std::vector<std::pair<double, int>> order{{target_.pos.y, -1}};
  for (size_t i = 0; i < others_.size(); ++i)
    order.emplace_back(others_[i].pos.y, static_cast<int>(i));
  std::sort(order.begin(), order.end());
  cv::Rect2d truth;
  for (const auto& [y, i] : order) {
    if (i < 0) {
      truth = drawPlayer(bgr, target_.pos - view, target_.radius,
                         cv::Scalar(target_rgb_[2], target_rgb_[1], target_rgb_[0]), phase);
    } else {
      drawPlayer(bgr, others_[i].pos - view, others_[i].radius, other_colors_[i], phase + i);
    }
  }
  return truth;
}

cv::Rect2d TrackingScene::drawPlayer(cv::Mat* bgr, const cv::Point2d& centre, double half_height,
                                     const cv::Scalar& skin, double phase) {
  // Head (hair on top), shirt, shorts, two legs swinging with the walk, shoes: the team's kit.
  const cv::Scalar shirt(30, 190, 235), shorts(110, 40, 25), hair(30, 30, 40), shoe(20, 20, 20);
  const double H = 2 * half_height, W = 0.3 * H, top = centre.y - half_height;
  auto px = [](double v) { return static_cast<int>(std::lround(v)); };
  auto rect = [&](double x0, double y0, double x1, double y1, const cv::Scalar& c) {
    cv::rectangle(*bgr, cv::Point(px(x0), px(y0)), cv::Point(px(x1), px(y1)), c, cv::FILLED,
                  cv::LINE_AA);
  };
  const cv::Point head(px(centre.x), px(top + 0.1 * H));
  const int head_r = std::max(1, static_cast<int>(std::lround(0.1 * H)));
  cv::circle(*bgr, head, head_r, skin, cv::FILLED, cv::LINE_AA);
  cv::ellipse(*bgr, head, cv::Size(head_r, head_r), 0, 180, 360, hair, cv::FILLED, cv::LINE_AA);
  const double swing = 0.06 * H * std::sin(phase);
  for (int side = -1; side <= 1; side += 2) {
    const double x = centre.x + side * 0.22 * W + side * swing;
    rect(x - 0.13 * W, top + 0.7 * H, x + 0.13 * W, top + 0.95 * H, skin);
    rect(x - 0.16 * W, top + 0.95 * H, x + 0.16 * W, top + H, shoe);
  }
  rect(centre.x - 0.5 * W, top + 0.2 * H, centre.x + 0.5 * W, top + 0.58 * H, shirt);
  rect(centre.x - 0.45 * W, top + 0.58 * H, centre.x + 0.45 * W, top + 0.72 * H, shorts);
  return {centre.x - 0.5 * W, top, W, H};
}

cv::Point2d TrackingScene::drawPoint(double sd) {
  const double y = rng_.gaussian(0, sd);  // y first: the order the scenes were made in
  const double x = rng_.gaussian(0, sd);
  return {x, y};
}

void TrackingScene::move(Mover* m, double max_speed) {
  // A smoothly wandering velocity, bouncing off the borders.
  m->vel += drawPoint(0.3);
  const double v = std::hypot(m->vel.x, m->vel.y);
  if (v > max_speed) m->vel *= max_speed / v;
  m->pos += m->vel;
  const double lo = m->radius + 2, hx = config_.width - m->radius - 2,
               hy = config_.height - m->radius - 2;
  if (m->pos.x < lo || m->pos.x > hx) m->vel.x = -m->vel.x;
  if (m->pos.y < lo || m->pos.y > hy) m->vel.y = -m->vel.y;
  m->pos.x = std::clamp(m->pos.x, lo, hx);
  m->pos.y = std::clamp(m->pos.y, lo, hy);
}

SceneFrame TrackingScene::next() {
  if (done()) throw std::out_of_range("TrackingScene::next: past the last frame");
  const double s = std::min(config_.width, config_.height) / 240.0;
  SceneFrame f;
  f.bgr = background_.clone();
  const int k = index_++;
  auto pt = [](const cv::Point2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  };
  switch (config_.scenario) {
    case TrackingScenario::kHandheld:
      f = handheld(k);
      break;
    case TrackingScenario::kSprint:
      f = sprint(k);
      break;
    case TrackingScenario::kTeam: {
      move(&target_, 2.0 * s);
      target_.vel.y *= 0.5;  // players run across the image more than up and down it
      others_[0].pos += others_[0].vel;  // the crossing one, a little nearer than the target
      others_[0].pos.y += 0.1 * (target_.pos.y + 4 * s - others_[0].pos.y);
      for (size_t i = 1; i < others_.size(); ++i) {
        move(&others_[i], 2.0 * s);
        others_[i].vel.y *= 0.5;
      }
      f.truth = drawPlayers(&f.bgr, {0.0, 0.0}, 0.35 * k);  // a walker's stride
      break;
    }
    case TrackingScenario::kCircles: {
      for (size_t i = 0; i < others_.size(); ++i) {
        move(&others_[i], 3.0 * s);
        cv::circle(f.bgr, pt(others_[i].pos), static_cast<int>(others_[i].radius), other_colors_[i],
                   cv::FILLED, cv::LINE_AA);
      }
      move(&target_, 3.0 * s);
      for (int c = 0; c < 3; ++c)  // the colour changes randomly
        target_rgb_[c] = std::clamp(target_rgb_[c] + rng_.gaussian(0, 3.0), 30.0, 235.0);
      cv::circle(f.bgr, pt(target_.pos), static_cast<int>(target_.radius),
                 cv::Scalar(target_rgb_[2], target_rgb_[1], target_rgb_[0]), cv::FILLED,
                 cv::LINE_AA);
      const double r = static_cast<int>(target_.radius);
      f.truth = {target_.pos.x - r, target_.pos.y - r, 2 * r + 1, 2 * r + 1};
      break;
    }
    case TrackingScenario::kLambertianRectangle: {
      // The light at the image centre; the rectangle on an orbit around it, facing it.
      const cv::Point2d light(config_.width / 2.0, config_.height / 2.0);
      cv::circle(f.bgr, pt(light), static_cast<int>(10 * s), cv::Scalar(200, 245, 255), cv::FILLED,
                 cv::LINE_AA);
      const double period = 240.0;
      const double a = 2 * M_PI * k / period;
      const double orbit = 75 * s;
      const cv::Point2d c = light + orbit * cv::Point2d(std::cos(a), 0.8 * std::sin(a));
      // Its normal turns away from the light and back once per orbit: the reflected light runs
      // from 0.25 to 1 of full, and the colour of the light warms as it dims.
      const double facing = 0.25 + 0.75 * (0.5 + 0.5 * std::cos(a));
      const cv::Vec3d albedo(0.85, 0.3, 0.22);  // reddish (r, g, b)
      const cv::Vec3d light_rgb(1.0, 0.85 + 0.15 * facing, 0.7 + 0.3 * facing);
      const cv::Size2d size(64 * s, 38 * s);
      const cv::RotatedRect rr(cv::Point2f(c), cv::Size2f(size),
                               static_cast<float>(a * 180 / M_PI));
      cv::Point2f corners[4];
      rr.points(corners);
      std::vector<cv::Point> poly(corners, corners + 4);
      cv::Mat mask = cv::Mat::zeros(f.bgr.size(), CV_8U);
      cv::fillConvexPoly(mask, poly, cv::Scalar(255), cv::LINE_AA);
      const cv::Rect box = cv::boundingRect(poly) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
      for (int y = box.y; y < box.y + box.height; ++y)
        for (int x = box.x; x < box.x + box.width; ++x) {
          const double m = mask.at<uchar>(y, x) / 255.0;
          if (m <= 0) continue;
          // Shading across the surface: brighter nearer the light.
          const double d = std::hypot(x - light.x, y - light.y);
          const double shade = std::clamp(1.25 - 0.5 * d / orbit, 0.5, 1.2);
          cv::Vec3b& px = f.bgr.at<cv::Vec3b>(y, x);
          for (int ch = 0; ch < 3; ++ch) {
            const double v = 255.0 * albedo[2 - ch] * light_rgb[2 - ch] * facing * shade;
            px[ch] = cv::saturate_cast<uchar>(m * v + (1 - m) * px[ch]);
          }
        }
      const cv::Rect2f bb = rr.boundingRect2f();
      f.truth = bb;
      break;
    }
    case TrackingScenario::kDistractor: {
      move(&target_, 2.0 * s);
      for (int c = 0; c < 3; ++c)  // a slow drift
        target_rgb_[c] = std::clamp(target_rgb_[c] + rng_.gaussian(0, 1.0), 30.0, 235.0);
      const cv::Scalar color(target_rgb_[2], target_rgb_[1], target_rgb_[0]);
      // The square follows the target's height so it passes close by, drawn behind it.
      distractor_.pos += distractor_.vel;
      distractor_.pos.y += 0.1 * (target_.pos.y + 2.1 * target_.radius - distractor_.pos.y);
      const double h = distractor_.radius;
      cv::rectangle(f.bgr,
                    cv::Rect(pt(distractor_.pos - cv::Point2d(h, h)),
                             cv::Size(static_cast<int>(2 * h), static_cast<int>(2 * h))),
                    color, cv::FILLED);
      cv::circle(f.bgr, pt(target_.pos), static_cast<int>(target_.radius), color, cv::FILLED,
                 cv::LINE_AA);
      const double r = static_cast<int>(target_.radius);
      f.truth = {target_.pos.x - r, target_.pos.y - r, 2 * r + 1, 2 * r + 1};
      break;
    }
  }
  if (config_.noise_sd > 0) {
    cv::Mat noise(f.bgr.size(), CV_16SC3), wide;
    cv::RNG cv_rng(rng_.split());  // seeded from the scene's stream, not OpenCV's global one
    cv_rng.fill(noise, cv::RNG::NORMAL, 0, config_.noise_sd);
    f.bgr.convertTo(wide, CV_16SC3);
    wide += noise;
    wide.convertTo(f.bgr, CV_8UC3);
  }
  return f;
}

}  // namespace adaptive_perception::sim
