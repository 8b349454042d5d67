// A textured wall seen by a rig whose right view has left its calibration, and one frame of it
// run as the stereo_matcher runs it (the right view corrected, matched, checked), for the tests of
// the rig's corrections (view_correction.hpp, rig_check.hpp, rig_state.hpp).
#pragma once

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

#include "rig_check.hpp"
#include "stereo_scene_texture.hpp"

namespace nerv::stereo {

inline cv::Mat wallTexture(unsigned seed) { return multiScaleTexture(640, 240, seed); }

// The right view of a wall at disparity 20, its content moved down by dy rows and turned by
// turn_deg about the view's centre (a point at u from the centre moves tan(turn) u down).
inline cv::Mat movedRightView(const cv::Mat& left, double dy, double turn_deg = 0) {
  const double t = turn_deg * CV_PI / 180, cx = 0.5 * left.cols, cy = 0.5 * left.rows;
  // right(p) = left(q + 20 columns) with p = R (q - c) + c + (0, dy): the inverse map.
  const double c = std::cos(t), s = std::sin(t);
  // q = R^T (p - c - (0, dy)) + c, then + 20 columns.
  const cv::Mat inverse = (cv::Mat_<double>(2, 3) << c, s, -c * cx - s * (cy + dy) + cx + 20,  //
                           -s, c, s * cx - c * (cy + dy) + cy);
  cv::Mat right;
  cv::warpAffine(left, right, inverse, left.size(), cv::INTER_CUBIC | cv::WARP_INVERSE_MAP, cv::BORDER_REFLECT);
  return right;
}

// Mean absolute gray difference over the view's middle (away from the borders a shift fills).
inline double meanViewDifference(const cv::Mat& a, const cv::Mat& b) {
  const cv::Rect inner(40, 30, a.cols - 80, a.rows - 60);
  cv::Mat d;
  cv::absdiff(a(inner), b(inner), d);
  return cv::mean(d)[0];
}

// The wall's disparity, as the matcher would find it.
inline const cv::Mat& wallDisparity() {
  static const cv::Mat wall(240, 640, CV_32FC1, cv::Scalar(20.0f));
  return wall;
}

// One frame as the service runs it: the right view corrected, matched (here: the wall), checked.
inline std::vector<RigFinding> wallFrame(RigCheck& rig, const cv::Mat& left, const cv::Mat& right) {
  const cv::Mat matched = rig.rightToMatch(right);
  return rig.afterMatching(left, matched, wallDisparity());
}

}  // namespace nerv::stereo
