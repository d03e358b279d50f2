#include "adaptive_perception/sim/camera_sensor.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/color/color_space.h"

namespace adaptive_perception::sim {

void CameraSensorConfig::validate() const {
  auto check = [](bool ok, const char* name, double v, const char* range) {
    if (!ok)
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(v) +
                                  " (allowed: " + range + ")");
  };
  sensor.validate();
  check(chroma_noise >= 0.0, "chroma_noise", chroma_noise, ">= 0");
}

CameraSensor::CameraSensor(const world::PinholeCamera& camera, CameraSensorConfig config)
    : camera_(camera), config_(config) {
  config_.validate();
  const double half_diag2 =
      0.25 * (camera.width_px * camera.width_px + camera.height_px * camera.height_px);
  radial2_.resize(static_cast<size_t>(camera.width_px) * camera.height_px);
  for (int v = 0; v < camera.height_px; ++v)
    for (int u = 0; u < camera.width_px; ++u) {
      const double du = u + 0.5 - 0.5 * camera.width_px, dv = v + 0.5 - 0.5 * camera.height_px;
      radial2_[static_cast<size_t>(v) * camera.width_px + u] =
          static_cast<float>((du * du + dv * dv) / half_diag2);
    }
}

namespace {
// Procedural texture of the room around the field: blocks of varying shade by direction.
double roomTexture(const Eigen::Vector3d& d) {
  const double az = std::atan2(d.y(), d.x());
  const double el = std::atan2(d.z(), std::hypot(d.x(), d.y()));
  const int a = static_cast<int>(std::floor(az * 9.0)), e = static_cast<int>(std::floor(el * 6.0));
  unsigned h = static_cast<unsigned>(a * 73856093) ^ static_cast<unsigned>(e * 19349663);
  h = (h ^ (h >> 13)) * 0x5bd1e995u;
  h ^= h >> 15;
  return 0.4 + 1.2 * (h % 1000) / 1000.0;
}
}  // namespace

CameraImage CameraSensor::render(const std::vector<world::RayHit>& hits,
                                 const Eigen::Isometry3d& map_to_optical,
                                 const world::SceneLighting& lighting, const FieldEnvironment& env,
                                 math::Rng& rng) const {
  const int w = camera_.width_px, h = camera_.height_px;
  if (hits.size() != static_cast<size_t>(w) * h)
    throw std::invalid_argument("CameraSensor::render: one hit per pixel expected");
  cv::Mat y(h, w, CV_32F), u(h, w, CV_32F), v(h, w, CV_32F);
  CameraImage out;
  out.labels.create(h, w, CV_8UC1);
  const SensorResponse& sensor = config_.sensor;
  const Eigen::Vector3d wb = world::colorTemperatureRgb(sensor.white_point_k, sensor.white_point_k);
  const world::SceneLighting::SourceColors colors = lighting.sourceColors();
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const size_t i = static_cast<size_t>(r) * w + c;
      const world::RayHit& hit = hits[i];
      Eigen::Vector3d radiance;
      if (hit.kind == world::SurfaceKind::kNone) {
        const Eigen::Vector3d d = (map_to_optical.linear() * camera_.rayThrough(c, r)).normalized();
        const Eigen::Vector3d e =
            lighting.irradiance(map_to_optical.translation() + 4.0 * d, -d, colors);
        radiance = roomTexture(d) * env.materials.room.cwiseProduct(e);
      } else {
        radiance =
            env.albedo(hit).cwiseProduct(lighting.irradiance(hit.point_m, hit.normal, colors));
      }
      const double r2 = radial2_[i];
      Eigen::Vector3d rgb = env.exposure * sensor.falloff(r2) * radiance.cwiseProduct(wb);
      for (int k = 0; k < 3; ++k) rgb[k] = sensor.level(rgb[k]);
      const Eigen::Vector3d yuv = color::rgbToYuv(rgb);
      const double luma_sd = sensor.noiseSd(yuv[0]);
      y.at<float>(r, c) = static_cast<float>(yuv[0] + rng.gaussian(0.0, luma_sd));
      u.at<float>(r, c) = static_cast<float>(yuv[1] + config_.vignetting_chroma_u * r2 +
                                             rng.gaussian(0.0, config_.chroma_noise));
      v.at<float>(r, c) = static_cast<float>(yuv[2] + rng.gaussian(0.0, config_.chroma_noise));
      out.labels.at<std::uint8_t>(r, c) = hit.color;
    }
  }
  out.uyvy = color::packUyvy(y, u, v);
  return out;
}

}  // namespace adaptive_perception::sim
