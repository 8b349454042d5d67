#include "ground_line_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ground_geometry.hpp"

namespace nerv::stixel {

namespace {

struct Cell {
  float v, d, w;  // row, mean disparity, pixel count
};

// Strongest cells of each row: the road is the mode of a row's histogram below
// the horizon, while scattered mismatches spread thinly over many bins.
std::vector<Cell> votingCells(const VDisparity& vd, const GroundLineFitParams& p) {
  const int min_count = std::max(3, static_cast<int>(p.min_cell_fraction * vd.sampled_columns));
  std::vector<Cell> cells;
  std::vector<std::pair<int, int>> row;  // (count, bin)
  for (int v = 0; v < vd.rows; ++v) {
    row.clear();
    const int* count = &vd.count[static_cast<size_t>(v) * vd.bins];
    // Bin 0 (d < 1 px) carries no slope information. Most bins hold fewer than
    // min_count pixels: blocks of 8 are tested at once (a loop the compiler
    // vectorizes) and only blocks with a strong bin are walked.
    int k = 1;
    for (; k + 8 <= vd.bins; k += 8) {
      int any = 0;
      for (int j = 0; j < 8; ++j) any |= count[k + j] >= min_count;
      if (!any) continue;
      for (int j = 0; j < 8; ++j)
        if (count[k + j] >= min_count) row.emplace_back(count[k + j], k + j);
    }
    for (; k < vd.bins; ++k)
      if (count[k] >= min_count) row.emplace_back(count[k], k);
    const int keep = std::min<int>(p.max_cells_per_row, static_cast<int>(row.size()));
    std::partial_sort(row.begin(), row.begin() + keep, row.end(),
                      [](const auto& x, const auto& y) { return x.first > y.first; });
    for (int i = 0; i < keep; ++i)
      cells.push_back({static_cast<float>(v), vd.cellMean(v, row[i].second),
                       static_cast<float>(row[i].first)});
  }
  return cells;
}

// Weighted least squares d = a*v + b.
bool solveLine(const std::vector<Cell>& c, const std::vector<float>& w, float& a, float& b) {
  double sw = 0, sv = 0, sd = 0, svv = 0, svd = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    if (w[i] <= 0) continue;
    sw += w[i];
    sv += w[i] * c[i].v;
    sd += w[i] * c[i].d;
    svv += w[i] * c[i].v * c[i].v;
    svd += w[i] * c[i].v * c[i].d;
  }
  const double det = sw * svv - sv * sv;
  if (sw <= 0 || std::abs(det) < 1e-9 * sw * sw) return false;
  a = static_cast<float>((sw * svd - sv * sd) / det);
  b = static_cast<float>((sd - a * sv) / sw);
  return true;
}

}  // namespace

