// Conversions between the LCM messages and the plain types the algorithms use.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"
#include "perception_types.hpp"
#include "rectification.hpp"
#include "stereo_camera.hpp"

namespace nerv {

StereoCamera toCamera(const stereo_calibration_t& calib);
stereo_calibration_t toCalibration(const StereoCamera& cam);
// The raw block (rectified = false) of a calibration message.
RawStereoCalibration toRawCalibration(const stereo_calibration_t& calib);
// A raw pair's calibration message: rectified = false, the raw block from `raw`, and the
// first block from `rectified` (the camera the receiver's rectification gives).
stereo_calibration_t toCalibration(const RawStereoCalibration& raw, const StereoCamera& rectified);

// Images: "gray8" | "bgr8" raw, or "png" | "jpeg" compressed.
image_t encodeImage(const cv::Mat& image, const std::string& encoding, int jpeg_quality = 95);
// Returns "" on success, else why the image could not be decoded.
std::string decodeImage(const image_t& msg, cv::Mat& out);

// Disparity: CV_32F pixels, <= 0 or non-finite = invalid. Stored as uint16
// disparity*scale (KITTI: scale 256), 0 = invalid.
constexpr float kDisparityScale = 256.0f;
void encodeDisparity(const cv::Mat& disparity, const std::string& encoding, disparity_t& msg);
std::string decodeDisparity(const disparity_t& msg, cv::Mat& disparity);
// CV_32F 0..1 -> bytes 0..255 (empty Mat: no confidence)
void encodeConfidence(const cv::Mat& confidence, disparity_t& msg);

ground_model_t toMessage(const GroundModel& g);
GroundModel fromMessage(const ground_model_t& m);
stixel_t toMessage(const Stixel& s);
Stixel fromMessage(const stixel_t& m);
roi_t toMessage(const Hypothesis& h);
Hypothesis fromMessage(const roi_t& m);
normal_stats_t toMessage(const NormalStats& s);
NormalStats fromMessage(const normal_stats_t& m);
void fillExtrinsics(const PoseEstimate& p, extrinsics_t& m);
PoseEstimate fromMessage(const extrinsics_t& m);
detection_t toDetection(const Hypothesis& h, const Verdict& v);

// The whole STIXELS / SURFACE_NORMALS message of one frame's results (the
// stixel and snv_extrinsic services publish these; the fuzz paths check them).
stixels_t stixelsMessage(const header_t& header, const GroundModel& ground, const std::vector<Stixel>& stixels,
                         const std::vector<Hypothesis>& hypotheses, float processing_ms,
                         const ObservedFreeSpace& observed = {});
surface_normals_t surfaceNormalsMessage(const header_t& header, int interval_px, int ground_samples,
                                        const float ground_normal[3], const std::vector<NormalStats>& rois,
                                        float processing_ms);

}  // namespace nerv
