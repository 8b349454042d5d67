#include "renderer.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "ground.hpp"
#include "noise.hpp"
#include "sky.hpp"

namespace nerv::synth {
namespace {

constexpr int kTile = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kShadowMargin = 0.45;  // contact shadow reaches this far beyond a footprint [m]

// Screen-space binning: for each 8x8 tile, the solids whose projected bounds
// (in either view) overlap it. `mirrored` bins the solids' reflections in the
// road instead (for rays reflected by wet patches).
struct Bins {
  int tiles_x = 0, tiles_y = 0;
  std::vector<std::vector<int>> lists;
  const std::vector<int>& at(int u, int v) const { return lists[(v / kTile) * tiles_x + u / kTile]; }
};

Bins binSolids(const World& w, const StereoCamera& k, const CameraPose& pose, bool mirrored) {
  Bins b;
  b.tiles_x = (k.width + kTile - 1) / kTile;
  b.tiles_y = (k.height + kTile - 1) / kTile;
  b.lists.resize(static_cast<size_t>(b.tiles_x) * b.tiles_y);
  const double near = 0.05;
  for (size_t i = 0; i < w.solids.size(); ++i) {
    const Solid& s = w.solids[i];
    Vec3 lo = s.lo, hi = s.hi;
    if (s.casts_shadow && !mirrored) {
      lo -= Vec3(kShadowMargin, 0, kShadowMargin);
      hi += Vec3(kShadowMargin, 0, kShadowMargin);
    }
    double u0 = kInf, u1 = -kInf, v0 = kInf, v1 = -kInf;
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
      Vec3 p = s.base + s.R * Vec3(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z());
      if (mirrored) p.y() = 2 * w.profile(p.z()) - p.y();
      const Vec3 q = pose.toCamera(p);
      if (q.z() < near) {
        ++behind;
        continue;
      }
      const double v = k.fy * q.y() / q.z() + k.cy;
      for (const double x : {q.x(), q.x() - k.baseline_m}) {
        const double u = k.fx * x / q.z() + k.cx;
        u0 = std::min(u0, u);
        u1 = std::max(u1, u);
      }
      v0 = std::min(v0, v);
      v1 = std::max(v1, v);
    }
    if (behind == 8) continue;
    if (behind > 0) {
      u0 = v0 = -1e9;
      u1 = v1 = 1e9;
    }
    const double margin = mirrored ? 8.0 : 2.0;  // mirror binning is exact only on a flat road
    const int tx0 = std::max(0, static_cast<int>(std::floor((u0 - margin) / kTile)));
    const int tx1 = std::min(b.tiles_x - 1, static_cast<int>(std::floor((u1 + margin) / kTile)));
    const int ty0 = std::max(0, static_cast<int>(std::floor((v0 - margin) / kTile)));
    const int ty1 = std::min(b.tiles_y - 1, static_cast<int>(std::floor((v1 + margin) / kTile)));
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) b.lists[static_cast<size_t>(ty) * b.tiles_x + tx].push_back(static_cast<int>(i));
  }
  return b;
}

struct Hit {
  double t = kInf;
  int solid = -1, part = -1;
  bool ground = false;
  GroundHit g;
  Vec3 p_local, n_local;
};

// Nearer hit (than hit.t) of the ray with one solid.
void traceSolid(const World& w, int idx, const Vec3& o, const Vec3& d, const Vec3& inv_d, Hit& hit) {
  const Solid& s = w.solids[idx];
  if (!overlapsBox(s.world_lo, s.world_hi, o, inv_d, 0.0, hit.t)) return;
  const Vec3 ol = s.toLocal(o), dl = s.dirToLocal(d);
  const Vec3 inv(1.0 / dl.x(), 1.0 / dl.y(), 1.0 / dl.z());
  if (!overlapsBox(s.lo, s.hi, ol, inv, 0.0, hit.t)) return;
  for (size_t p = 0; p < s.parts.size(); ++p) {
    const Part& part = s.parts[p];
    PrimitiveHit ph;
    if (!intersect(part.shape, part.c, part.e, ol, dl, 1e-6, hit.t, ph)) continue;
    hit.t = ph.t;
    hit.solid = idx;
    hit.part = static_cast<int>(p);
    hit.ground = false;
    hit.n_local = ph.normal;
    hit.p_local = ol + ph.t * dl;
  }
}

