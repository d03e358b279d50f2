#pragma once
// The relative-displacement metric of Kuemmerle et al. 2009 ("On measuring the accuracy of SLAM
// algorithms"): for each relation (t1, t2, delta*) taken from reference data, the estimated
// displacement delta = between(pose(t1), pose(t2)) is compared with delta*, and the error
// between(delta*, delta) is split into translation (m) and rotation (rad). Unlike the absolute
// trajectory error it does not depend on where an early error happened.
//
// File format (the Freiburg relations files): one relation a line,
//   t1 t2 x y z roll pitch yaw
// with times in seconds (matching the log's stamps) and the displacement from the pose at t1 to
// the pose at t2 in the frame of the pose at t1; z, roll and pitch are ignored. '#' starts a
// comment.
#include <map>
#include <string>
#include <vector>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::slam {

struct Relation {
  double t1_s = 0.0, t2_s = 0.0;
  math::SE2 delta;
};

/// Reads a relations file; throws std::runtime_error naming the file and line of anything malformed
/// (wrong field count, non-numeric or non-finite values).
std::vector<Relation> readRelations(const std::string& path);
/// Writes relations in the same format (temporary file, then rename).
void writeRelations(const std::string& path, const std::vector<Relation>& relations);

struct RelationErrors {
  int used = 0, skipped = 0;  // skipped: no pose within the time tolerance of t1 or t2
  double trans_mean_m = 0.0, trans_std_m = 0.0;
  double rot_mean_rad = 0.0, rot_std_rad = 0.0;
};

/// The metric over a trajectory given as stamped poses; a relation uses the poses nearest t1 and
/// t2 when both are within time_tolerance_s.
RelationErrors evaluateRelations(const std::vector<Relation>& relations,
                                 const std::map<double, math::SE2>& trajectory,
                                 double time_tolerance_s = 0.01);

/// Reference relations from a ground-truth trajectory: every pair of poses step_s apart (a chain)
/// plus `random_pairs` pairs drawn uniformly (loop-closing scale), deterministic for the seed.
std::vector<Relation> relationsFromTrajectory(const std::map<double, math::SE2>& truth,
                                              double step_s, int random_pairs, unsigned seed = 1);

}  // namespace adaptive_perception::slam
