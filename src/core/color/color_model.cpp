#include "adaptive_perception/color/color_model.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/io/yaml_file.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

namespace {
constexpr double kLog2Pi = 1.8378770664093454836;
}

const config::EnumNames<ObservationNoise>& observationNoises() {
  static const config::EnumNames<ObservationNoise> names(
      "observation_noise", {{ObservationNoise::kPixelNoise, "pixel"},
                            {ObservationNoise::kPixelNoiseOverCount, "pixel_over_count"}});
  return names;
}

ObservationNoise parseObservationNoise(const std::string& name) {
  return observationNoises().parse(name);
}

std::vector<std::uint8_t> ColorModelConfig::defaultClasses() {
  return {world::kGreen, world::kWhite, world::kPink, world::kYellow, world::kCyan};
}

int ColorModelConfig::colorIndex(std::uint8_t class_id) const {
  for (int k = 0; k < numColors(); ++k)
    if (classes[k] == class_id) return k;
  return -1;
}

void ColorModelConfig::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (classes.empty()) fail("classes must name at least one colour");
  for (size_t i = 0; i < classes.size(); ++i) {
    if (classes[i] >= world::kNumColorClasses)
      fail("classes[" + std::to_string(i) + "] = " + std::to_string(classes[i]) +
           " is not a map colour (0..5)");
    for (size_t j = 0; j < i; ++j)
      if (classes[i] == classes[j])
        fail("classes lists " + world::colorClassName(classes[i]) + " twice");
  }
  if (!(drift_std_per_sqrt_s >= 0.0 && drift_std_per_sqrt_s <= 100.0))
    fail("drift_std_per_sqrt_s = " + std::to_string(drift_std_per_sqrt_s) + " (allowed: 0..100)");
  if (!(observation_noise_floor_var >= 0.0 && observation_noise_floor_var <= 1e4))
    fail("observation_noise_floor_var = " + std::to_string(observation_noise_floor_var) +
         " (allowed: 0..10000)");
  if (min_pixels_per_color < 1)
    fail("min_pixels_per_color = " + std::to_string(min_pixels_per_color) + " (allowed: >= 1)");
  if (!(unknown_mahalanobis > 0.0 && std::isfinite(unknown_mahalanobis)))
    fail("unknown_mahalanobis = " + std::to_string(unknown_mahalanobis) +
         " (allowed: finite, > 0)");
}

double observationVariance(const ColorModelConfig& config, const Eigen::Vector3d& nu, int count,
                           int channel) {
  if (config.observation_noise == ObservationNoise::kPixelNoise) return nu[channel];
  return nu[channel] / std::max(1, count) + config.observation_noise_floor_var;
}

ColorObservation computeColorObservation(const cv::Mat& yuv, const cv::Mat& labels,
                                         const ColorModelConfig& config) {
  if (yuv.type() != CV_8UC3 || labels.type() != CV_8UC1 || yuv.size() != labels.size())
    throw std::invalid_argument(
        "computeColorObservation: needs CV_8UC3 YUV and CV_8UC1 labels of one size");
  std::int16_t slot[256];
  for (int i = 0; i < 256; ++i) slot[i] = -1;
  for (int k = 0; k < config.numColors(); ++k)
    slot[config.classes[k]] = static_cast<std::int16_t>(k);
  const int m = config.numColors();
  std::vector<long> n(m, 0);
  std::vector<std::array<double, 3>> sum(m, {0, 0, 0}), sum_sq(m, {0, 0, 0});
  for (int r = 0; r < yuv.rows; ++r) {
    const std::uint8_t* p = yuv.ptr<std::uint8_t>(r);
    const std::uint8_t* l = labels.ptr<std::uint8_t>(r);
    for (int c = 0; c < yuv.cols; ++c) {
      const int k = slot[l[c]];
      if (k < 0) continue;
      ++n[k];
      for (int ch = 0; ch < 3; ++ch) {
        const double v = p[3 * c + ch];
        sum[k][ch] += v;
        sum_sq[k][ch] += v * v;
      }
    }
  }
  ColorObservation obs;
  obs.counts.resize(m);
  obs.means.resize(m, Eigen::Vector3d::Zero());
  obs.variances.resize(m, Eigen::Vector3d::Zero());
  for (int k = 0; k < m; ++k) {
    obs.counts[k] = static_cast<int>(n[k]);
    if (n[k] == 0) continue;
    for (int ch = 0; ch < 3; ++ch) {
      const double mean = sum[k][ch] / n[k];
      obs.means[k][ch] = mean;
      obs.variances[k][ch] = std::max(0.0, sum_sq[k][ch] / n[k] - mean * mean);
    }
  }
  return obs;
}

