// Does one view show nothing? A lens cap, a covered, fogged or iced lens, a dead or
// saturated sensor: the matcher finds nothing, the stages behind it report unobserved
// strips and no ground, and nothing says which camera to look at. When one view holds
// textured points and the other almost none, that view is blank.
#pragma once

#include <opencv2/core.hpp>

#include <string>

namespace nerv::stereo {

struct BlankViewParams {
  int grid_px = 12;
  int window_px = 11;
  // A textured point: the structure tensor's smaller eigenvalue over the 11 x 11 window
  // above this (121 px x a mean squared gray step of 100, about 10 gray levels over two
  // pixels in both directions); sensor noise of a few gray levels stays far below.
  double min_score = 121.0 * 100.0;
  int max_points = 300;        // counting stops here
  int min_textured = 50;       // the other view must have at least this many
  double max_share = 0.1;      // blank: fewer than this share of the other view's
};

struct ViewTexture {
  int left = 0, right = 0;  // textured points counted (at most max_points)
  std::string blank;        // "", "left" or "right"
};

ViewTexture compareViewTexture(const cv::Mat& left, const cv::Mat& right, const BlankViewParams& params = {});

}  // namespace nerv::stereo
