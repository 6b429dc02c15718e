// Pan, zoom, rotation and flip of the map view as one affine map (see view_transform.hpp).
#include "viewer/core/view_transform.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slam::viewer {

Affine2 Affine2::then(const Affine2& n) const {
  return {n.a * a + n.c * b, n.b * a + n.d * b,          n.a * c + n.c * d,
          n.b * c + n.d * d, n.a * tx + n.c * ty + n.tx, n.b * tx + n.d * ty + n.ty};
}

Affine2 Affine2::inverse() const {
  const double det = a * d - b * c;
  const double ia = d / det, ib = -b / det, ic = -c / det, id = a / det;
  return {ia, ib, ic, id, -(ia * tx + ic * ty), -(ib * tx + id * ty)};
}

void Affine2::to_mat3(float out[9]) const {
  const double m[9] = {a, b, 0.0, c, d, 0.0, tx, ty, 1.0};
  for (int i = 0; i < 9; ++i) out[i] = static_cast<float>(m[i]);
}

Affine2 ViewTransform::world_to_screen_affine() const {
  const double cs = std::cos(angle_), sn = std::sin(angle_);
  const double k = flip_y_ ? 1.0 : -1.0;  // screen y grows downwards
  Affine2 m{scale_ * cs, k * scale_ * sn, -scale_ * sn, k * scale_ * cs, 0.0, 0.0};
  const double cx = viewport_.x + viewport_.width / 2.0, cy = viewport_.y + viewport_.height / 2.0;
  m.tx = cx - (m.a * center_.x + m.c * center_.y);
  m.ty = cy - (m.b * center_.x + m.d * center_.y);
  return m;
}

Affine2 ViewTransform::world_to_ndc() const {
  const double w = viewport_.width, h = viewport_.height;
  const Affine2 to_ndc{
      2.0 / w, 0.0, 0.0, -2.0 / h, -2.0 * viewport_.x / w - 1.0, 2.0 * viewport_.y / h + 1.0};
  return world_to_screen_affine().then(to_ndc);
}

void ViewTransform::pan_pixels(Vec2 from, Vec2 to) {
  const Vec2 a = screen_to_world(from), b = screen_to_world(to);
  center_.x += a.x - b.x;
  center_.y += a.y - b.y;
}

void ViewTransform::zoom_about(Vec2 cursor, double factor) {
  const Vec2 before = screen_to_world(cursor);
  scale_ = std::clamp(scale_ * factor, kMinScale, kMaxScale);
  const Vec2 after = screen_to_world(cursor);
  center_.x += before.x - after.x;
  center_.y += before.y - after.y;
}

void ViewTransform::rotate_about(Vec2 pivot, double radians) {
  const Vec2 before = screen_to_world(pivot);
  angle_ = std::remainder(angle_ + (flip_y_ ? -radians : radians), 2.0 * M_PI);
  const Vec2 after = screen_to_world(pivot);
  center_.x += before.x - after.x;
  center_.y += before.y - after.y;
}

void ViewTransform::set_flip_y(bool flip) {
  flip_y_ = flip;
}

void ViewTransform::fit(const WorldBox& box, double margin) {
  const double bw = std::max(box.max_x - box.min_x, 1e-3), bh = std::max(box.max_y - box.min_y, 1e-3);
  const double cs = std::abs(std::cos(angle_)), sn = std::abs(std::sin(angle_));
  const double ex = cs * bw + sn * bh, ey = sn * bw + cs * bh;
  const double s = std::min(viewport_.width / ex, viewport_.height / ey) / (1.0 + 2.0 * margin);
  scale_ = std::clamp(s, kMinScale, kMaxScale);
  center_ = {(box.min_x + box.max_x) / 2.0, (box.min_y + box.max_y) / 2.0};
}

void ViewTransform::set(Vec2 center, double scale, double angle, bool flip_y) {
  center_ = center;
  scale_ = std::clamp(scale, kMinScale, kMaxScale);
  angle_ = angle;
  flip_y_ = flip_y;
}

std::string ViewTransform::describe() const {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "view center=%.17g,%.17g scale=%.17g angle=%.17g flip=%d viewport=%.17g,%.17g,%.17g,%.17g",
                center_.x, center_.y, scale_, angle_, flip_y_ ? 1 : 0, viewport_.x, viewport_.y,
                viewport_.width, viewport_.height);
  return buf;
}

Result<ViewTransform> ViewTransform::parse(const std::string& line) {
  const auto at = line.find("view center=");
  if (at == std::string::npos) return Error{"no 'view center=' in line: " + line};
  ViewTransform v;
  int flip = 0;
  Viewport vp;
  const int n = std::sscanf(
      line.c_str() + at, "view center=%lf,%lf scale=%lf angle=%lf flip=%d viewport=%lf,%lf,%lf,%lf",
      &v.center_.x, &v.center_.y, &v.scale_, &v.angle_, &flip, &vp.x, &vp.y, &vp.width, &vp.height);
  if (n != 9) return Error{"malformed view line (expected 9 fields, got " + std::to_string(n) + "): " + line};
  if (!(v.scale_ > 0.0) || !(vp.width > 0.0) || !(vp.height > 0.0))
    return Error{"view line has a non-positive size: " + line};
  v.flip_y_ = flip != 0;
  v.viewport_ = vp;
  return v;
}

bool ViewTransform::operator==(const ViewTransform& o) const {
  return center_.x == o.center_.x && center_.y == o.center_.y && scale_ == o.scale_ && angle_ == o.angle_ &&
         flip_y_ == o.flip_y_ && viewport_.x == o.viewport_.x && viewport_.y == o.viewport_.y &&
         viewport_.width == o.viewport_.width && viewport_.height == o.viewport_.height;
}

}  // namespace slam::viewer
