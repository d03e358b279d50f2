#include "adaptive_perception/slam/map_io.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "adaptive_perception/io/atomic_file.h"

namespace adaptive_perception::slam {

namespace {
YAML::Node pieces(const Landmark& info) {
  YAML::Node out(YAML::NodeType::Sequence);
  for (const auto& p : info.pieces) {
    YAML::Node piece(YAML::NodeType::Sequence);
    for (double v : {p.first.x(), p.first.y(), p.second.x(), p.second.y()}) piece.push_back(v);
    piece.SetStyle(YAML::EmitterStyle::Flow);
    out.push_back(piece);
  }
  out.SetStyle(YAML::EmitterStyle::Flow);
  return out;
}
}  // namespace

void writeLineMapYaml(const std::string& path, const LineEkfSlam& slam) {
  YAML::Node root;
  root["variant"] = variantName(slam.config().variant);
  YAML::Node pose(YAML::NodeType::Sequence);
  for (double v : {slam.pose().x_m, slam.pose().y_m, slam.pose().yaw_rad}) pose.push_back(v);
  pose.SetStyle(YAML::EmitterStyle::Flow);
  root["robot_pose"] = pose;
  root["landmarks"] = YAML::Node(YAML::NodeType::Sequence);
  for (int i = 0; i < slam.numLandmarks(); ++i) {
    const Landmark& info = slam.landmarkInfo(i);
    YAML::Node l;
    l["id"] = info.id;
    l["rho_m"] = slam.landmark(i).rho_m;
    l["alpha_rad"] = slam.landmark(i).alpha_rad;
    l["sightings"] = info.sightings;
    l["confirmed"] = info.confirmed();
    l["pieces"] = pieces(info);
    root["landmarks"].push_back(l);
  }
  root["fixed_landmarks"] = YAML::Node(YAML::NodeType::Sequence);
  for (int k = 0; k < slam.numFixedLandmarks(); ++k) {
    const FixedLandmark& f = slam.fixedLandmark(k);
    YAML::Node l;
    l["id"] = f.info.id;
    l["rho_m"] = f.line.rho_m;
    l["alpha_rad"] = f.line.alpha_rad;
    l["anchor"] = f.anchor;
    YAML::Node cov(YAML::NodeType::Sequence);
    for (double v : {f.cov(0, 0), f.cov(0, 1), f.cov(1, 0), f.cov(1, 1)}) cov.push_back(v);
    cov.SetStyle(YAML::EmitterStyle::Flow);
    l["covariance"] = cov;
    l["sightings"] = f.info.sightings;
    l["pieces"] = pieces(f.info);
    root["fixed_landmarks"].push_back(l);
  }
  const Eigen::MatrixXd& p = slam.covariance();
  YAML::Node data(YAML::NodeType::Sequence);
  for (int r = 0; r < p.rows(); ++r)
    for (int c = 0; c < p.cols(); ++c) data.push_back(p(r, c));
  data.SetStyle(YAML::EmitterStyle::Flow);
  root["state_covariance"]["dim"] = static_cast<int>(p.rows());
  root["state_covariance"]["data"] = data;

  io::writeTextFileAtomically(
      path, "# line-landmark map written by adaptive_perception (see slam/map_io.h)\n" +
                YAML::Dump(root) + "\n");
}

}  // namespace adaptive_perception::slam
