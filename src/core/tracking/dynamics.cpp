#include "adaptive_perception/tracking/dynamics.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <stdexcept>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/io/yaml_file.h"

namespace adaptive_perception::tracking {

Ar2Model Ar2Model::constantVelocity(const DistributionState& noise_sd) {
  Ar2Model m;
  m.b = noise_sd.asDiagonal();
  return m;
}

DistributionState Ar2Model::mean(const DistributionState& x1, const DistributionState& x0) const {
  return a1 * x1 + a0 * x0 + d;
}

DistributionState Ar2Model::sample(const DistributionState& x1, const DistributionState& x0,
                                   math::Rng& rng) const {
  DistributionState w;
  for (int k = 0; k < kStateDim; ++k) w[k] = rng.gaussian();
  return mean(x1, x0) + b * w;
}

namespace {
template <typename M>
void readMatrix(const YAML::Node& root, const char* key, const std::string& path, M* out) {
  const YAML::Node n = root[key];
  const int count = static_cast<int>(out->size());
  if (!n || !n.IsSequence() || static_cast<int>(n.size()) != count)
    throw std::runtime_error(path + ": '" + key + "' must be a list of " + std::to_string(count) +
                             " numbers");
  for (int i = 0; i < count; ++i) {
    try {
      (*out)(i / out->cols(), i % out->cols()) = n[i].as<double>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error(io::yamlWhere(path, n[i]) + ": '" + key + "' entry " +
                               std::to_string(i) + " is not a number");
    }
  }
}
template <typename M>
YAML::Node writeMatrix(const M& m) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) n.push_back(m(r, c));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}
}  // namespace

Ar2Model Ar2Model::loadYaml(const std::string& path) {
  const YAML::Node root = io::loadYamlFile(path, "tracking dynamics");
  if (!root.IsMap()) throw std::runtime_error(path + ": not a map of a1, a0, d, b");
  Ar2Model m;
  readMatrix(root, "a1", path, &m.a1);
  readMatrix(root, "a0", path, &m.a0);
  readMatrix(root, "d", path, &m.d);
  readMatrix(root, "b", path, &m.b);
  if (!m.a1.allFinite() || !m.a0.allFinite() || !m.d.allFinite() || !m.b.allFinite())
    throw std::runtime_error(path + ": dynamics with a non-finite number");
  return m;
}

void Ar2Model::saveYaml(const std::string& path) const {
  YAML::Node root;
  root["a1"] = writeMatrix(a1);
  root["a0"] = writeMatrix(a0);
  root["d"] = writeMatrix(d);
  root["b"] = writeMatrix(b);
  io::writeTextFileAtomically(
      path,
      "# CONDENSATION dynamics x_t = A1 x_{t-1} + A0 x_{t-2} + d + B w (tracking/dynamics.h);\n"
      "# state [m (3), lambda (3), theta, phi]; matrices row-major.\n" +
          YAML::Dump(root) + "\n");
}

Ar2Model learnAr2(const std::vector<DistributionState>& seq, bool diagonal) {
  const int n = static_cast<int>(seq.size()) - 2;  // equations
  const int need = diagonal ? 20 : 4 * (2 * kStateDim + 1);
  if (n + 2 < need)
    throw std::invalid_argument("learnAr2: " + std::to_string(seq.size()) + " states; at least " +
                                std::to_string(need) + " needed");
  Ar2Model m;
  m.a1.setZero();
  m.a0.setZero();
  Eigen::MatrixXd residual(n, kStateDim);
  if (diagonal) {
    for (int k = 0; k < kStateDim; ++k) {
      Eigen::MatrixXd x(n, 3);
      Eigen::VectorXd y(n);
      for (int t = 0; t < n; ++t) {
        x(t, 0) = seq[t + 1][k];
        x(t, 1) = seq[t][k];
        x(t, 2) = 1.0;
        y[t] = seq[t + 2][k];
      }
      const Eigen::Vector3d c = x.colPivHouseholderQr().solve(y);
      m.a1(k, k) = c[0];
      m.a0(k, k) = c[1];
      m.d[k] = c[2];
      residual.col(k) = y - x * c;
    }
  } else {
    Eigen::MatrixXd x(n, 2 * kStateDim + 1), y(n, kStateDim);
    for (int t = 0; t < n; ++t) {
      x.row(t) << seq[t + 1].transpose(), seq[t].transpose(), 1.0;
      y.row(t) = seq[t + 2].transpose();
    }
    const Eigen::MatrixXd c = x.colPivHouseholderQr().solve(y);  // (2D + 1) x D
    m.a1 = c.topRows(kStateDim).transpose();
    m.a0 = c.middleRows(kStateDim, kStateDim).transpose();
    m.d = c.row(2 * kStateDim).transpose();
    residual = y - x * c;
  }
  StateMatrix cov = (residual.transpose() * residual) / std::max(1, n - 1);
  if (diagonal) cov = StateMatrix(cov.diagonal().asDiagonal());
  // A dimension that never moved gets a tiny noise so B stays a Cholesky factor.
  cov += 1e-12 * StateMatrix::Identity();
  m.b = cov.llt().matrixL();
  return m;
}

}  // namespace adaptive_perception::tracking
