#include "adaptive_perception/slam/map_io.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/io/yaml_file.h"
#include "adaptive_perception/math/symmetric2.h"

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

namespace {
[[noreturn]] void bad(const std::string& path, const YAML::Node& node, const std::string& what) {
  throw std::runtime_error(io::yamlWhere(path, node) + ": " + what);
}

double number(const std::string& path, const YAML::Node& parent, const char* key) {
  const YAML::Node v = parent[key];
  if (!v) bad(path, parent, std::string("missing '") + key + "'");
  try {
    const double d = v.as<double>();
    if (!std::isfinite(d)) bad(path, v, std::string("'") + key + "' is not finite");
    return d;
  } catch (const YAML::Exception&) {
    bad(path, v, std::string("'") + key + "' is not a number");
  }
}

void readPieces(const std::string& path, const YAML::Node& l, Landmark* info) {
  const YAML::Node ps = l["pieces"];
  if (!ps) return;
  if (!ps.IsSequence()) bad(path, ps, "'pieces' is not a list");
  for (const auto& p : ps) {
    if (!p.IsSequence() || p.size() != 4) bad(path, p, "a piece is not [x0, y0, x1, y1]");
    double v[4];
    for (int i = 0; i < 4; ++i) {
      try {
        v[i] = p[i].as<double>();
      } catch (const YAML::Exception&) {
        bad(path, p, "a piece holds something that is not a number");
      }
    }
    info->pieces.emplace_back(Eigen::Vector2d(v[0], v[1]), Eigen::Vector2d(v[2], v[3]));
  }
  if (!info->pieces.empty()) {
    info->start_m = info->pieces.front().first;
    info->end_m = info->pieces.back().second;
  }
}

/// A landmark's id, sightings, line and pieces (its covariance is read by the caller).
FixedLandmark landmarkOf(const std::string& path, const YAML::Node& l) {
  FixedLandmark f;
  f.info.id = static_cast<std::uint64_t>(number(path, l, "id"));
  f.info.sightings = static_cast<int>(l["sightings"] ? number(path, l, "sightings") : 0);
  f.line = Line{number(path, l, "rho_m"), number(path, l, "alpha_rad")};
  readPieces(path, l, &f.info);
  return f;
}
}  // namespace

std::vector<FixedLandmark> readLineMapYaml(const std::string& path) {
  const YAML::Node root = io::loadYamlFile(path, "line map");
  if (!root.IsMap()) bad(path, root, "not a line map (no top-level mapping)");
  const YAML::Node landmarks = root["landmarks"], fixed = root["fixed_landmarks"];
  if (!landmarks || !landmarks.IsSequence()) bad(path, root, "missing the 'landmarks' list");
  const YAML::Node cov = root["state_covariance"];
  if (!cov || !cov["dim"] || !cov["data"] || !cov["data"].IsSequence())
    bad(path, root, "missing 'state_covariance' with 'dim' and 'data'");
  const int dim = static_cast<int>(number(path, cov, "dim"));
  if (dim != 3 + 2 * static_cast<int>(landmarks.size()))
    bad(path, cov,
        "state_covariance dim " + std::to_string(dim) + " does not match " +
            std::to_string(landmarks.size()) + " landmarks (3 + 2 per landmark)");
  if (static_cast<int>(cov["data"].size()) != dim * dim)
    bad(path, cov["data"],
        "state_covariance data holds " + std::to_string(cov["data"].size()) +
            " values, not dim^2 = " + std::to_string(dim * dim));
  auto at = [&](int r, int c) {
    const YAML::Node v = cov["data"][r * dim + c];
    try {
      return v.as<double>();
    } catch (const YAML::Exception&) {
      bad(path, v, "a covariance value is not a number");
    }
  };
  auto check = [&](const Eigen::Matrix2d& c, const YAML::Node& where) {
    if (!math::isCovariance(c))
      bad(path, where, "a landmark covariance that is not symmetric positive semi-definite");
  };
  std::vector<FixedLandmark> out;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const YAML::Node l = landmarks[i];
    if (l["confirmed"] && !l["confirmed"].as<bool>(false)) continue;  // tentative: not the map
    FixedLandmark f = landmarkOf(path, l);
    const int k = 3 + 2 * static_cast<int>(i);
    f.cov << at(k, k), at(k, k + 1), at(k + 1, k), at(k + 1, k + 1);
    check(f.cov, l);
    out.push_back(f);
  }
  if (fixed) {
    if (!fixed.IsSequence()) bad(path, fixed, "'fixed_landmarks' is not a list");
    for (const auto& l : fixed) {
      FixedLandmark f = landmarkOf(path, l);
      const YAML::Node c = l["covariance"];
      if (!c || !c.IsSequence() || c.size() != 4) bad(path, l, "'covariance' is not 4 values");
      for (int j = 0; j < 4; ++j) {
        try {
          f.cov(j / 2, j % 2) = c[j].as<double>();
        } catch (const YAML::Exception&) {
          bad(path, c, "a covariance value is not a number");
        }
      }
      check(f.cov, l);
      out.push_back(f);
    }
  }
  return out;
}

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
