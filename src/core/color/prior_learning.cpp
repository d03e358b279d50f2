#include "adaptive_perception/color/prior_learning.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

void PriorLearningConfig::validate() const {
  if (max_iterations < 1) throw std::invalid_argument("max_iterations must be >= 1");
  if (!(tolerance > 0.0)) throw std::invalid_argument("tolerance must be > 0");
  if (!(hyper_prior_dof > 0.0)) throw std::invalid_argument("hyper_prior_dof must be > 0");
  if (!(hyper_prior_std > 0.0)) throw std::invalid_argument("hyper_prior_std must be > 0");
}

Eigen::Vector3d pooledPixelNoise(const std::vector<LightingDataSet>& sets) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double n = 0.0;
  for (const auto& s : sets)
    for (const auto& f : s.frames)
      for (size_t k = 0; k < f.counts.size(); ++k) {
        if (f.counts[k] < 2) continue;
        sum += f.counts[k] * f.variances[k];
        n += f.counts[k];
      }
  if (n == 0.0) return {25.0, 9.0, 9.0};
  return (sum / n).cwiseMax(1.0);
}

Eigen::MatrixXd lumaFeatures(const std::vector<LightingDataSet>& sets,
                             const ColorModelConfig& config) {
  const int m = config.numColors();
  Eigen::MatrixXd f =
      Eigen::MatrixXd::Constant(sets.size(), m, std::numeric_limits<double>::quiet_NaN());
  for (size_t j = 0; j < sets.size(); ++j) {
    for (int k = 0; k < m; ++k) {
      double sum = 0.0;
      int n = 0;
      for (const auto& fr : sets[j].frames)
        if (k < static_cast<int>(fr.counts.size()) && fr.counts[k] >= config.min_pixels_per_color) {
          sum += fr.means[k][0];
          ++n;
        }
      if (n > 0) f(j, k) = sum / n;
    }
  }
  for (int k = 0; k < m; ++k) {  // fill colours a set never shows with the mean over sets
    double sum = 0.0;
    int n = 0;
    for (int j = 0; j < f.rows(); ++j)
      if (!std::isnan(f(j, k))) {
        sum += f(j, k);
        ++n;
      }
    for (int j = 0; j < f.rows(); ++j)
      if (std::isnan(f(j, k))) f(j, k) = n ? sum / n : 128.0;
  }
  return f;
}

std::vector<int> kMeans(const Eigen::MatrixXd& x, int k, std::uint64_t seed) {
  const int n = static_cast<int>(x.rows());
  if (k < 1 || k > n)
    throw std::invalid_argument("kMeans: k = " + std::to_string(k) + " with " + std::to_string(n) +
                                " points");
  math::Rng rng(seed);
  // k-means++ seeding.
  std::vector<Eigen::VectorXd> centres{x.row(rng.uniformInt(0, n - 1)).transpose()};
  while (static_cast<int>(centres.size()) < k) {
    std::vector<double> d2(n);
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& c : centres) best = std::min(best, (x.row(i).transpose() - c).squaredNorm());
      d2[i] = best;
      total += best;
    }
    double u = rng.uniform(0.0, total);
    int pick = n - 1;
    for (int i = 0; i < n; ++i) {
      if ((u -= d2[i]) <= 0.0) {
        pick = i;
        break;
      }
    }
    centres.push_back(x.row(pick).transpose());
  }
  std::vector<int> assign(n, -1);
  for (int iter = 0; iter < 200; ++iter) {
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      int best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (int c = 0; c < k; ++c) {
        const double d = (x.row(i).transpose() - centres[c]).squaredNorm();
        if (d < best_d) {
          best_d = d;
          best = c;
        }
      }
      changed |= assign[i] != best;
      assign[i] = best;
    }
    for (int c = 0; c < k; ++c) {
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(x.cols());
      int cnt = 0;
      for (int i = 0; i < n; ++i)
        if (assign[i] == c) {
          sum += x.row(i).transpose();
          ++cnt;
        }
      if (cnt > 0) centres[c] = sum / cnt;
    }
    if (!changed) break;
  }
  // Order clusters by the mean of their centre: 0 is the darkest.
  std::vector<int> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return centres[a].mean() < centres[b].mean(); });
  std::vector<int> rank(k);
  for (int r = 0; r < k; ++r) rank[order[r]] = r;
  for (int& a : assign) a = rank[a];
  return assign;
}

