#include "ground_samples.hpp"

#include <algorithm>
#include <cmath>

#include "point_cloud.hpp"

namespace nerv::snv {
namespace {

bool usableModel(const GroundModel& m) {
  return m.valid && m.vd_slope > 0 && std::isfinite(m.vd_slope) && std::isfinite(m.vd_intercept);
}

}  // namespace

cv::Range groundRows(const StereoCamera& cam, const GroundModel& model,
                     const GroundSampleParams& params) {
  double first;
  if (usableModel(model)) {
    // Row where the model's ground is max_depth_m away.
    const double d_far = cam.fx * cam.baseline_m / params.max_depth_m;
    first = std::floor((d_far - model.vd_intercept) / model.vd_slope);
  } else {
    first = std::ceil(cam.cy) + params.lower_margin_px;
  }
  // Clamped before the cast: a corrupt STIXELS ground model puts this row far
  // outside int (the cast was undefined behaviour).
  const int row = std::isnan(first) ? 0 : static_cast<int>(std::clamp(first, 0.0, static_cast<double>(cam.height)));
  return cv::Range(row, cam.height);
}

bool isGroundCandidate(int v, float d, const StereoCamera& cam, const GroundModel& model,
                       const GroundSampleParams& params) {
  if (!validDisparity(d)) return false;
  const double z = cam.fx * cam.baseline_m / d;
  if (z > params.max_depth_m || z < params.min_depth_m) return false;
  if (!usableModel(model)) return v > cam.cy + params.lower_margin_px;
  const float dg = model.groundDisparity(static_cast<float>(v));
  if (!(dg > 0)) return false;
  return std::abs(d - dg) <= std::max(params.disparity_tol_px, params.disparity_tol_rel * dg);
}

std::vector<GroundSample> selectGroundSamples(const IntegralNormalField& field,
                                              const cv::Mat& disparity, const StereoCamera& cam,
                                              const GroundModel& model,
                                              const GroundSampleParams& params, cv::Range rows,
                                              int interval_px) {
  std::vector<GroundSample> out;
  if (field.empty() || rows.empty()) return out;
  const float min_up = static_cast<float>(std::cos(params.prior_cone_deg * CV_PI / 180.0));
  const float fb = static_cast<float>(cam.fx * cam.baseline_m);
  const int v0 = (std::max(rows.start, field.rowBegin()) + interval_px - 1) / interval_px * interval_px;
  const int v1 = std::min(rows.end, field.rowEnd());
  if (v0 >= v1) return out;
  // Grid rows in parallel; each keeps its samples, concatenated in row order.
  const int grid_rows = (v1 - v0 + interval_px - 1) / interval_px;
  const int grid_cols = (disparity.cols + interval_px - 1) / interval_px;
  // Per-row results in storage kept by the calling thread (capacity reused:
  // fresh vectors page-faulted ~300 KB per frame); bound to a local reference
  // because inside the parallel lambda the thread_local's name would mean the
  // worker thread's own instance.
  thread_local std::vector<std::vector<GroundSample>> kept_rows;
  std::vector<std::vector<GroundSample>>& per_row = kept_rows;
  if (per_row.size() < static_cast<size_t>(grid_rows)) per_row.resize(grid_rows);
  for (int j = 0; j < grid_rows; ++j) per_row[j].clear();
  const bool use_model = usableModel(model);
  const double fb_d = cam.fx * cam.baseline_m;
  const double max_depth = params.max_depth_m, min_depth = params.min_depth_m;
  // x / z of every grid column (the same on every row).
  std::vector<float> x_over_z(grid_cols);
  for (int i = 0; i < grid_cols; ++i) x_over_z[i] = static_cast<float>((i * interval_px - cam.cx) / cam.fx);
  cv::parallel_for_(cv::Range(0, grid_rows), [&](const cv::Range& range) {
    NormalRow row;
    std::vector<uchar> candidate(grid_cols);
    std::vector<float> grid_d(grid_cols);  // the row's grid disparities, contiguous
    for (int j = range.start; j < range.end; ++j) {
      const int v = v0 + j * interval_px;
      const float* d_row = disparity.ptr<float>(v);
      // isGroundCandidate for the whole grid row: the row's terms first, then a
      // branch-free (vectorised) test per pixel with the same arithmetic.
      float dg = 0, tol = 0;
      bool row_ok;
      if (use_model) {
        dg = model.groundDisparity(static_cast<float>(v));
        tol = std::max(params.disparity_tol_px, params.disparity_tol_rel * dg);
        row_ok = dg > 0;
      } else {
        row_ok = v > cam.cy + params.lower_margin_px;
      }
      if (!row_ok) continue;
      float* d = grid_d.data();
      for (int i = 0; i < grid_cols; ++i) d[i] = d_row[i * interval_px];
      uchar* cand = candidate.data();
      for (int i = 0; i < grid_cols; ++i) {
        const float x = d[i];
        const bool valid = (x > 0.0f) & (x < 1e6f);  // validDisparity
        const double z = fb_d / (valid ? x : 1.0f);
        const bool in_range = !(z > max_depth) & !(z < min_depth);
        const bool on_ground = !use_model | (std::abs(x - dg) <= tol);
        cand[i] = static_cast<uchar>(valid & in_range & on_ground);
      }
      int first = 0, last = grid_cols - 1;
      while (first < grid_cols && !cand[first]) ++first;
      while (last > first && !cand[last]) --last;
      if (first == grid_cols) continue;
      field.normalRow(v, first * interval_px, last - first + 1, interval_px, row);
      std::vector<GroundSample>& dst = per_row[j];
      const float y_over_z = static_cast<float>((v - cam.cy) / cam.fy);
      for (int i = first; i <= last; ++i) {
        const int k = i - first;
        if (!cand[i] || row.radius[k] < 1 || !(-row.ny[k] >= min_up)) continue;
        const float z = fb / d[i];
        dst.push_back({i * interval_px, v, cv::Vec3f(row.nx[k], row.ny[k], row.nz[k]),
                       cv::Vec3f(x_over_z[i] * z, y_over_z * z, z), d[i]});
      }
    }
  });
  size_t total = 0;
  for (int j = 0; j < grid_rows; ++j) total += per_row[j].size();
  out.reserve(total);
  for (int j = 0; j < grid_rows; ++j) out.insert(out.end(), per_row[j].begin(), per_row[j].end());
  return out;
}

}  // namespace nerv::snv
