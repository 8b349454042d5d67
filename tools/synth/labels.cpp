#include "labels.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace nerv::synth {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxLabelDistance_m = 80.0;

double wrapAngle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

// Share of the 3D box's projection outside the image (1 when it reaches behind the camera).
double truncation(const Solid& s, const StereoCamera& k, const CameraPose& pose) {
  double u0 = 1e30, u1 = -1e30, v0 = 1e30, v1 = -1e30;
  for (int c = 0; c < 8; ++c) {
    const Vec3 local((c & 1 ? 0.5 : -0.5) * s.width_m, c & 2 ? s.height_m : 0.0,
                     (c & 4 ? 0.5 : -0.5) * s.length_m);
    const Vec3 q = pose.toCamera(s.base + s.R * local);
    if (q.z() < 0.1) return 1.0;
    const double u = k.fx * q.x() / q.z() + k.cx, v = k.fy * q.y() / q.z() + k.cy;
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  const double full = (u1 - u0) * (v1 - v0);
  const double iw = std::max(0.0, std::min(u1, k.width - 0.5) - std::max(u0, -0.5));
  const double ih = std::max(0.0, std::min(v1, k.height - 0.5) - std::max(v0, -0.5));
  return full > 0 ? std::clamp(1.0 - iw * ih / full, 0.0, 1.0) : 1.0;
}

// The outermost columns of box [x0..x1] x [y0..y1] that see at least min_run
// pixels of object id (unchanged when none does).
void trimSlivers(const cv::Mat& object_id, int id, int min_run, int& x0, int y0, int& x1, int y1) {
  std::vector<int> cols(static_cast<size_t>(x1 - x0 + 1), 0);
  for (int v = y0; v <= y1; ++v) {
    const int* row = object_id.ptr<int>(v);
    for (int u = x0; u <= x1; ++u) cols[static_cast<size_t>(u - x0)] += row[u] == id;
  }
  int c0 = -1, c1 = -1;
  for (size_t i = 0; i < cols.size(); ++i)
    if (cols[i] >= min_run) c1 = static_cast<int>(i), c0 = c0 < 0 ? c1 : c0;
  if (c0 < 0) return;
  x1 = x0 + c1, x0 += c0;
}

}  // namespace

std::vector<Label> makeLabels(const World& world, const StereoCamera& k, const CameraPose& pose,
                              const RenderedFrame& frame, int min_pixels, int min_run_px) {
  const size_t n = world.solids.size();
  std::vector<int> count(n, 0), x0(n, INT32_MAX), y0(n, INT32_MAX), x1(n, -1), y1(n, -1);
  for (int v = 0; v < frame.object_id.rows; ++v) {
    const int* row = frame.object_id.ptr<int>(v);
    for (int u = 0; u < frame.object_id.cols; ++u) {
      const int id = row[u];
      if (id < 0) continue;
      ++count[id];
      x0[id] = std::min(x0[id], u);
      x1[id] = std::max(x1[id], u);
      y0[id] = std::min(y0[id], v);
      y1[id] = std::max(y1[id], v);
    }
  }
  std::vector<Label> labels;
  for (size_t i = 0; i < n; ++i) {
    const Solid& s = world.solids[i];
    if (s.type.empty() || count[i] < std::max(1, min_pixels)) continue;
    Label l;
    l.type = s.type;
    l.solid = static_cast<int>(i);
    l.left = x0[i];
    l.top = y0[i];
    l.right = x1[i];
    l.bottom = y1[i];
    if (min_run_px > 0 && s.type != "DontCare")
      trimSlivers(frame.object_id, static_cast<int>(i), min_run_px, l.left, l.top, l.right, l.bottom);
    l.visible_px = count[i];
    // Obstacles beyond the labelled range are DontCare, as in KITTI's hand labels.
    if (s.type != "DontCare" && pose.toCamera(s.base).z() > kMaxLabelDistance_m) l.type = "DontCare";
    if (l.type != "DontCare") {
      l.truncation = truncation(s, k, pose);
      const int unoccluded = std::max(count[i], frame.unoccluded_px[i]);
      const double visible = double(count[i]) / unoccluded;
      l.occlusion = visible >= 0.85 ? 0 : (visible >= 0.45 ? 1 : 2);
      l.height_m = s.height_m;
      l.width_m = s.width_m;
      l.length_m = s.length_m;
      l.location = pose.toCamera(s.base);
      const Vec3 heading = s.R.col(2);
      const Vec3 h(pose.right.dot(heading), pose.down.dot(heading), pose.forward.dot(heading));
      // KITTI: the object's x axis (its length) is (cos ry, 0, -sin ry) in the camera frame.
      l.rotation_y = std::atan2(-h.z(), h.x());
      l.alpha = wrapAngle(l.rotation_y - std::atan2(l.location.x(), l.location.z()));
    }
    labels.push_back(l);
  }
  return labels;
}

std::string formatLabel(const Label& l) {
  char buf[320];
  if (l.type == "DontCare") {
    std::snprintf(buf, sizeof buf,
                  "DontCare -1 -1 -10 %.2f %.2f %.2f %.2f -1 -1 -1 -1000 -1000 -1000 -10",
                  double(l.left), double(l.top), double(l.right), double(l.bottom));
  } else {
    std::snprintf(buf, sizeof buf, "%s %.2f %d %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f",
                  l.type.c_str(), l.truncation, l.occlusion, l.alpha, double(l.left), double(l.top),
                  double(l.right), double(l.bottom), l.height_m, l.width_m, l.length_m, l.location.x(),
                  l.location.y(), l.location.z(), l.rotation_y);
  }
  return buf;
}

}  // namespace nerv::synth