// ------------------------------------------------------------------------------------------------
// LightingPrior

LightingPrior LightingPrior::loadYaml(const std::string& path) {
  const YAML::Node root = io::loadYamlFile(path, "lighting prior file");
  LightingPrior p;
  try {
    p.name =
        root["name"] ? root["name"].as<std::string>() : std::filesystem::path(path).stem().string();
    if (!root["colors"] || !root["mean"] || !root["cov"] || !root["pixel_noise_var"])
      throw std::runtime_error("needs the keys colors, mean, cov and pixel_noise_var");
    p.color_names = root["colors"].as<std::vector<std::string>>();
    const auto mean = root["mean"].as<std::vector<double>>();
    const auto cov = root["cov"].as<std::vector<std::vector<double>>>();
    const auto nu = root["pixel_noise_var"].as<std::vector<double>>();
    const size_t d = 3 * p.color_names.size();
    if (mean.size() != d)
      throw std::runtime_error("mean has " + std::to_string(mean.size()) + " values, expected " +
                               std::to_string(d));
    if (cov.size() != d)
      throw std::runtime_error("cov has " + std::to_string(cov.size()) + " rows, expected " +
                               std::to_string(d));
    if (nu.size() != 3) throw std::runtime_error("pixel_noise_var needs 3 values (Y, U, V)");
    p.mean = Eigen::Map<const Eigen::VectorXd>(mean.data(), d);
    p.cov.resize(d, d);
    for (size_t r = 0; r < d; ++r) {
      if (cov[r].size() != d)
        throw std::runtime_error("cov row " + std::to_string(r) + " has " +
                                 std::to_string(cov[r].size()) + " values");
      for (size_t c = 0; c < d; ++c) p.cov(r, c) = cov[r][c];
    }
    p.pixel_noise_var = {nu[0], nu[1], nu[2]};
    if (!p.mean.allFinite() || !p.cov.allFinite() || !p.pixel_noise_var.allFinite() ||
        p.pixel_noise_var.minCoeff() <= 0.0)
      throw std::runtime_error("non-finite values or non-positive pixel_noise_var");
    Eigen::LLT<Eigen::MatrixXd> llt(p.cov);
    if (!p.cov.isApprox(p.cov.transpose(), 1e-9) || llt.info() != Eigen::Success)
      throw std::runtime_error("cov is not symmetric positive definite");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).rfind(path, 0) == 0) throw;
    throw std::runtime_error(path + ": " + e.what());
  }
  return p;
}

void LightingPrior::saveYaml(const std::string& path) const {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << name;
  out << YAML::Key << "colors" << YAML::Value << YAML::Flow << color_names;
  out << YAML::Key << "pixel_noise_var" << YAML::Value << YAML::Flow
      << std::vector<double>{pixel_noise_var[0], pixel_noise_var[1], pixel_noise_var[2]};
  out << YAML::Key << "mean" << YAML::Value << YAML::Flow
      << std::vector<double>(mean.data(), mean.data() + mean.size());
  out << YAML::Key << "cov" << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < cov.rows(); ++r) {
    std::vector<double> row(cov.cols());
    for (int c = 0; c < cov.cols(); ++c) row[c] = cov(r, c);
    out << YAML::Flow << row;
  }
  out << YAML::EndSeq << YAML::EndMap;
  io::writeTextFileAtomically(
      path,
      "# Lighting prior over the colour means (YUV, 8-bit levels): mean and cov over the 3M "
      "vector\n"
      "# [Y U V] per colour in the order of `colors`; pixel_noise_var is nu (eq. 1).\n" +
          std::string(out.c_str()) + "\n");
}

LightingPrior LightingPrior::independent() const {
  LightingPrior p = *this;
  const int m = static_cast<int>(color_names.size());
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      if (a != b) p.cov.block<3, 3>(3 * a, 3 * b).setZero();
  p.name = name + "_independent";
  return p;
}

void LightingPrior::validate(const ColorModelConfig& config) const {
  if (mean.size() != config.dim() || cov.rows() != config.dim() || cov.cols() != config.dim())
    throw std::invalid_argument("prior '" + name + "' has dimension " +
                                std::to_string(mean.size()) + " but the model has " +
                                std::to_string(config.numColors()) + " colours");
  for (int k = 0; k < config.numColors(); ++k) {
    if (k < static_cast<int>(color_names.size()) &&
        color_names[k] != world::colorClassName(config.classes[k]))
      throw std::invalid_argument("prior '" + name + "' colour " + std::to_string(k) + " is " +
                                  color_names[k] + ", the model expects " +
                                  world::colorClassName(config.classes[k]));
  }
}

