#include "adaptive_perception/slam/relations.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/io/atomic_file.h"

namespace adaptive_perception::slam {

std::vector<Relation> readRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the relations file");
  std::vector<Relation> out;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream ss(line);
    std::vector<double> v;
    std::string tok;
    while (ss >> tok) {
      try {
        size_t used = 0;
        const double d = std::stod(tok, &used);
        if (used != tok.size() || !std::isfinite(d)) throw std::invalid_argument(tok);
        v.push_back(d);
      } catch (const std::exception&) {
        throw std::runtime_error(path + ":" + std::to_string(number) + ": '" + tok +
                                 "' is not a finite number");
      }
    }
    if (v.empty()) continue;
    if (v.size() != 8)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " +
                               std::to_string(v.size()) +
                               " fields (expected 8: t1 t2 x y z roll pitch yaw)");
    out.push_back(Relation{v[0], v[1], math::SE2(v[2], v[3], v[7])});
  }
  return out;
}

void writeRelations(const std::string& path, const std::vector<Relation>& relations) {
  std::ostringstream out;
  out << std::setprecision(12);
  for (const auto& r : relations)
    out << r.t1_s << " " << r.t2_s << " " << r.delta.x_m << " " << r.delta.y_m << " 0 0 0 "
        << r.delta.yaw_rad << "\n";
  io::writeTextFileAtomically(path, out.str());
}

namespace {
const math::SE2* nearestPose(const std::map<double, math::SE2>& traj, double t, double tol) {
  if (traj.empty()) return nullptr;
  auto it = traj.lower_bound(t);
  if (it == traj.end() || (it != traj.begin() && t - std::prev(it)->first < it->first - t)) --it;
  return std::fabs(it->first - t) <= tol ? &it->second : nullptr;
}
}  // namespace

RelationErrors evaluateRelations(const std::vector<Relation>& relations,
                                 const std::map<double, math::SE2>& trajectory, double tol) {
  RelationErrors e;
  double st = 0.0, st2 = 0.0, sr = 0.0, sr2 = 0.0;
  for (const auto& r : relations) {
    const math::SE2* a = nearestPose(trajectory, r.t1_s, tol);
    const math::SE2* b = nearestPose(trajectory, r.t2_s, tol);
    if (!a || !b) {
      ++e.skipped;
      continue;
    }
    const math::SE2 err = math::between(r.delta, math::between(*a, *b));
    const double t = std::hypot(err.x_m, err.y_m), rot = std::fabs(err.yaw_rad);
    st += t;
    st2 += t * t;
    sr += rot;
    sr2 += rot * rot;
    ++e.used;
  }
  if (e.used > 0) {
    const double n = e.used;
    e.trans_mean_m = st / n;
    e.rot_mean_rad = sr / n;
    e.trans_std_m = std::sqrt(std::max(0.0, st2 / n - e.trans_mean_m * e.trans_mean_m));
    e.rot_std_rad = std::sqrt(std::max(0.0, sr2 / n - e.rot_mean_rad * e.rot_mean_rad));
  }
  return e;
}

std::vector<Relation> relationsFromTrajectory(const std::map<double, math::SE2>& truth,
                                              double step_s, int random_pairs, unsigned seed) {
  std::vector<Relation> out;
  if (truth.size() < 2) return out;
  double last = -1e300;
  const math::SE2* prev = nullptr;
  double prev_t = 0.0;
  for (const auto& [t, p] : truth) {
    if (t - last < step_s) continue;
    if (prev) out.push_back(Relation{prev_t, t, math::between(*prev, p)});
    prev = &p;
    prev_t = t;
    last = t;
  }
  std::vector<std::pair<double, math::SE2>> v(truth.begin(), truth.end());
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, v.size() - 1);
  for (int k = 0; k < random_pairs; ++k) {
    size_t i = pick(rng), j = pick(rng);
    if (i == j) continue;
    if (i > j) std::swap(i, j);
    out.push_back(Relation{v[i].first, v[j].first, math::between(v[i].second, v[j].second)});
  }
  return out;
}

}  // namespace adaptive_perception::slam
