// The most textured points of a grid over a gray image: where a patch can be followed
// into the other view in both directions. The score is the smaller eigenvalue of the
// structure tensor of the central differences over a square window (Shi and Tomasi's
// corner measure), which is large only where the image changes both along and across
// rows. Used by the stereo_matcher's rectification, view-order, blank-view and shutter checks.
#pragma once

#include <opencv2/core.hpp>

#include <functional>
#include <vector>

namespace nerv::stereo {

struct TexturedPointsParams {
  int grid_px = 12;      // candidates every grid_px columns and rows
  int window_px = 11;    // square window of the score (odd); candidates keep it, plus 2 px, inside the image
  int max_points = 200;  // the highest scores kept
  double min_score = 0;  // only scores above this (the smaller eigenvalue, summed squared gray steps)
};

// The candidates that `usable(x, y)` accepts (all when empty) with a score above min_score, the
// max_points highest first-come among equals, in no particular order. image: CV_8UC1;
// anything else, or an image smaller than two windows, gives none.
std::vector<cv::Point2f> texturedPoints(const cv::Mat& image, const TexturedPointsParams& params,
                                        const std::function<bool(int x, int y)>& usable = {});

// Textured points of the left view, where the matcher's disparity puts each in the right
// view, and that disparity.
struct MatchedPoints {
  std::vector<cv::Point2f> left;
  std::vector<cv::Point2f> right;  // (x - d, y)
  std::vector<float> disparity;
};

// The textured points of the left view (as above) that have a disparity d > 0 (disparity:
// CV_32F, the left view's size) whose match x - d lies window_px / 2 + 2 px or more inside
// the right view: where a check can follow a point from one view into the other.
MatchedPoints matchedTexturedPoints(const cv::Mat& left, const cv::Mat& disparity, const TexturedPointsParams& params);

}  // namespace nerv::stereo
