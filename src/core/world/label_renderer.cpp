#include "adaptive_perception/world/label_renderer.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace adaptive_perception::world {

namespace {
constexpr int kMaxQuads = 64;
constexpr int kMaxCylinders = 32;
constexpr int kMaxSpheres = 8;

}  // namespace

struct LabelRenderer::PoseSetup {
  double ox, oy, oz;
  double r[9];  // map <- optical rotation, row-major
  int n_quads = 0;
  int quad_idx[kMaxQuads];
  double quad_num[kMaxQuads];  // n . (p0 - o): the numerator of the ray parameter
  ViewBox quad_box[kMaxQuads];
  int n_cyl = 0;
  int cyl_idx[kMaxCylinders];
  double cyl_ocx[kMaxCylinders], cyl_ocy[kMaxCylinders], cyl_c[kMaxCylinders];
  ViewBox cyl_box[kMaxCylinders];
  int n_sph = 0;
  int sph_idx[kMaxSpheres];
  double sph_oc[kMaxSpheres][3], sph_c[kMaxSpheres];
  ViewBox sph_box[kMaxSpheres];
};

// The corners' box, which bounds the projection of the whole (convex) box while
// every corner lies in front of the camera. A box reaching to or behind the image plane gets no
// bound. The margin absorbs rounding (rays and corners are projected by different routes).
LabelRenderer::ViewBox LabelRenderer::viewBoxOf(const Eigen::Vector3d& lo,
                                                const Eigen::Vector3d& hi, const double* o,
                                                const double* r) {
  constexpr double kMinDepthM = 1e-3, kMargin = 1e-6;
  ViewBox b{ViewBox::kNone, -ViewBox::kNone, ViewBox::kNone, -ViewBox::kNone};
  for (int c = 0; c < 8; ++c) {
    const double p[3] = {(c & 1 ? hi : lo).x() - o[0], (c & 2 ? hi : lo).y() - o[1],
                         (c & 4 ? hi : lo).z() - o[2]};
    // optical = r^T (p - o)
    const double x = r[0] * p[0] + r[3] * p[1] + r[6] * p[2];
    const double y = r[1] * p[0] + r[4] * p[1] + r[7] * p[2];
    const double z = r[2] * p[0] + r[5] * p[1] + r[8] * p[2];
    if (!(z > kMinDepthM)) return ViewBox{};
    b.x0 = std::min(b.x0, x / z);
    b.x1 = std::max(b.x1, x / z);
    b.y0 = std::min(b.y0, y / z);
    b.y1 = std::max(b.y1, y / z);
  }
  return ViewBox{b.x0 - kMargin, b.x1 + kMargin, b.y0 - kMargin, b.y1 + kMargin};
}
LabelRenderer::LabelRenderer(const FieldMap& map, const PinholeCamera& camera)
    : map_(map), camera_(camera) {
  camera_.validate();
  if (map.quads().size() > kMaxQuads || map.cylinders().size() > kMaxCylinders ||
      map.spheres().size() > kMaxSpheres) {
    throw std::invalid_argument(
        "LabelRenderer: the map has more primitives than the renderer supports");
  }
  rays_optical_.resize(static_cast<size_t>(camera_.width_px) * camera_.height_px);
  for (int v = 0; v < camera_.height_px; ++v)
    for (int u = 0; u < camera_.width_px; ++u)
      rays_optical_[static_cast<size_t>(v) * camera_.width_px + u] =
          camera_.rayThrough(u, v).cast<float>();
  image_box_ = ViewBox{ViewBox::kNone, -ViewBox::kNone, ViewBox::kNone, -ViewBox::kNone};
  for (const Eigen::Vector3f& r : rays_optical_) {
    image_box_.x0 = std::min<double>(image_box_.x0, r.x());
    image_box_.x1 = std::max<double>(image_box_.x1, r.x());
    image_box_.y0 = std::min<double>(image_box_.y0, r.y());
    image_box_.y1 = std::max<double>(image_box_.y1, r.y());
  }
  for (const auto& q : map.quads()) {
    const Eigen::Vector2d e = q.p1_m - q.p0_m;
    const double len = e.norm();
    const Eigen::Vector2d eu = e / len;
    quads_.push_back({q.p0_m.x(), q.p0_m.y(), eu.x(), eu.y(), len, -eu.y(), eu.x(), q.z0_m, q.z1_m,
                      q.color, static_cast<std::uint8_t>(q.kind)});
  }
  for (const auto& c : map.cylinders()) {
    cylinders_.push_back({c.cx_m, c.cy_m, c.radius_m * c.radius_m, c.bands, c.bands.front().z0_m,
                          c.bands.back().z1_m, c.kind});
  }
}