void traceSolids(const World& w, const std::vector<int>& cand, const Vec3& o, const Vec3& d, Hit& hit) {
  const Vec3 inv_d(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
  for (const int idx : cand) traceSolid(w, idx, o, d, inv_d, hit);
}

Hit trace(const World& w, const std::vector<int>& cand, const Vec3& o, const Vec3& d, bool with_ground) {
  Hit hit;
  if (with_ground && intersectGround(w, o, d, 1e-6, kInf, hit.g)) {
    hit.t = hit.g.t;
    hit.ground = true;
  }
  traceSolids(w, cand, o, d, hit);
  return hit;
}

// Texture coordinates [m] of a hit on a part: planar per box face (v = height
// on upright faces), arc length x height on cylinders and spheres.
void partUV(const Part& part, const Vec3& p, const Vec3& n, float& u, float& v) {
  switch (part.shape) {
    case Shape::Box: {
      const Vec3 a = n.cwiseAbs();
      if (a.x() >= a.y() && a.x() >= a.z()) {
        u = static_cast<float>(p.z());
        v = static_cast<float>(p.y());
      } else if (a.y() >= a.z()) {
        u = static_cast<float>(p.x());
        v = static_cast<float>(p.z());
      } else {
        u = static_cast<float>(p.x());
        v = static_cast<float>(p.y());
      }
      return;
    }
    case Shape::CylinderY:
    case Shape::Sphere: {
      const double r = part.e.x();
      u = static_cast<float>(std::atan2(p.x() - part.c.x(), p.z() - part.c.z()) * r);
      v = static_cast<float>(p.y());
      return;
    }
    case Shape::CylinderX:
      u = static_cast<float>(std::atan2(p.y() - part.c.y(), p.z() - part.c.z()) * part.e.y());
      v = static_cast<float>(p.x());
      return;
  }
}

struct Context {
  const World& w;
  double pixel_angle;  // angular size of one sample [rad]
  cv::Vec3f haze;
};

float footprintAt(const Context& ctx, double dist, double cos_incidence) {
  return static_cast<float>(ctx.pixel_angle * dist / std::sqrt(std::max(std::abs(cos_incidence), 0.02)));
}

cv::Vec3f lit(const World& w, const cv::Vec3f& albedo, const Vec3& n_world) {
  const double diffuse = std::max(0.0, n_world.dot(w.sun_dir));
  return albedo * static_cast<float>(0.55 + 0.5 * diffuse);
}

cv::Vec3f applyHaze(const Context& ctx, const cv::Vec3f& c, double dist) {
  const float k = static_cast<float>(std::exp(-dist / 900.0));
  return c * k + ctx.haze * (1 - k);
}

cv::Vec3f shadeSolid(const Context& ctx, const Hit& hit, const Vec3& d) {
  const Solid& s = ctx.w.solids[hit.solid];
  const Part& part = s.parts[hit.part];
  const Vec3 n_world = s.R * hit.n_local;
  const double dist = hit.t * d.norm();
  const float fp = footprintAt(ctx, dist, n_world.dot(d.normalized()));
  float u = 0, v = 0;
  partUV(part, hit.p_local, hit.n_local, u, v);
  const cv::Vec3f a = albedo(part.surface, u, v, hit.p_local, hit.n_local, fp, s.seed);
  return applyHaze(ctx, lit(ctx.w, a, n_world), dist);
}

// Darkening of the ground under vehicles (ambient occlusion of the contact area).
float contactShadow(const World& w, const std::vector<int>& cand, const Vec3& p) {
  float shade = 1.0f;
  for (const int idx : cand) {
    const Solid& s = w.solids[idx];
    if (!s.casts_shadow) continue;
    const Vec3 q = s.toLocal(p);
    const double ox = std::abs(q.x()) - s.width_m / 2, oz = std::abs(q.z()) - s.length_m / 2;
    const double outside = std::max(std::max(ox, oz), -0.25);
    if (outside > kShadowMargin) continue;
    shade = std::min(shade, 0.35f + 0.65f * smoothstep(-0.25f, float(kShadowMargin), float(outside)));
  }
  return shade;
}

// Colour seen along one sample ray; `mcand` are the solids whose reflection
// may appear at this pixel.
cv::Vec3f shadeHit(const Context& ctx, const Hit& hit, const std::vector<int>& cand,
                   const std::vector<int>& mcand, const Vec3& d, int view) {
  const World& w = ctx.w;
  if (hit.t == kInf) return skyColour(w, d, static_cast<float>(ctx.pixel_angle));
  if (!hit.ground) return shadeSolid(ctx, hit, d);
  const double dist = hit.t * d.norm();
  const Vec3 dn = d.normalized();
  const float fp = footprintAt(ctx, dist, hit.g.normal.dot(dn));
  cv::Vec3f c = lit(w, groundAlbedo(w, hit.g, fp), hit.g.normal);
  if (hit.g.zone != GroundZone::Curb) c *= contactShadow(w, cand, hit.g.point);
  if (hit.g.zone == GroundZone::Road && wetPatchAt(w, hit.g.point) >= 0) {
    // Wet asphalt: darker, mirrors the scene, and sparkles differently in each
    // view (specular glints depend on the viewpoint).
    const Vec3& n = hit.g.normal;
    const Vec3 r = d - 2 * d.dot(n) * n;
    const Vec3 p = hit.g.point + n * 1e-4;
    Hit rh;
    traceSolids(w, mcand, p, r, rh);
    cv::Vec3f mirror;
    if (rh.t == kInf)
      mirror = skyColour(w, r, static_cast<float>(ctx.pixel_angle));
    else
      mirror = shadeSolid(ctx, rh, r);
    const float refl = static_cast<float>(w.traps.reflectivity);
    const float x = static_cast<float>(hit.g.point.x()), z = static_cast<float>(hit.g.point.z());
    const float g = std::max(0.0f, valueNoise(x * 28.0f, z * 9.0f, w.seed + 977u * (view + 1)) - 0.45f) / 0.55f;
    const float glitter = static_cast<float>(w.traps.glitter) * g * g;
    c = c * (0.5f * (1 - refl)) + mirror * refl + cv::Vec3f(glitter, glitter, glitter);
  }
  return applyHaze(ctx, c, dist);
}

cv::Vec3f shade(const Context& ctx, const std::vector<int>& cand, const std::vector<int>& mcand,
                const Vec3& o, const Vec3& d, int view) {
  return shadeHit(ctx, trace(ctx.w, cand, o, d, true), cand, mcand, d, view);
}

}  // namespace