// ------------------------------------------------------------------------------------------------
// PixelClassifier

PixelClassifier::PixelClassifier(const std::vector<Eigen::Vector3d>& means,
                                 const std::vector<Eigen::Matrix3d>& covs,
                                 const std::vector<std::uint8_t>& classes,
                                 double unknown_mahalanobis)
    : means_(means),
      covs_(covs),
      classes_(classes),
      unknown_mahalanobis_sq_(unknown_mahalanobis * unknown_mahalanobis) {
  for (const auto& c : covs_) {
    inv_covs_.push_back(c.inverse());
    log_norms_.push_back(-0.5 * (3.0 * kLog2Pi + std::log(c.determinant())));
  }
}

std::uint8_t PixelClassifier::classify(const Eigen::Vector3d& yuv) const {
  double best = -std::numeric_limits<double>::infinity();
  int best_k = -1;
  bool near_any = false;
  for (int k = 0; k < numColors(); ++k) {
    const double d2 = mahalanobisSq(yuv, k);
    near_any |= d2 <= unknown_mahalanobis_sq_;
    const double ll = log_norms_[k] - 0.5 * d2;
    if (ll > best) {
      best = ll;
      best_k = k;
    }
  }
  return (near_any && best_k >= 0) ? classes_[best_k] : static_cast<std::uint8_t>(255);
}

// ------------------------------------------------------------------------------------------------
// ColorFilter

ColorFilter::ColorFilter(const LightingPrior& prior, const ColorModelConfig& config)
    : config_(config) {
  config_.validate();
  reset(prior);
}

void ColorFilter::reset(const LightingPrior& prior) {
  prior.validate(config_);
  kf_.reset(prior.mean, prior.cov);
  nu_ = prior.pixel_noise_var;
}

void ColorFilter::predict(double dt_s) {
  if (dt_s <= 0.0) return;
  const double q = config_.drift_std_per_sqrt_s * config_.drift_std_per_sqrt_s * dt_s;
  kf_.predict(q * Eigen::MatrixXd::Identity(config_.dim(), config_.dim()));
}

void ColorFilter::observationOf(const ColorObservation& obs, std::vector<int>* idx,
                                Eigen::VectorXd* z, Eigen::MatrixXd* noise) const {
  idx->clear();
  std::vector<double> values, vars;
  for (int k = 0; k < config_.numColors(); ++k) {
    if (k >= static_cast<int>(obs.counts.size()) || obs.counts[k] < config_.min_pixels_per_color)
      continue;
    for (int ch = 0; ch < 3; ++ch) {
      idx->push_back(componentIndex(k, ch));
      values.push_back(obs.means[k][ch]);
      vars.push_back(observationVariance(config_, nu_, obs.counts[k], ch));
    }
  }
  *z = Eigen::Map<Eigen::VectorXd>(values.data(), values.size());
  *noise = Eigen::Map<Eigen::VectorXd>(vars.data(), vars.size()).asDiagonal();
}

double ColorFilter::update(const ColorObservation& obs) {
  std::vector<int> idx;
  Eigen::VectorXd z;
  Eigen::MatrixXd noise;
  observationOf(obs, &idx, &z, &noise);
  if (idx.empty()) return 0.0;
  return kf_.updatePartial(idx, z, noise).log_likelihood;
}

double ColorFilter::predictiveLogLikelihood(const ColorObservation& obs) const {
  std::vector<int> idx;
  Eigen::VectorXd z;
  Eigen::MatrixXd noise;
  observationOf(obs, &idx, &z, &noise);
  if (idx.empty()) return 0.0;
  return kf_.predictiveLogLikelihood(math::selectionMatrix(config_.dim(), idx), z, noise);
}

PixelClassifier ColorFilter::classifier() const {
  std::vector<Eigen::Vector3d> means;
  std::vector<Eigen::Matrix3d> covs;
  for (int k = 0; k < config_.numColors(); ++k) {
    means.push_back(colorMean(k));
    covs.push_back(colorCov(k) + Eigen::Matrix3d(nu_.asDiagonal()));  // eq. (9)
  }
  return PixelClassifier(means, covs, config_.classes, config_.unknown_mahalanobis);
}

}  // namespace adaptive_perception::color
