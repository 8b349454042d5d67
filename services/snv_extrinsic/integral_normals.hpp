// Surface normals from integral images (Holzer et al., "Adaptive Neighborhood
// Selection for Real-Time Surface Normal Estimation from Organized Point Cloud
// Data Using Integral Images", IROS 2012; NERV slides 15-19).
//
// S(I,m,n,r) = box mean of I over the (2r+1)x(2r+1) window centred on (m,n),
// read from an integral image in O(1). The smoothed point at a pixel is its
// viewing ray scaled by the smoothed depth: P~(m,n) = (P_x/P_z, P_y/P_z, 1) * Z~,
// so P~_x and P~_y differences carry the smoothing of P_z (raw P_x, P_y of
// stereo carry the full depth noise). Tangents over the baseline 2r:
//   u = P~(m+r,n) - P~(m-r,n)   (horizontal)   v = P~(m,n+r) - P~(m,n-r)  (vertical)
// N = v x u (unit, facing the camera: N . P < 0).
// Adaptive window: r = min(floor((B-1)/2), floor(T/2), cap) where B is the
// chessboard distance to the nearest depth-change edge or invalid pixel (all
// smoothing windows, which reach 2r from the centre, then stay on one surface)
// and T = window_base_px + window_px_per_m * Z grows with depth (stereo depth
// noise grows with Z^2). A pixel whose r < 1 has no normal.
#pragma once

#include <opencv2/core.hpp>

#include <climits>
#include <vector>

#include "stereo_camera.hpp"

namespace nerv::snv {

struct IntegralNormalParams {
  float depth_change_px = 1.0f;    // neighbours differing by more disparity are a discontinuity [px]
  float depth_change_rel = 0.05f;  // ... or by more than this share of their disparity
  float window_base_px = 6.0f;     // T = window_base_px + window_px_per_m * Z [px]
  float window_px_per_m = 0.2f;    // growth of T with depth [px/m]
  int max_radius_px = 8;           // hard cap of r [px]
  bool smooth_disparity = true;    // smooth disparity (exact on planes) rather than P_z (Holzer)
};

// A grid of normals: normals(j, i) belongs to pixel (u = i*interval, v = j*interval).
struct NormalMap {
  int interval_px = 1;
  cv::Mat normals;  // CV_32FC3 unit normals (x, y, z), NaN where there is no normal
};

// Normals of one grid row, structure of arrays: sample i is pixel
// (u0 + i*step, v); nx/ny/nz are NaN where there is no normal, radius is r (0 = none).
struct NormalRow {
  std::vector<float> nx, ny, nz;
  std::vector<int> radius;
  void resize(int n);
};

// Integral images of one disparity map (or a band of its rows) from which the
// normal at any pixel is read in O(1). Shared by the full-frame map and the
// local (ROI / ground) normals so both give identical vectors.
//
// Value integral: when every valid value of the band is a multiple of 1/256
// (SGBM disparity is 1/16 px, KITTI ground truth 1/256 px) it holds 256 * d as
// wrapping uint32: a box sum (at most 289 * 256 * d) is then exact; otherwise
// CV_64F. Both give bit-identical box sums on quantised input.
class IntegralNormalField {
 public:
  IntegralNormalField() = default;
  // Not copyable: the integral images live in buffers that prepare() reuses.
  IntegralNormalField(const IntegralNormalField&) = delete;
  IntegralNormalField& operator=(const IntegralNormalField&) = delete;
  IntegralNormalField(IntegralNormalField&&) = default;
  IntegralNormalField& operator=(IntegralNormalField&&) = default;

