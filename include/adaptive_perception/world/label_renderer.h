#pragma once
// Label renderer: for a camera pose in the map, the expected colour class of each pixel (or of a
// given list of pixels), by casting the pixel's ray against the field map's primitives.
//
// It is the inner loop of the particle filter (one call per particle per frame on a pixel
// subsample), so per camera pose it precomputes what does not depend on the pixel (the ray origin
// terms of every primitive; each primitive's box projected into the image, culling those outside
// the view or behind the camera) and per pixel tests only the primitives whose box holds it, with
// no allocation. The culling is exact: castRay, which culls nothing, gives the same labels
// for the same (float) pixel rays.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception::world {

struct RayHit {
  double range_m = 0.0;  // distance along the unit ray; 0 when nothing was hit
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, facing the ray origin
  ColorClass color = kBackground;
  SurfaceKind kind = SurfaceKind::kNone;
};

struct PixelCoord {
  std::uint16_t u, v;
};

class LabelRenderer {
 public:
  LabelRenderer(const FieldMap& map, const PinholeCamera& camera);

  const PinholeCamera& camera() const { return camera_; }
  const FieldMap& map() const { return map_; }

  /// Fills `labels` (width*height, row-major) with the class of every pixel.
  /// `map_to_optical` is the pose of camera_optical_frame in map.
  void renderImage(const Eigen::Isometry3d& map_to_optical, std::uint8_t* labels) const;
  /// The class of each listed pixel, into out[i].
  void renderPixels(const Eigen::Isometry3d& map_to_optical, const PixelCoord* pixels,
                    std::size_t count, std::uint8_t* out) const;
  void renderPixels(const Eigen::Isometry3d& map_to_optical, const std::vector<PixelCoord>& pixels,
                    std::vector<std::uint8_t>* out) const;

  /// Full hit record of every pixel (row-major), for the simulator's shading.
  void renderHitImage(const Eigen::Isometry3d& map_to_optical, std::vector<RayHit>* hits) const;

  /// Full hit record of one ray in the map frame (`dir` need not be unit); for the simulator.
  RayHit castRay(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& dir) const;

 private:
  /// A box in the optical frame's normalised image plane (x / z, y / z); the default is
  /// unbounded.
  struct ViewBox {
    static constexpr double kNone = 1e300;
    double x0 = -kNone, x1 = kNone, y0 = -kNone, y1 = kNone;
    bool contains(double rx, double ry) const {
      return rx >= x0 && rx <= x1 && ry >= y0 && ry <= y1;
    }
    bool overlaps(const ViewBox& b) const {
      return x0 <= b.x1 && b.x0 <= x1 && y0 <= b.y1 && b.y0 <= y1;
    }
  };
  // The view box of the map-frame box [lo, hi] for a camera at `origin` with map <- optical
  // rotation `r` (row-major).
  static ViewBox viewBoxOf(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                           const double* origin, const double* r);

  struct PoseSetup;  // per-pose precomputation, on the stack of each render call
  // (rx, ry): the ray in the normalised image plane, tested against each primitive's view box
  // before the primitive itself; (dx, dy, dz): the ray in the map frame.
  template <bool kFullHit>
  void trace(const PoseSetup& s, double rx, double ry, double dx, double dy, double dz, RayHit* hit,
             std::uint8_t* label) const;
  void setup(const Eigen::Vector3d& origin, const Eigen::Matrix3d* rot, PoseSetup* s) const;

  FieldMap map_;
  PinholeCamera camera_;
  std::vector<Eigen::Vector3f> rays_optical_;  // per pixel, z = 1
  ViewBox image_box_;                          // the rays' box: primitives outside are culled

  // Flattened primitives for the hot loop.
  struct QuadP {
    double p0x, p0y, ex, ey, len, nx, ny, z0, z1;
    std::uint8_t color, kind;
  };
  struct CylP {
    double cx, cy, r2;
    std::vector<CylinderBand> bands;
    double zmin, zmax;
    SurfaceKind kind;
  };
  std::vector<QuadP> quads_;
  std::vector<CylP> cylinders_;
};

}  // namespace adaptive_perception::world