void LabelRenderer::setup(const Eigen::Vector3d& o, const Eigen::Matrix3d* rot,
                          PoseSetup* s) const {
  s->ox = o.x();
  s->oy = o.y();
  s->oz = o.z();
  const double origin[3] = {o.x(), o.y(), o.z()};
  Eigen::Vector3d fwd(0, 0, 0);
  if (rot) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s->r[3 * i + j] = (*rot)(i, j);
    fwd = rot->col(2);
  }
  // Quads: skip those entirely behind the image plane (all four corners behind the camera).
  s->n_quads = 0;
  for (int i = 0; i < static_cast<int>(quads_.size()); ++i) {
    const QuadP& q = quads_[i];
    if (rot) {
      bool any_front = false;
      for (double sgn : {0.0, 1.0})
        for (double z : {q.z0, q.z1}) {
          const Eigen::Vector3d c(q.p0x + sgn * q.len * q.ex - o.x(),
                                  q.p0y + sgn * q.len * q.ey - o.y(), z - o.z());
          any_front |= c.dot(fwd) > 0.0;
        }
      if (!any_front) continue;
    }
    ViewBox box;
    if (rot) {
      const Eigen::Vector3d a(q.p0x, q.p0y, q.z0),
          b(q.p0x + q.len * q.ex, q.p0y + q.len * q.ey, q.z1);
      box = viewBoxOf(a.cwiseMin(b), a.cwiseMax(b), origin, s->r);
      if (!box.overlaps(image_box_)) continue;
    }
    s->quad_box[s->n_quads] = box;
    s->quad_idx[s->n_quads] = i;
    s->quad_num[s->n_quads] = q.nx * (q.p0x - o.x()) + q.ny * (q.p0y - o.y());
    ++s->n_quads;
  }
  s->n_cyl = 0;
  for (int i = 0; i < static_cast<int>(cylinders_.size()); ++i) {
    const CylP& c = cylinders_[i];
    const double ocx = o.x() - c.cx, ocy = o.y() - c.cy;
    if (rot) {
      const double r = std::sqrt(c.r2);
      // Behind the camera when even the nearest point of the bounding box lies behind it.
      const double along = -ocx * fwd.x() - ocy * fwd.y();
      const double reach = r * std::hypot(fwd.x(), fwd.y()) +
                           std::max((c.zmin - o.z()) * fwd.z(), (c.zmax - o.z()) * fwd.z());
      if (along + reach <= 0.0) continue;
    }
    ViewBox box;
    if (rot) {
      const double r = std::sqrt(c.r2);
      box = viewBoxOf(Eigen::Vector3d(c.cx - r, c.cy - r, c.zmin),
                      Eigen::Vector3d(c.cx + r, c.cy + r, c.zmax), origin, s->r);
      if (!box.overlaps(image_box_)) continue;
    }
    s->cyl_box[s->n_cyl] = box;
    s->cyl_idx[s->n_cyl] = i;
    s->cyl_ocx[s->n_cyl] = ocx;
    s->cyl_ocy[s->n_cyl] = ocy;
    s->cyl_c[s->n_cyl] = ocx * ocx + ocy * ocy - c.r2;
    ++s->n_cyl;
  }
  s->n_sph = 0;
  for (int i = 0; i < static_cast<int>(map_.spheres().size()); ++i) {
    const Sphere& sp = map_.spheres()[i];
    const Eigen::Vector3d oc = o - sp.centre_m;
    ViewBox box;
    if (rot) {
      const Eigen::Vector3d half = Eigen::Vector3d::Constant(sp.radius_m);
      box = viewBoxOf(sp.centre_m - half, sp.centre_m + half, origin, s->r);
      if (!box.overlaps(image_box_)) continue;
    }
    s->sph_box[s->n_sph] = box;
    s->sph_idx[s->n_sph] = i;
    for (int k = 0; k < 3; ++k) s->sph_oc[s->n_sph][k] = oc[k];
    s->sph_c[s->n_sph] = oc.squaredNorm() - sp.radius_m * sp.radius_m;
    ++s->n_sph;
  }
}

