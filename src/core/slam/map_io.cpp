#include "adaptive_perception/slam/map_io.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <charconv>
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
  std::string text = "# line-landmark map written by adaptive_perception (see slam/map_io.h)\n" +
                     YAML::Dump(root) + "\n";
  // The covariance is most of the file (n^2 values for 3 + 2 * landmarks states): written
  // directly, one row a line, each value in its shortest form that reads back exactly
  // (std::to_chars), rather than through n^2 yaml-cpp nodes.
  const Eigen::MatrixXd& p = slam.covariance();
  text += "state_covariance:\n  dim: " + std::to_string(p.rows()) + "\n  data: [";
  text.reserve(text.size() + static_cast<std::size_t>(p.size()) * 12);
  std::array<char, 32> buf{};
  for (int r = 0; r < p.rows(); ++r) {
    if (r > 0) text += ",\n    ";
    for (int c = 0; c < p.cols(); ++c) {
      if (c > 0) text += ", ";
      const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), p(r, c));
      text.append(buf.data(), res.ptr);
    }
  }
  text += "]\n";
  io::writeTextFileAtomically(path, text);
}

}  // namespace adaptive_perception::slam
