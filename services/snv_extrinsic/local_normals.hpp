// Local SNV (NERV slides 20-21): the integral-image normals read only on an
// interval grid inside the ROIs and on ground samples, instead of a full map.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "integral_normals.hpp"

namespace nerv::snv {

struct LocalNormal {
  int u = 0, v = 0;  // pixel [px]
  cv::Vec3f n;       // unit normal, camera frame, facing the camera
};

// Grid pixels are those with u % interval == 0 and v % interval == 0, so the
// local normals coincide with the full-frame map of the same interval.
// Returns the number of grid pixels of `rect` inside the image (the samples);
// appends one LocalNormal per sample whose normal exists.
int localNormalsInRect(const IntegralNormalField& field, const cv::Rect& rect, int interval_px,
                       std::vector<LocalNormal>& out);

// Rows [start, end) a field must prepare so every grid pixel in `rects` can use
// its largest window (2 * max_radius_px around it).
cv::Range rowBandFor(const std::vector<cv::Rect>& rects, int image_rows, int max_radius_px);

// The rectangle a field must prepare for the grid pixels of one `rect` alone
// (IntegralNormalField::prepare with a region): rect grown by the same margin,
// clipped to the image; empty for an empty rect.
cv::Rect regionFor(const cv::Rect& rect, const cv::Size& image, int max_radius_px);

}  // namespace nerv::snv