RenderedFrame renderFrame(const World& w, const CameraRig& rig, const CameraPose& pose, int frame,
                          uint64_t seed, const RenderOptions& options) {
  const StereoCamera& k = rig.intrinsics;
  const int W = k.width, H = k.height;
  const int ss = std::max(1, options.supersample);
  const Bins bins = binSolids(w, k, pose, false);
  const Bins mirror_bins = binSolids(w, k, pose, true);
  // Quincunx (ss = 2): a pixel averages its centre (weight 1/2) and its four
  // corners (1/8 each), corners shared with the neighbours: 2 rays per pixel
  // and view for an anti-aliasing filter about as wide as 2x2 supersampling.
  const bool quincunx = ss == 2;
  Context ctx{w, quincunx ? 0.7 / k.fx : 1.0 / (k.fx * ss), cv::Vec3f(205, 200, 195)};

  RenderedFrame out;
  cv::Mat3f colour[2] = {cv::Mat3f(H, W), cv::Mat3f(H, W)};
  out.disparity.create(H, W, CV_32F);
  out.object_id.create(H, W, CV_32S);
  out.trap_mask.create(H, W, CV_8U);
  out.unoccluded_px.assign(w.solids.size(), 0);
  std::mutex merge;
  // Occlusion levels are only reported for labelled obstacles.
  std::vector<char> occlusion_needed(w.solids.size());
  for (size_t i = 0; i < w.solids.size(); ++i)
    occlusion_needed[i] = !w.solids[i].type.empty() && w.solids[i].type != "DontCare";
  const Vec3 centres[2] = {pose.centre, pose.rightCentre(k.baseline_m)};
  auto ray = [&](double su, double sv) {
    return Vec3(pose.right * ((su - k.cx) / k.fx) + pose.down * ((sv - k.cy) / k.fy) + pose.forward);
  };
  // Colour of the sample at image point (su, sv); the tile of the nearest
  // pixel lists every solid that can appear there (bins have a 2 px margin).
  auto sample = [&](int view, double su, double sv) {
    const int pu = std::clamp(static_cast<int>(std::lround(su)), 0, W - 1);
    const int pv = std::clamp(static_cast<int>(std::lround(sv)), 0, H - 1);
    return shade(ctx, bins.at(pu, pv), mirror_bins.at(pu, pv), centres[view], ray(su, sv), view);
  };
  auto cornerRow = [&](int view, int cv_row, std::vector<cv::Vec3f>& row) {
    row.resize(W + 1);
    for (int cu = 0; cu <= W; ++cu) row[cu] = sample(view, cu - 0.5, cv_row - 0.5);
  };

  auto rows = [&](const cv::Range& range) {
    std::vector<int> unoccluded(w.solids.size(), 0);
    std::vector<cv::Vec3f> top[2], bottom[2];
    if (quincunx)
      for (int view = 0; view < 2; ++view) cornerRow(view, range.start, top[view]);
    for (int v = range.start; v < range.end; ++v) {
      if (quincunx)
        for (int view = 0; view < 2; ++view) cornerRow(view, v + 1, bottom[view]);
      for (int u = 0; u < W; ++u) {
        const std::vector<int>& cand = bins.at(u, v);
        const std::vector<int>& mcand = mirror_bins.at(u, v);
        // Ground truth along the pixel-centre ray of the left view.
        const Vec3 d = ray(u, v);
        const Hit hit = trace(w, cand, pose.centre, d, true);
        bool trap = false;
        if (hit.t == kInf) {
          out.disparity.at<float>(v, u) = 0;
          out.object_id.at<int>(v, u) = -1;
          if (w.traps.overexposed_sky) {
            const cv::Vec3f c = skyColour(w, d, static_cast<float>(ctx.pixel_angle));
            trap = std::min(c[0], std::min(c[1], c[2])) >= 250.0f;
          }
        } else {
          out.disparity.at<float>(v, u) = static_cast<float>(k.fx * k.baseline_m / hit.t);
          out.object_id.at<int>(v, u) = hit.ground ? -1 : hit.solid;
          if (hit.ground)
            trap = hit.g.zone == GroundZone::Road && wetPatchAt(w, hit.g.point) >= 0;
          else
            trap = w.solids[hit.solid].parts[hit.part].trap;
        }
        out.trap_mask.at<uchar>(v, u) = trap ? 255 : 0;
        const Vec3 inv_d(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
        for (const int idx : cand) {
          if (!occlusion_needed[idx]) continue;
          Hit alone;
          traceSolid(w, idx, pose.centre, d, inv_d, alone);
          if (alone.solid == idx) ++unoccluded[idx];
        }
        for (int view = 0; view < 2; ++view) {
          cv::Vec3f c;
          if (quincunx) {
            const cv::Vec3f centre = view == 0 ? shadeHit(ctx, hit, cand, mcand, d, 0) : sample(1, u, v);
            c = 0.5f * centre + 0.125f * (top[view][u] + top[view][u + 1] + bottom[view][u] + bottom[view][u + 1]);
          } else if (ss == 1) {
            c = view == 0 ? shadeHit(ctx, hit, cand, mcand, d, 0) : sample(1, u, v);
          } else {
            c = cv::Vec3f(0, 0, 0);
            for (int sy = 0; sy < ss; ++sy)
              for (int sx = 0; sx < ss; ++sx)
                c += sample(view, u + (sx + 0.5) / ss - 0.5, v + (sy + 0.5) / ss - 0.5);
            c *= 1.0f / (ss * ss);
          }
          colour[view](v, u) = c;
        }
      }
      if (quincunx)
        for (int view = 0; view < 2; ++view) std::swap(top[view], bottom[view]);
    }
    std::lock_guard<std::mutex> lock(merge);
    for (size_t i = 0; i < unoccluded.size(); ++i) out.unoccluded_px[i] += unoccluded[i];
  };
  if (options.threads == 1)
    rows(cv::Range(0, H));
  else
    cv::parallel_for_(cv::Range(0, H), rows, std::max(1, std::min(16, H / 8)));

  // Sensor: per-camera Gaussian noise, right camera gain/offset, 8-bit clipping.
  for (int view = 0; view < 2; ++view) {
    cv::Mat3f noise(H, W);
    cv::RNG rng(seed * 1000003ull + static_cast<uint64_t>(frame) * 2 + view + 1);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, rig.noise_sigma);
    cv::Mat3f img = colour[view] + noise;
    if (view == 1) img = img * rig.right_gain + cv::Scalar::all(rig.right_offset);
    img.convertTo(view == 0 ? out.left : out.right, CV_8UC3);
  }
  return out;
}

}  // namespace nerv::synth
