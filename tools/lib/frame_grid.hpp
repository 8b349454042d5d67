// One rendered frame: the panels of overlay_draw.hpp laid out in a labelled
// grid of 2 columns x 3 rows, each cell the left image's size plus a title bar:
//
//   detections (+ ground truth)     | disparity + ground model
//   stixels by depth                | surface-normal needles by class
//   v-disparity + fitted line       | frame facts and legend
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "kitti_labels.hpp"
#include "log_frames.hpp"
#include "normal_needles.hpp"

namespace nerv::viz {

constexpr int kTitleBarPx = 26;   // height of each panel's title bar [px]
constexpr int kGridColumns = 2;
constexpr int kGridRows = 3;
constexpr int kPanelCount = kGridColumns * kGridRows;

struct GridOptions {
  NeedleParams needles;
  const std::vector<KittiLabel>* labels = nullptr;  // ground truth of this frame (may be null)
};

// Top-left corner of panel `index` (0..5, row-major) in a grid of cells `cell`.
cv::Point panelOrigin(int index, cv::Size cell);

// The frame's left image as BGR, or empty with `problem` set (no STEREO_FRAME,
// an image that does not decode, a raw view whose calibration cannot be rectified).
// A raw view (calib.rectified false) comes back rectified as the stereo_matcher
// rectifies it, so the detections and stixels drawn on it sit on their objects.
// Not thread-safe (one cache of rectification maps).
cv::Mat leftImage(const LogFrame& frame, std::string* problem);

// Renders the grid. Returns an empty Mat and sets `problem` when the frame has
// no usable left image; a missing or broken message otherwise only empties its
// panel, which says so.
cv::Mat renderFrameGrid(const LogFrame& frame, const GridOptions& options, std::string* problem);

}  // namespace nerv::viz
