// The panels of a rendered frame, each drawn from messages of the log onto an
// image of the left camera's size (BGR). Nothing here reads files or logs.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "kitti_labels.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/ground_model_t.hpp"
#include "nerv/stixels_t.hpp"
#include "normal_needles.hpp"
#include "stereo_camera.hpp"

namespace nerv::viz {

// Short code of why a hypothesis was removed: "GND", "ERR", "UNV" (from its
// label) followed by a word from its reason: "tall" / "low" / "wide" (size
// limits), "none" / "few" / "mix" (normal evidence), else the reason's first
// percentage, e.g. "GND 78%".
std::string removalCode(const detection_t& d);

// Text on a dark box, so it reads on any background. `origin` is the
// baseline's left end, as in cv::putText.
void drawLabel(cv::Mat& img, const std::string& text, cv::Point origin, const cv::Scalar& color,
               double scale = 0.45);

// Kept detections (green, 2 px, "12.3 m object"), removed hypotheses (red,
// 1 px, removal code) and, when given, ground-truth boxes (thin dashed-free
// 1 px in the label colour; DontCare grey).
void drawDetections(cv::Mat& img, const detections_t& detections);
void drawGroundTruth(cv::Mat& img, const std::vector<KittiLabel>& labels);

// The ground model on a disparity panel: pixels whose disparity lies within
// max(1 px, 5 %) of d_g(v) = vd_slope * v + vd_intercept are brightened, and
// the horizon row is drawn.
void drawGroundOnDisparity(cv::Mat& panel, const cv::Mat& disparity, const ground_model_t& ground);

// Every stixel as a translucent column coloured by its depth (colour bar in the panel),
// and a magenta band of kUnobservedBandPx rows along the lower edge under every strip
// whose free space was not measured (stixels_t.observed below min_observed).
constexpr int kUnobservedBandPx = 6;
const cv::Scalar kUnobservedColor(255, 0, 255);
void drawStixels(cv::Mat& panel, const stixels_t& stixels);

// Needles as short lines from each sample towards its projected normal,
// coloured by class; facing needles show as dots.
void drawNeedles(cv::Mat& panel, const std::vector<Needle>& needles, const StereoCamera& cam);

// v-disparity image (rows = image rows, column = disparity) of `disparity`,
// log-scaled grey, stretched to `size`, with the fitted line d = slope * v +
// intercept and the horizon row; `max_disparity` sets the column range.
cv::Mat vDisparityPanel(const cv::Mat& disparity, float max_disparity, const ground_model_t* ground,
                        cv::Size size);

// A black panel that says why it is empty ("no DISPARITY in the log").
cv::Mat emptyPanel(cv::Size size, const std::string& why);

}  // namespace nerv::viz