  // Prepares rows [row_begin, row_end) (clamped to the image), all columns.
  // disparity: CV_32F, <= 0 invalid. Rows are prepared in parallel
  // (cv::parallel_for_). The buffers are kept and reused by the next prepare():
  // keep one field across frames.
  void prepare(const cv::Mat& disparity, const StereoCamera& cam, const IntegralNormalParams& params,
               int row_begin = 0, int row_end = INT_MAX);
  // Prepares a rectangle of the image (clamped to it). Its sides act as the
  // image border for the radius (windows stay inside), so a pixel at least
  // 2 * max_radius_px + 1 from every side that is not the image's gets the same
  // radius and normal as in a whole-image field (bit-identical in fixed point).
  void prepare(const cv::Mat& disparity, const StereoCamera& cam, const IntegralNormalParams& params,
               const cv::Rect& region);

  int rowBegin() const { return row0_; }
  int rowEnd() const { return row1_; }
  int colBegin() const { return col0_; }
  int colEnd() const { return col1_; }
  bool empty() const { return disparity_.empty(); }
  int cols() const { return disparity_.cols; }  // of the image
  // True when the value integral is the exact fixed-point (uint32) one.
  bool fixedPoint() const { return fixed_point_; }

  // --- fast path: a whole grid row at once (vectorised, no per-pixel division) ---
  // Normals of pixels (u0 + i*step, v), i < count; v in the region, u0 >= colBegin(),
  // u0 + (count-1)*step < colEnd(). Equal to adaptiveRadius + normalAt per pixel
  // (same radius; vectors within float rounding, test FastRowEqualsReference).
  void normalRow(int v, int u0, int count, int step, NormalRow& out) const;

  // --- slow, per-pixel reference path (tests, and a few single pixels) ---
  // Largest radius allowed by depth (T) and borders alone; 0 where the pixel is invalid.
  int depthRadius(int u, int v) const;
  // Adaptive radius r = min(floor((B-1)/2), depthRadius) where B is the chessboard
  // distance transform of the edge map: found from the edge integral image by
  // shrinking r until the (4r+1)^2 window holds no edge; 0 = no normal.
  int adaptiveRadius(int u, int v) const;
  // Normal with a given radius (r >= 1, windows inside the band); false when a
  // smoothed depth is not positive.
  bool normalAt(int u, int v, int r, cv::Vec3f& n) const;
  // Chessboard distance of every pixel in the band to the nearest edge (CV_32F, band rows).
  cv::Mat edgeDistance() const;
  // The band's integral images, (rows + 1) x (cols + 1) (tests): edges (CV_16U, wrapping
  // modulo 2^16: box counts of up to 255^2 pixels stay exact) and
  // values (CV_32S holding wrapping uint32 of 256 * value when fixedPoint(), else CV_64F).
  const cv::Mat& edgeIntegral() const { return edge_integral_; }
  const cv::Mat& valueIntegral() const { return value_integral_; }

 private:
  double boxSum(int u, int v, int r) const;  // value box sum (unscaled)
  int edgeCount(int u, int v, int r) const;
  float smoothedDepth(int u, int v, int r) const;
  template <bool kUnit>
  void normalRowImpl(int v, int u0, int count, int step, NormalRow& out) const;
  template <typename Acc, bool kUnit>
  void normalRuns(int v, int u0, int count, int step, NormalRow& out) const;

  cv::Mat disparity_;      // the caller's map (header only)
  cv::Mat value_integral_; // CV_32S (uint32, 256 * value) or CV_64F integral, invalid = 0, band rows
  cv::Mat edge_integral_;  // CV_16U (wrapping) integral of the edge map (1 = edge/invalid), band rows
  cv::Mat edge_integral_buffer_, fixed_buffer_, double_buffer_;  // whole-image storage of the above
  bool fixed_point_ = false;
  StereoCamera cam_;
  IntegralNormalParams params_;
  int row0_ = 0, row1_ = 0, col0_ = 0, col1_ = 0;
  float fb_ = 0, inv_fx_ = 0, inv_fy_ = 0;
};

// Full-frame SNV map at any interval (fast row path, rows in parallel with cv::parallel_for_).
NormalMap computeNormalMap(const cv::Mat& disparity, const StereoCamera& cam,
                           const IntegralNormalParams& params, int interval_px);

}  // namespace nerv::snv
