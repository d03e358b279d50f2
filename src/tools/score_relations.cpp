// score_relations: the relations benchmark's metric (Kuemmerle et al. 2009; slam/relations.h) over
// a trajectory another mapper wrote, so that a peer is scored exactly as evaluate_slam scores ours.
//
//   score_relations --trajectory FILE --relations FILE [--time_tolerance_s 0.01]
//
// --trajectory: TUM format, one pose a line, `t x y z qx qy qz qw` (the yaw from the quaternion,
// z and the tilt ignored), lines starting with '#' skipped; a malformed line is refused naming the
// file and line. A relation uses the poses nearest its two stamps when both are within
// --time_tolerance_s (evaluate_slam uses 0.01 s). Last line:
//   score_relations: trajectory=.. poses=.. relations_used=.. relations_skipped=..
//   relation_trans_error_m=.. relation_trans_error_m_std=.. relation_rot_error_deg=..
//   relation_rot_error_deg_std=..
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/relations.h"
#include "command_line.h"

using namespace adaptive_perception;

namespace {

std::map<double, math::SE2> readTum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::map<double, math::SE2> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double v[8];
    for (double& x : v)
      if (!(s >> x) || !std::isfinite(x))
        throw std::runtime_error(path + ":" + std::to_string(n) +
                                 ": expected 8 finite numbers, t x y z qx qy qz qw");
    const double yaw = std::atan2(2.0 * (v[7] * v[6] + v[4] * v[5]),
                                  1.0 - 2.0 * (v[5] * v[5] + v[6] * v[6]));
    out[v[0]] = math::SE2(v[1], v[2], yaw);
  }
  if (out.empty()) throw std::runtime_error(path + ": no pose in it");
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("score_relations",
                         "The relations benchmark's metric over a trajectory another mapper wrote "
                         "(TUM format), as evaluate_slam scores its own.");
  std::string trajectory_path, relations_path;
  cli.option("trajectory", &trajectory_path, "the trajectory scored, TUM format")->required();
  cli.option("relations", &relations_path, "the relations file (the benchmark's)")->required();
  double tolerance_s = 0.01;
  cli.option("time_tolerance_s", &tolerance_s, config::aboveZero(10.0),
             "largest gap between a relation's stamp and the pose taken for it, s");
  cli.parse(argc, argv);
  try {
    const std::map<double, math::SE2> trajectory = readTum(trajectory_path);
    const std::vector<slam::Relation> relations = slam::readRelations(relations_path);
    const slam::RelationErrors e = slam::evaluateRelations(relations, trajectory, tolerance_s);
    std::printf(
        "score_relations: trajectory=%s poses=%zu relations_used=%d relations_skipped=%d "
        "relation_trans_error_m=%.4f relation_trans_error_m_std=%.4f relation_rot_error_deg=%.3f "
        "relation_rot_error_deg_std=%.3f\n",
        trajectory_path.c_str(), trajectory.size(), e.used, e.skipped, e.trans_mean_m,
        e.trans_std_m, math::radToDeg(e.rot_mean_rad), math::radToDeg(e.rot_std_rad));
    return e.used > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "score_relations: error: %s\n", e.what());
    return 1;
  }
}