GroundLine fitGroundLine(const VDisparity& vd, const StereoCamera& cam,
                         const GroundLineFitParams& p) {
  GroundLine out;
  const std::vector<Cell> cells = votingCells(vd, p);
  if (cells.size() < 2) {
    out.reason = "too few v-disparity cells";
    return out;
  }

  // Hough space (slope a, horizon row vh) with d = a*(v - vh), bounded by the pose
  // limits: a = fx*B*cos(theta)/(fy*h) and vh = cy - fy*tan(theta).
  const double max_t = p.max_pitch_deg * M_PI / 180.0;
  const double k = cam.fx * cam.baseline_m / cam.fy;
  const double a_min = k * std::cos(max_t) / p.max_camera_height_m;
  const double a_max = k / p.min_camera_height_m;
  const double vh_min = cam.cy - cam.fy * std::tan(max_t);
  const double vh_max = cam.cy + cam.fy * std::tan(max_t);
  // Slope steps such that a line drifts ~1.5 px (half a step) over the image
  // height: finer than the IRLS capture band below.
  const int na = std::clamp(static_cast<int>((a_max - a_min) * vd.rows / 3) + 1, 32, 256);
  const int nh = std::max(3, static_cast<int>(std::ceil(vh_max - vh_min)) + 1);
  // The accumulator is stored horizon-major (acc[j * na + i]): a cell's votes
  // for neighbouring slopes land in neighbouring horizon bins, so this way they
  // share cache lines; slope-major, each vote touched another line of a space
  // too large for the first-level cache.
  std::vector<float> acc(static_cast<size_t>(na) * nh, 0.0f);
  std::vector<double> inv_a(na);
  for (int i = 0; i < na; ++i) inv_a[i] = 1.0 / (a_min + (a_max - a_min) * i / (na - 1));
  // A cell's horizon bin x = base - d / a grows with the slope index (d > 0 and
  // 1/a falls, both exactly monotonic in floating point), so its votes inside
  // the space form one run of slopes: found by two bisections on the same
  // expression, then added without a test per slope.
  const double nh_d = nh;
  for (const Cell& c : cells) {
    const double base = c.v - vh_min + 0.5;  // + 0.5: truncation below rounds
    auto xAt = [&](int i) { return base - c.d * inv_a[i]; };
    // First slope in [lo, na) whose x reaches `bound` (x grows with the slope).
    auto firstReaching = [&](int lo, double bound) {
      int hi = na;
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (xAt(mid) >= bound) hi = mid;
        else lo = mid + 1;
      }
      return lo;
    };
    const int first = firstReaching(0, 0.0), end = firstReaching(first, nh_d);
    for (int i = first; i < end; ++i) acc[static_cast<size_t>(static_cast<int>(xAt(i)) * na + i)] += c.w;
  }
  // 3x3 box sum (separable): a cell's disparity noise scatters its vote over
  // neighbouring horizon bins.
  std::vector<float> hsum(acc.size(), 0.0f);
  for (int j = 1; j + 1 < nh; ++j)
    for (int i = 0; i < na; ++i) {
      const size_t o = static_cast<size_t>(j) * na + i;
      hsum[o] = acc[o - na] + acc[o] + acc[o + na];
    }
  // The first maximum in slope-major order (smallest slope, then smallest
  // horizon), whichever order the loops run in.
  float best = 0;
  int bi = -1, bj = -1;
  for (int j = 1; j + 1 < nh; ++j)
    for (int i = 1; i + 1 < na; ++i) {
      const size_t o = static_cast<size_t>(j) * na + i;
      const float s = hsum[o - 1] + hsum[o] + hsum[o + 1];
      if (s > best || (s == best && bi >= 0 && i < bi)) best = s, bi = i, bj = j;
    }
  if (bi < 0) {
    out.reason = "no Hough peak";
    return out;
  }
  float a = static_cast<float>(1.0 / inv_a[bi]);
  float b = static_cast<float>(-a * (vh_min + bj));

  // IRLS with Huber weights on the cells near the current line; the band shrinks
  // from twice the tolerance so a coarse Hough peak still captures the road.
  // Obstacles standing on the road put cells just above the line in the rows
  // of their feet (their disparity exceeds the road's there), never below it;
  // within a symmetric band they tilt the line (synthetic urban: +0.28 deg
  // pitch, +3 cm height), so that side gets its own, tighter band.
  std::vector<float> w(cells.size());
  const float huber_px = 0.5f;
  const float above_px = p.obstacle_side_tolerance_px > 0
                             ? std::min(p.obstacle_side_tolerance_px, p.inlier_tolerance_px)
                             : p.inlier_tolerance_px;
  for (int it = 0; it < 30; ++it) {
    const float scale = it == 0 ? 2.0f : 1.0f;
    for (size_t i = 0; i < cells.size(); ++i) {
      const float signed_r = cells[i].d - (a * cells[i].v + b);
      const float r = std::abs(signed_r);
      const float band = scale * (signed_r > 0 ? above_px : p.inlier_tolerance_px);
      w[i] = r > band ? 0.0f : cells[i].w * (r <= huber_px ? 1.0f : huber_px / r);
    }
    float na_, nb_;
    if (!solveLine(cells, w, na_, nb_)) break;
    const bool settled = std::abs(na_ - a) < 1e-6f && std::abs(nb_ - b) < 1e-4f;
    a = na_, b = nb_;
    if (settled) break;
  }

  // Support of the final line.
  double sw = 0, sr2 = 0;
  float dmin = 1e30f, dmax = -1e30f;
  int last_row = -1;
  for (const Cell& c : cells) {
    const float r = c.d - (a * c.v + b);
    if (std::abs(r) > p.inlier_tolerance_px) continue;
    ++out.inlier_cells;
    if (static_cast<int>(c.v) != last_row) ++out.inlier_rows, last_row = static_cast<int>(c.v);
    sw += c.w;
    sr2 += c.w * r * r;
    dmin = std::min(dmin, c.d);
    dmax = std::max(dmax, c.d);
  }
  out.slope = a;
  out.intercept = b;
  out.residual_px = sw > 0 ? static_cast<float>(std::sqrt(sr2 / sw)) : 0.0f;

  if (!(a > 0) || !std::isfinite(b)) {
    out.reason = "ground line has no positive slope";
    return out;
  }
  if (out.inlier_rows < p.min_inlier_rows) {
    out.reason = "ground line supported by only " + std::to_string(out.inlier_rows) + " rows";
    return out;
  }
  if (dmax - dmin < p.min_disparity_span_px) {
    out.reason = "ground inliers span too small a disparity range";
    return out;
  }
  const LinePose pose = poseFromGroundLine(a, b, cam);
  if (!(pose.height_m >= p.min_camera_height_m && pose.height_m <= p.max_camera_height_m)) {
    out.reason = "ground line implies camera height " + std::to_string(pose.height_m) + " m";
    return out;
  }
  if (!(std::abs(pose.pitch_deg) <= p.max_pitch_deg)) {
    out.reason = "ground line implies pitch " + std::to_string(pose.pitch_deg) + " deg";
    return out;
  }
  out.ok = true;
  return out;
}

}  // namespace nerv::stixel