template <bool kFullHit>
inline void LabelRenderer::trace(const PoseSetup& s, double rx, double ry, double dx, double dy,
                                 double dz, RayHit* hit, std::uint8_t* label) const {
  double best_t = std::numeric_limits<double>::infinity();
  std::uint8_t color = kBackground;
  SurfaceKind kind = SurfaceKind::kNone;
  int what = -1;  // 0 ground, 1 quad, 2 cylinder, 3 sphere
  int which = 0;

  if (dz < 0.0) {
    const double t = -s.oz / dz;
    const double x = s.ox + t * dx, y = s.oy + t * dy;
    if (std::fabs(x) <= map_.carpetHalfLength() && std::fabs(y) <= map_.carpetHalfWidth()) {
      best_t = t;
      what = 0;
    }
  }
  for (int k = 0; k < s.n_quads; ++k) {
    if (!s.quad_box[k].contains(rx, ry)) continue;
    const QuadP& q = quads_[s.quad_idx[k]];
    const double denom = q.nx * dx + q.ny * dy;
    if (denom == 0.0) continue;
    const double t = s.quad_num[k] / denom;
    if (t <= 0.0 || t >= best_t) continue;
    const double z = s.oz + t * dz;
    if (z < q.z0 || z > q.z1) continue;
    const double along = q.ex * (s.ox + t * dx - q.p0x) + q.ey * (s.oy + t * dy - q.p0y);
    if (along < 0.0 || along > q.len) continue;
    best_t = t;
    color = q.color;
    kind = static_cast<SurfaceKind>(q.kind);
    what = 1;
    which = s.quad_idx[k];
  }
  const double a_xy = dx * dx + dy * dy;
  for (int k = 0; k < s.n_cyl; ++k) {
    if (!s.cyl_box[k].contains(rx, ry)) continue;
    const double b = s.cyl_ocx[k] * dx + s.cyl_ocy[k] * dy;
    const double disc = b * b - a_xy * s.cyl_c[k];
    if (disc < 0.0 || b >= 0.0) continue;  // missed, or moving away from the axis
    const double t = (-b - std::sqrt(disc)) / a_xy;
    if (t <= 0.0 || t >= best_t) continue;
    const CylP& c = cylinders_[s.cyl_idx[k]];
    const double z = s.oz + t * dz;
    if (z < c.zmin || z > c.zmax) continue;
    for (const auto& band : c.bands) {
      if (z <= band.z1_m) {
        color = band.color;
        break;
      }
    }
    best_t = t;
    kind = c.kind;
    what = 2;
    which = s.cyl_idx[k];
  }
  if (s.n_sph > 0) {
    const double a = a_xy + dz * dz;
    for (int k = 0; k < s.n_sph; ++k) {
      if (!s.sph_box[k].contains(rx, ry)) continue;
      const double b = s.sph_oc[k][0] * dx + s.sph_oc[k][1] * dy + s.sph_oc[k][2] * dz;
      const double disc = b * b - a * s.sph_c[k];
      if (disc < 0.0 || b >= 0.0) continue;
      const double t = (-b - std::sqrt(disc)) / a;
      if (t <= 0.0 || t >= best_t) continue;
      best_t = t;
      color = map_.spheres()[s.sph_idx[k]].color;
      kind = SurfaceKind::kBall;
      what = 3;
      which = s.sph_idx[k];
    }
  }
  if (what == 0) {
    const double x = s.ox + best_t * dx, y = s.oy + best_t * dy;
    color = map_.groundColorAt(x, y);
    kind = color == kGreen ? SurfaceKind::kCarpet : SurfaceKind::kLine;
  }
  if (label) *label = color;
  if constexpr (kFullHit) {
    hit->color = static_cast<ColorClass>(color);
    hit->kind = kind;
    if (what < 0) {
      hit->range_m = 0.0;
      return;
    }
    const Eigen::Vector3d d(dx, dy, dz);
    const Eigen::Vector3d o(s.ox, s.oy, s.oz);
    hit->range_m = best_t * d.norm();
    hit->point_m = o + best_t * d;
    Eigen::Vector3d n;
    if (what == 0) {
      n = Eigen::Vector3d::UnitZ();
    } else if (what == 1) {
      n = Eigen::Vector3d(quads_[which].nx, quads_[which].ny, 0.0);
    } else if (what == 2) {
      n = Eigen::Vector3d(hit->point_m.x() - cylinders_[which].cx,
                          hit->point_m.y() - cylinders_[which].cy, 0.0)
              .normalized();
    } else {
      n = (hit->point_m - map_.spheres()[which].centre_m).normalized();
    }
    if (n.dot(d) > 0.0) n = -n;
    hit->normal = n;
  }
}