LightingPrior learnPrior(const std::vector<LightingDataSet>& sets, const ColorModelConfig& mc,
                         const PriorLearningConfig& config, const std::string& name) {
  mc.validate();
  config.validate();
  const int d = mc.dim();
  const Eigen::Vector3d nu = pooledPixelNoise(sets);
  // Sufficient statistics per set: a_j = sum_t 1/r_jt (precision), b_j = sum_t v_jt / r_jt.
  std::vector<Eigen::VectorXd> a, b;
  for (const auto& s : sets) {
    Eigen::VectorXd aj = Eigen::VectorXd::Zero(d), bj = Eigen::VectorXd::Zero(d);
    for (const auto& f : s.frames)
      for (int k = 0; k < mc.numColors() && k < static_cast<int>(f.counts.size()); ++k) {
        if (f.counts[k] < mc.min_pixels_per_color) continue;
        for (int ch = 0; ch < 3; ++ch) {
          const double r = observationVariance(mc, nu, f.counts[k], ch);
          aj[componentIndex(k, ch)] += 1.0 / r;
          bj[componentIndex(k, ch)] += f.means[k][ch] / r;
        }
      }
    if (aj.maxCoeff() > 0.0) {
      a.push_back(aj);
      b.push_back(bj);
    }
  }
  if (a.empty()) throw std::invalid_argument("learnPrior: no data set shows any modelled colour");
  const int n = static_cast<int>(a.size());

  // Initialise from the per-set data means.
  Eigen::VectorXd mu = Eigen::VectorXd::Constant(d, 128.0);
  Eigen::VectorXd spread = Eigen::VectorXd::Constant(d, 30.0 * 30.0);
  for (int c = 0; c < d; ++c) {
    double s = 0.0, s2 = 0.0;
    int cnt = 0;
    for (int j = 0; j < n; ++j)
      if (a[j][c] > 0) {
        const double m = b[j][c] / a[j][c];
        s += m;
        s2 += m * m;
        ++cnt;
      }
    if (cnt > 0) {
      mu[c] = s / cnt;
      if (cnt > 1) spread[c] = std::max(s2 / cnt - mu[c] * mu[c], 1.0);
    }
  }
  Eigen::MatrixXd sigma = spread.asDiagonal();
  const double kappa = config.hyper_prior_dof, s2 = config.hyper_prior_std * config.hyper_prior_std;
  for (int iter = 0; iter < config.max_iterations; ++iter) {
    const Eigen::MatrixXd sigma_inv = sigma.inverse();
    const Eigen::VectorXd sigma_inv_mu = sigma_inv * mu;
    std::vector<Eigen::VectorXd> m(n);
    std::vector<Eigen::MatrixXd> v(n);
    for (int j = 0; j < n; ++j) {
      Eigen::MatrixXd p = sigma_inv;
      p.diagonal() += a[j];
      const Eigen::LLT<Eigen::MatrixXd> llt(p);
      v[j] = llt.solve(Eigen::MatrixXd::Identity(d, d));
      m[j] = llt.solve(sigma_inv_mu + b[j]);
    }
    Eigen::VectorXd mu_new = Eigen::VectorXd::Zero(d);
    for (int j = 0; j < n; ++j) mu_new += m[j];
    mu_new /= n;
    Eigen::MatrixXd s = kappa * s2 * Eigen::MatrixXd::Identity(d, d);
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd dm = m[j] - mu_new;
      s += dm * dm.transpose() + v[j];
    }
    Eigen::MatrixXd sigma_new = s / (n + kappa);
    sigma_new = 0.5 * (sigma_new + sigma_new.transpose());
    const double change = (mu_new - mu).norm() / (mu.norm() + 1e-9) +
                          (sigma_new - sigma).norm() / (sigma.norm() + 1e-9);
    mu = mu_new;
    sigma = sigma_new;
    if (change < config.tolerance) break;
  }
  LightingPrior prior;
  prior.name = name;
  for (auto c : mc.classes) prior.color_names.push_back(world::colorClassName(c));
  prior.mean = mu;
  prior.cov = sigma;
  prior.pixel_noise_var = nu;
  return prior;
}

}  // namespace adaptive_perception::color
