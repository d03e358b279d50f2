#include "adaptive_perception/slam/monobot.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/math/kalman_filter.h"
#include "adaptive_perception/slam/observability.h"

namespace adaptive_perception::slam {

void MonobotConfig::validate() const {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("MonobotConfig: " + what);
  };
  check(steps >= 1, "steps must be >= 1");
  check(landmarks >= 1, "landmarks must be >= 1");
  for (double v :
       {initial_robot_std_m, motion_noise_fraction, min_motion_std_m, range_noise_fraction})
    check(v >= 0.0 && std::isfinite(v), "noise parameters must be finite and >= 0");
  check(min_range_std_m > 0.0 && external_std_m > 0.0,
        "min_range_std_m and external_std_m must be > 0 (a noise-free sensor has no S^-1)");
}

MonobotRun runMonobot(const MonobotConfig& c, Variant model, math::Rng& rng) {
  c.validate();
  const int n = c.landmarks, dim = 1 + n;
  const bool extra = model != Variant::kStandard;  // the z0 row
  auto path = [&](int k) {
    return c.start_m + c.amplitude_m * (1.0 - std::cos(2.0 * M_PI * k / c.steps));
  };
  auto range_sd = [&](double dist) {
    return c.range_noise_fraction * std::fabs(dist) + c.min_range_std_m;
  };

  MonobotRun run;
  FisherInformation fisher(dim);
  double true_r = c.start_m + rng.gaussian(0.0, c.initial_robot_std_m);
  // Initialisation: the first observation of each landmark, x_f = x_r + z.
  Eigen::VectorXd mean(dim);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(dim, dim);
  mean[0] = c.start_m;
  cov(0, 0) = c.initial_robot_std_m * c.initial_robot_std_m;
  double z1 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double sd = range_sd(c.landmark_m - true_r);
    const double z = c.landmark_m - true_r + rng.gaussian(0.0, sd);
    if (i == 0) z1 = z;
    mean[1 + i] = mean[0] + z;
    cov(1 + i, 0) = cov(0, 1 + i) = cov(0, 0);
    for (int j = 0; j <= i; ++j) cov(1 + i, 1 + j) = cov(1 + j, 1 + i) = cov(0, 0);
    cov(1 + i, 1 + i) += sd * sd;
  }
  math::KalmanFilter kf(mean, cov);
  run.first_observation_error_m = mean[1] - c.landmark_m;
  run.initial_robot_error_m = true_r - c.start_m;
  MonobotStep s0;
  s0.true_robot_m = true_r;
  s0.est_robot_m = mean[0];
  s0.robot_var = cov(0, 0);
  s0.measurement_m = z1;
  s0.est_landmark_m = mean[1];
  s0.landmark_var = cov(1, 1);
  run.steps.push_back(s0);

  // Measurement model: rows (z0 if any), then one per landmark.
  const int m = n + (extra ? 1 : 0);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m, dim);
  if (extra) h(0, 0) = model == Variant::kAnchor ? -1.0 : 1.0;
  for (int i = 0; i < n; ++i) {
    h(m - n + i, 0) = -1.0;
    h(m - n + i, 1 + i) = 1.0;
  }
  for (int k = 1; k <= c.steps; ++k) {
    const double u = path(k) - path(k - 1);
    const double q_sd = c.motion_noise_fraction * std::fabs(u) + c.min_motion_std_m;
    true_r += u + rng.gaussian(0.0, q_sd);
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(dim, dim);
    q(0, 0) = q_sd * q_sd;
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(dim, dim);
    Eigen::VectorXd shifted = kf.mean();
    shifted[0] += u;
    kf.reset(shifted, kf.cov());
    kf.predict(a, q);

    Eigen::VectorXd z(m);
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(m, m);
    if (extra) {
      const bool anchor = model == Variant::kAnchor;
      const double sd = anchor ? range_sd(c.anchor_m - true_r) : c.external_std_m;
      z[0] = (anchor ? c.anchor_m - true_r : true_r) + rng.gaussian(0.0, sd);
      // The model of the anchor row is z0 - anchor = -x_r: move the known offset to z.
      if (anchor) z[0] -= c.anchor_m;
      w(0, 0) = sd * sd;
    }
    for (int i = 0; i < n; ++i) {
      const double sd = range_sd(c.landmark_m - true_r);
      z[m - n + i] = c.landmark_m - true_r + rng.gaussian(0.0, sd);
      w(m - n + i, m - n + i) = sd * sd;
    }
    const Eigen::MatrixXd s = h * kf.cov() * h.transpose() + w;
    const Eigen::MatrixXd gain = kf.cov() * h.transpose() * s.inverse();
    fisher.add(h, s);
    kf.update(h, z, w);
    MonobotStep st;
    st.true_robot_m = true_r;
    st.est_robot_m = kf.mean()[0];
    st.robot_var = kf.cov()(0, 0);
    st.measurement_m = z[m - n];
    st.est_landmark_m = kf.mean()[1];
    st.landmark_var = kf.cov()(1, 1);
    st.robot_gain = gain(0, m - n);
    st.landmark_gain = gain(1, m - n);
    run.steps.push_back(st);
  }
  run.fisher = fisher.matrix();
  return run;
}

}  // namespace adaptive_perception::slam