void LabelRenderer::renderImage(const Eigen::Isometry3d& map_to_optical,
                                std::uint8_t* labels) const {
  PoseSetup s;
  const Eigen::Matrix3d rot = map_to_optical.linear();
  setup(map_to_optical.translation(), &rot, &s);
  const size_t n = rays_optical_.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& r = rays_optical_[i];
    const double dx = s.r[0] * r.x() + s.r[1] * r.y() + s.r[2];
    const double dy = s.r[3] * r.x() + s.r[4] * r.y() + s.r[5];
    const double dz = s.r[6] * r.x() + s.r[7] * r.y() + s.r[8];
    trace<false>(s, r.x(), r.y(), dx, dy, dz, nullptr, labels + i);
  }
}

void LabelRenderer::renderPixels(const Eigen::Isometry3d& map_to_optical, const PixelCoord* pixels,
                                 std::size_t count, std::uint8_t* out) const {
  PoseSetup s;
  const Eigen::Matrix3d rot = map_to_optical.linear();
  setup(map_to_optical.translation(), &rot, &s);
  const int w = camera_.width_px, h = camera_.height_px;
  for (size_t i = 0; i < count; ++i) {
    const PixelCoord p = pixels[i];
    if (p.u >= w || p.v >= h) {
      out[i] = kBackground;
      continue;
    }
    const Eigen::Vector3f& r = rays_optical_[static_cast<size_t>(p.v) * w + p.u];
    const double dx = s.r[0] * r.x() + s.r[1] * r.y() + s.r[2];
    const double dy = s.r[3] * r.x() + s.r[4] * r.y() + s.r[5];
    const double dz = s.r[6] * r.x() + s.r[7] * r.y() + s.r[8];
    trace<false>(s, r.x(), r.y(), dx, dy, dz, nullptr, out + i);
  }
}

void LabelRenderer::renderPixels(const Eigen::Isometry3d& map_to_optical,
                                 const std::vector<PixelCoord>& pixels,
                                 std::vector<std::uint8_t>* out) const {
  out->resize(pixels.size());
  renderPixels(map_to_optical, pixels.data(), pixels.size(), out->data());
}

void LabelRenderer::renderHitImage(const Eigen::Isometry3d& map_to_optical,
                                   std::vector<RayHit>* hits) const {
  PoseSetup s;
  const Eigen::Matrix3d rot = map_to_optical.linear();
  setup(map_to_optical.translation(), &rot, &s);
  hits->resize(rays_optical_.size());
  for (size_t i = 0; i < rays_optical_.size(); ++i) {
    const Eigen::Vector3f& r = rays_optical_[i];
    const Eigen::Vector3d d = rot * r.cast<double>();
    trace<true>(s, r.x(), r.y(), d.x(), d.y(), d.z(), &(*hits)[i], nullptr);
  }
}

RayHit LabelRenderer::castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) const {
  PoseSetup s;
  setup(origin, nullptr, &s);
  RayHit hit;
  trace<true>(s, 0.0, 0.0, dir.x(), dir.y(), dir.z(), &hit, nullptr);  // no rotation: no boxes
  return hit;
}

}  // namespace adaptive_perception::world
