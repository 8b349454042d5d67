#include "message_check.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "delta16_codec.hpp"
#include "message_convert.hpp"

namespace nerv {
namespace {

Problem problem(const char* counter, const std::string& message) { return {counter, message}; }

bool finite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

// A share in 0..1 (false for NaN).
bool isShare(float v) { return v >= 0 && v <= 1; }

Problem checkSize(int width, int height, const Limits& limits, const std::string& what) {
  if (width <= 0 || height <= 0 || width > limits.max_width || height > limits.max_height) {
    std::ostringstream m;
    m << what << " size " << width << "x" << height << " is outside 1x1.." << limits.max_width
      << "x" << limits.max_height;
    return problem("bad_size", m.str());
  }
  return {};
}

}  // namespace

Problem checkCalibration(const stereo_calibration_t& calib, const Limits& limits) {
  if (Problem p = checkSize(calib.width, calib.height, limits, "calibration")) return p;
  if (const std::string why = toCamera(calib).problem(); !why.empty())
    return problem("bad_calibration", "calibration: " + why);
  if (!calib.rectified) {
    for (double v : calib.left_K)
      if (!std::isfinite(v)) return problem("bad_calibration", "calibration: left_K not finite");
    for (double v : calib.right_K)
      if (!std::isfinite(v)) return problem("bad_calibration", "calibration: right_K not finite");
  }
  return {};
}

Problem checkImage(const image_t& image, const Limits& limits, const char* which) {
  if (image.size < 0 || static_cast<size_t>(image.size) != image.data.size())
    return problem("bad_size", std::string(which) + " image: size field " +
                                   std::to_string(image.size) + " != " +
                                   std::to_string(image.data.size()) + " bytes");
  if (Problem p = checkSize(image.width, image.height, limits, std::string(which) + " image"))
    return p;
  if (image.encoding == "gray8" || image.encoding == "bgr8") {
    const int channels = image.encoding == "gray8" ? 1 : 3;
    const long long expected = 1LL * image.width * image.height * channels;
    if (image.channels != channels || image.size != expected)
      return problem("bad_size", std::string(which) + " image: " + image.encoding + " " +
                                     std::to_string(image.width) + "x" +
                                     std::to_string(image.height) + " needs " +
                                     std::to_string(expected) + " bytes, has " +
                                     std::to_string(image.size));
  } else if (image.encoding != "png" && image.encoding != "jpeg") {
    return problem("bad_encoding",
                   std::string(which) + " image: unknown encoding '" + image.encoding + "'");
  }
  return {};
}

Problem checkStereoFrame(const stereo_frame_t& msg, const Limits& limits) {
  if (Problem p = checkCalibration(msg.calib, limits)) return p;
  if (Problem p = checkImage(msg.left, limits, "left")) return p;
  if (Problem p = checkImage(msg.right, limits, "right")) return p;
  if (msg.left.width != msg.right.width || msg.left.height != msg.right.height)
    return problem("size_mismatch", "left " + std::to_string(msg.left.width) + "x" +
                                        std::to_string(msg.left.height) + " and right " +
                                        std::to_string(msg.right.width) + "x" +
                                        std::to_string(msg.right.height) + " differ");
  if (msg.left.width != msg.calib.width || msg.left.height != msg.calib.height)
    return problem("size_mismatch", "image " + std::to_string(msg.left.width) + "x" +
                                        std::to_string(msg.left.height) +
                                        " does not match calibration " +
                                        std::to_string(msg.calib.width) + "x" +
                                        std::to_string(msg.calib.height));
  return {};
}

Problem checkDisparity(const disparity_t& msg, const Limits& limits) {
  if (Problem p = checkCalibration(msg.calib, limits)) return p;
  if (Problem p = checkSize(msg.width, msg.height, limits, "disparity")) return p;
  if (msg.width != msg.calib.width || msg.height != msg.calib.height)
    return problem("size_mismatch", "disparity " + std::to_string(msg.width) + "x" +
                                        std::to_string(msg.height) +
                                        " does not match calibration " +
                                        std::to_string(msg.calib.width) + "x" +
                                        std::to_string(msg.calib.height));
  if (!finite({msg.scale}) || msg.scale <= 0)
    return problem("bad_value", "disparity scale " + std::to_string(msg.scale) + " is not positive");
  if (msg.size < 0 || static_cast<size_t>(msg.size) != msg.data.size())
    return problem("bad_size", "disparity size field " + std::to_string(msg.size) + " != " +
                                   std::to_string(msg.data.size()) + " bytes");
  if (msg.encoding == "u16le") {
    if (msg.size != 2LL * msg.width * msg.height)
      return problem("bad_size", "u16le disparity needs " +
                                     std::to_string(2LL * msg.width * msg.height) +
                                     " bytes, has " + std::to_string(msg.size));
  } else if (msg.encoding == "delta16") {
    // 1 to 3 bytes a pixel (delta16_codec.hpp): the bounds before anything is decoded.
    const size_t lo = delta16MinBytes(msg.width, msg.height), hi = delta16MaxBytes(msg.width, msg.height);
    if (msg.data.size() < lo || msg.data.size() > hi)
      return problem("bad_size", "delta16 disparity needs " + std::to_string(lo) + " to " + std::to_string(hi) +
                                     " bytes, has " + std::to_string(msg.size));
  } else if (msg.encoding != "png16") {
    return problem("bad_encoding", "disparity: unknown encoding '" + msg.encoding + "'");
  }
  if (msg.confidence_size < 0 || static_cast<size_t>(msg.confidence_size) != msg.confidence.size() ||
      (msg.confidence_size != 0 && msg.confidence_size != msg.width * msg.height))
    return problem("bad_size", "confidence size " + std::to_string(msg.confidence_size) +
                                   " is neither 0 nor width*height");
  return {};
}

Problem checkStixels(const stixels_t& msg, const Limits& limits) {
  if (msg.num_stixels < 0 || static_cast<size_t>(msg.num_stixels) != msg.stixels.size() ||
      msg.num_rois < 0 || static_cast<size_t>(msg.num_rois) != msg.rois.size())
    return problem("bad_size", "stixels: counts do not match arrays");
  if (msg.num_columns < 0 || static_cast<size_t>(msg.num_columns) != msg.observed.size())
    return problem("bad_size", "stixels: num_columns does not match the observed array");
  const auto& g = msg.ground;
  if (!finite({g.vd_slope, g.vd_intercept, g.horizon_row, g.pitch_deg, g.roll_deg, g.height_m}))
    return problem("bad_value", "stixels: ground model has non-finite numbers");
  // The free space's coverage tells a planner what is unknown: a share outside
  // 0..1 or a count beyond the strips would turn unseen into free.
  bool shares_ok = isShare(msg.min_observed) && isShare(msg.observed_share);
  for (const float v : msg.observed) shares_ok = shares_ok && isShare(v);
  if (!shares_ok || msg.num_unobserved < 0 || msg.num_unobserved > msg.num_columns ||
      msg.column_width_px < 0 || (msg.num_columns > 0 && msg.column_width_px == 0) ||
      int64_t{msg.num_columns} * msg.column_width_px > int64_t{limits.max_width} + msg.column_width_px)
    return problem("bad_value", "stixels: observed free space has shares outside 0..1 or strips that do not fit the image");
  for (const auto& r : msg.rois) {
    if (!finite({r.x_m, r.y_m, r.z_m, r.width_m, r.height_m, r.distance_m, r.nearest_z_m, r.nearest_z_sigma_m,
                 r.disparity}))
      return problem("bad_value", "stixels: roi " + std::to_string(r.id) + " has non-finite numbers");
    if (r.nearest_z_sigma_m < 0)
      return problem("bad_value", "stixels: roi " + std::to_string(r.id) + " has a negative depth uncertainty");
    // Boxes lie in the image: one outside every accepted image came from a
    // corrupt message (it would be kept as an unvalidated detection).
    if (r.w <= 0 || r.h <= 0 || r.x < 0 || r.y < 0 || int64_t{r.x} + r.w > limits.max_width ||
        int64_t{r.y} + r.h > limits.max_height)
      return problem("bad_value", "stixels: roi " + std::to_string(r.id) + " has box " +
                                      std::to_string(r.w) + "x" + std::to_string(r.h) + " at " +
                                      std::to_string(r.x) + "," + std::to_string(r.y) +
                                      ", outside 0,0.." + std::to_string(limits.max_width) + "," +
                                      std::to_string(limits.max_height));
  }
  return {};
}

Problem checkSurfaceNormals(const surface_normals_t& msg) {
  if (msg.num_rois < 0 || static_cast<size_t>(msg.num_rois) != msg.rois.size())
    return problem("bad_size", "surface normals: num_rois does not match the array");
  for (const auto& s : msg.rois)
    if (!finite({s.density, s.ground_fraction, s.object_fraction, s.error_fraction, s.normal_x,
                 s.normal_y, s.normal_z, s.pitch_deg, s.yaw_deg, s.tilt_from_ground_deg}))
      return problem("bad_value",
                     "surface normals: roi " + std::to_string(s.roi_id) + " has non-finite numbers");
  // Shares outside 0..1 and counts that do not add up fed the verdicts (a
  // ground share of 1e30 reads as all ground).
  for (const auto& s : msg.rois)
    if (!isShare(s.density) || !isShare(s.ground_fraction) || !isShare(s.object_fraction) ||
        !isShare(s.error_fraction) || s.num_samples < 0 || s.num_normals < 0 ||
        s.num_normals > s.num_samples)
      return problem("bad_value", "surface normals: roi " + std::to_string(s.roi_id) +
                                      " has shares outside 0..1 or counts that do not add up");
  return {};
}

Problem checkExtrinsics(const extrinsics_t& msg) {
  if (!finite({msg.pitch_deg, msg.roll_deg, msg.height_m}))
    return problem("bad_value", "extrinsics: pitch/roll/height not finite");
  // A NaN confidence passed "confidence < minimum" and made the pose a prior.
  if (!(msg.confidence >= 0 && msg.confidence <= 1))
    return problem("bad_value", "extrinsics: confidence " + std::to_string(msg.confidence) +
                                    " is not in 0..1");
  return {};
}

}  // namespace nerv
