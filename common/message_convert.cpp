#include "message_convert.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "delta16_codec.hpp"

namespace nerv {

namespace {

uint32_t bigEndian(const std::vector<uint8_t>& b, size_t at, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | b[at + i];
  return v;
}

// Width and height a PNG (IHDR) or JPEG (SOFn) stream declares, read before
// decoding: a small stream of zeros can declare, and decode to, up to 2^30 pixels.
bool declaredSize(const std::vector<uint8_t>& b, int64_t& width, int64_t& height) {
  static const uint8_t png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() >= 24 && std::equal(png, png + 8, b.begin())) {
    if (std::memcmp(b.data() + 12, "IHDR", 4) != 0) return false;
    width = bigEndian(b, 16, 4);
    height = bigEndian(b, 20, 4);
    return true;
  }
  if (b.size() < 4 || b[0] != 0xFF || b[1] != 0xD8) return false;
  size_t i = 2;
  while (i + 4 <= b.size()) {
    if (b[i] != 0xFF) return false;
    const uint8_t marker = b[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length field
      i += 2;
      continue;
    }
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (i + 9 > b.size()) return false;
      height = bigEndian(b, i + 5, 2);
      width = bigEndian(b, i + 7, 2);
      return true;
    }
    i += 2 + bigEndian(b, i + 2, 2);
  }
  return false;
}

// "" when the stream declares the message's size, else why not.
std::string declaredSizeProblem(const std::vector<uint8_t>& data, const std::string& what, int width,
                                int height) {
  int64_t w = 0, h = 0;
  if (!declaredSize(data, w, h)) return what + " stream has no readable size header";
  if (w != width || h != height)
    return what + " stream declares " + std::to_string(w) + "x" + std::to_string(h) +
           ", header says " + std::to_string(width) + "x" + std::to_string(height);
  return "";
}

}  // namespace

StereoCamera toCamera(const stereo_calibration_t& c) {
  StereoCamera cam;
  cam.width = c.width;
  cam.height = c.height;
  cam.fx = c.fx;
  cam.fy = c.fy;
  cam.cx = c.cx;
  cam.cy = c.cy;
  cam.baseline_m = c.baseline_m;
  return cam;
}

stereo_calibration_t toCalibration(const StereoCamera& cam) {
  stereo_calibration_t c{};
  c.width = cam.width;
  c.height = cam.height;
  c.fx = cam.fx;
  c.fy = cam.fy;
  c.cx = cam.cx;
  c.cy = cam.cy;
  c.baseline_m = cam.baseline_m;
  c.rectified = true;
  return c;
}

stereo_calibration_t toCalibration(const RawStereoCalibration& raw, const StereoCamera& rectified) {
  stereo_calibration_t c = toCalibration(rectified);
  c.rectified = false;
  c.width = raw.width;
  c.height = raw.height;
  std::copy(raw.left_K.begin(), raw.left_K.end(), c.left_K);
  std::copy(raw.left_D.begin(), raw.left_D.end(), c.left_D);
  std::copy(raw.right_K.begin(), raw.right_K.end(), c.right_K);
  std::copy(raw.right_D.begin(), raw.right_D.end(), c.right_D);
  std::copy(raw.R.begin(), raw.R.end(), c.R);
  std::copy(raw.T.begin(), raw.T.end(), c.T);
  return c;
}

RawStereoCalibration toRawCalibration(const stereo_calibration_t& c) {
  RawStereoCalibration raw;
  raw.width = c.width;
  raw.height = c.height;
  std::copy(c.left_K, c.left_K + 9, raw.left_K.begin());
  std::copy(c.left_D, c.left_D + 5, raw.left_D.begin());
  std::copy(c.right_K, c.right_K + 9, raw.right_K.begin());
  std::copy(c.right_D, c.right_D + 5, raw.right_D.begin());
  std::copy(c.R, c.R + 9, raw.R.begin());
  std::copy(c.T, c.T + 3, raw.T.begin());
  return raw;
}

image_t encodeImage(const cv::Mat& image, const std::string& encoding, int jpeg_quality) {
  image_t msg{};
  msg.width = image.cols;
  msg.height = image.rows;
  msg.channels = image.channels();
  msg.encoding = encoding;
  if (encoding == "gray8" || encoding == "bgr8") {
    const cv::Mat cont = image.isContinuous() ? image : image.clone();
    msg.data.assign(cont.data, cont.data + cont.total() * cont.elemSize());
  } else {
    std::vector<int> params;
    if (encoding == "jpeg") params = {cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
    if (encoding == "png") params = {cv::IMWRITE_PNG_COMPRESSION, 1};
    cv::imencode(encoding == "png" ? ".png" : ".jpg", image, msg.data, params);
  }
  msg.size = static_cast<int32_t>(msg.data.size());
  return msg;
}

std::string decodeImage(const image_t& msg, cv::Mat& out) {
  if (msg.encoding == "gray8" || msg.encoding == "bgr8") {
    const int type = msg.encoding == "gray8" ? CV_8UC1 : CV_8UC3;
    const size_t need = static_cast<size_t>(msg.width) * msg.height * (type == CV_8UC1 ? 1 : 3);
    if (msg.data.size() != need) return "raw image has the wrong number of bytes";
    out.create(msg.height, msg.width, type);
    std::memcpy(out.data, msg.data.data(), need);
    return "";
  }
  if (msg.encoding == "png" || msg.encoding == "jpeg") {
    if (std::string why = declaredSizeProblem(msg.data, msg.encoding, msg.width, msg.height); !why.empty())
      return why;
    // imdecode throws on an empty buffer (and a codec may on a corrupt stream).
    try {
      out = msg.data.empty() ? cv::Mat() : cv::imdecode(msg.data, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
      out.release();
    }
    if (out.empty()) return msg.encoding + " stream cannot be decoded";
    // The matchers take 8-bit gray (BGR and BGRA are converted): a 16-bit PNG
    // used to reach them and throw.
    if (out.depth() != CV_8U || (out.channels() != 1 && out.channels() != 3 && out.channels() != 4))
      return msg.encoding + " stream is not 8-bit gray, BGR or BGRA";
    if (out.cols != msg.width || out.rows != msg.height)
      return msg.encoding + " stream is " + std::to_string(out.cols) + "x" +
             std::to_string(out.rows) + ", header says " + std::to_string(msg.width) + "x" +
             std::to_string(msg.height);
    return "";
  }
  return "unknown encoding '" + msg.encoding + "'";
}

void encodeDisparity(const cv::Mat& disparity, const std::string& encoding, disparity_t& msg) {
  CV_Assert(disparity.type() == CV_32F);
  msg.width = disparity.cols;
  msg.height = disparity.rows;
  msg.scale = kDisparityScale;
  msg.encoding = encoding;
  // u16le: the fixed point is written straight into the message (x86/ARM
  // hosts are little-endian; uint16 memory order is the wire order); png16
  // encodes it from a matrix.
  cv::Mat fixed;
  uint16_t* out = nullptr;
  if (encoding == "png16" || encoding == "delta16") {
    fixed.create(disparity.size(), CV_16U);
  } else {
    msg.data.resize(disparity.total() * 2);
    out = reinterpret_cast<uint16_t*>(msg.data.data());
  }
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    uint16_t* o = out ? out + static_cast<size_t>(v) * disparity.cols : fixed.ptr<uint16_t>(v);
    // Round half up, 0 for invalid (<= 0.5 / scale), NaN and +-inf. Written
    // without branches so that the compiler vectorises it (the matcher
    // encodes every frame on the pipeline's critical path): NaN and -inf fail
    // s > 0.5, +inf fails s <= FLT_MAX; the clamp keeps the conversion defined.
    for (int u = 0; u < disparity.cols; ++u) {
      const float s = d[u] * kDisparityScale;
      const bool valid = s > 0.5f && s <= std::numeric_limits<float>::max();
      const float r = std::min(valid ? s + 0.5f : 0.0f, 65535.f);
      o[u] = static_cast<uint16_t>(static_cast<int>(r));
    }
  }
  if (encoding == "png16") cv::imencode(".png", fixed, msg.data, {cv::IMWRITE_PNG_COMPRESSION, 1});
  else if (encoding == "delta16") encodeDelta16(fixed, msg.data);
  msg.size = static_cast<int32_t>(msg.data.size());
}

std::string decodeDisparity(const disparity_t& msg, cv::Mat& disparity) {
  cv::Mat fixed;
  if (msg.encoding == "u16le") {
    if (msg.data.size() != 2ull * msg.width * msg.height) return "u16le disparity has the wrong size";
    fixed = cv::Mat(msg.height, msg.width, CV_16U, const_cast<uint8_t*>(msg.data.data()));
  } else if (msg.encoding == "png16") {
    if (std::string why = declaredSizeProblem(msg.data, "png16", msg.width, msg.height); !why.empty())
      return why;
    try {
      fixed = msg.data.empty() ? cv::Mat() : cv::imdecode(msg.data, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
      fixed.release();
    }
    if (fixed.empty() || fixed.type() != CV_16U) return "png16 disparity cannot be decoded";
    if (fixed.cols != msg.width || fixed.rows != msg.height) return "png16 disparity size differs from header";
  } else if (msg.encoding == "delta16") {
    if (std::string why = decodeDelta16(msg.data.data(), msg.data.size(), msg.width, msg.height, fixed); !why.empty())
      return why;
  } else {
    return "unknown disparity encoding '" + msg.encoding + "'";
  }
  fixed.convertTo(disparity, CV_32F, 1.0 / msg.scale);
  return "";
}

void encodeConfidence(const cv::Mat& confidence, disparity_t& msg) {
  msg.confidence.clear();
  if (!confidence.empty()) {
    cv::Mat bytes;
    confidence.convertTo(bytes, CV_8U, 255.0);
    msg.confidence.assign(bytes.data, bytes.data + bytes.total());
  }
  msg.confidence_size = static_cast<int32_t>(msg.confidence.size());
}

ground_model_t toMessage(const GroundModel& g) {
  ground_model_t m{};
  m.valid = g.valid;
  m.source = g.source;
  m.vd_slope = g.vd_slope;
  m.vd_intercept = g.vd_intercept;
  m.horizon_row = g.horizon_row;
  m.pitch_deg = g.pitch_deg;
  m.roll_deg = g.roll_deg;
  m.height_m = g.height_m;
  m.inliers = g.inliers;
  m.residual_px = g.residual_px;
  return m;
}

GroundModel fromMessage(const ground_model_t& m) {
  GroundModel g;
  g.valid = m.valid;
  g.source = m.source;
  g.vd_slope = m.vd_slope;
  g.vd_intercept = m.vd_intercept;
  g.horizon_row = m.horizon_row;
  g.pitch_deg = m.pitch_deg;
  g.roll_deg = m.roll_deg;
  g.height_m = m.height_m;
  g.inliers = m.inliers;
  g.residual_px = m.residual_px;
  return g;
}

stixel_t toMessage(const Stixel& s) {
  stixel_t m{};
  m.u = s.u;
  m.width = s.width;
  m.top_row = s.top_row;
  m.bottom_row = s.bottom_row;
  m.disparity = s.disparity;
  m.depth_m = s.depth_m;
  m.base_x_m = s.base_x_m;
  m.base_y_m = s.base_y_m;
  m.base_z_m = s.base_z_m;
  return m;
}

Stixel fromMessage(const stixel_t& m) {
  Stixel s;
  s.u = m.u;
  s.width = m.width;
  s.top_row = m.top_row;
  s.bottom_row = m.bottom_row;
  s.disparity = m.disparity;
  s.depth_m = m.depth_m;
  s.base_x_m = m.base_x_m;
  s.base_y_m = m.base_y_m;
  s.base_z_m = m.base_z_m;
  return s;
}

roi_t toMessage(const Hypothesis& h) {
  roi_t m{};
  m.id = h.id;
  m.x = h.box.x;
  m.y = h.box.y;
  m.w = h.box.w;
  m.h = h.box.h;
  m.x_m = h.x_m;
  m.y_m = h.y_m;
  m.z_m = h.z_m;
  m.width_m = h.width_m;
  m.height_m = h.height_m;
  m.distance_m = h.distance_m;
  m.nearest_z_m = h.nearest_z_m;
  m.nearest_z_sigma_m = h.nearest_z_sigma_m;
  m.disparity = h.disparity;
  m.num_stixels = h.num_stixels;
  return m;
}

Hypothesis fromMessage(const roi_t& m) {
  Hypothesis h;
  h.id = m.id;
  h.box = {m.x, m.y, m.w, m.h};
  h.x_m = m.x_m;
  h.y_m = m.y_m;
  h.z_m = m.z_m;
  h.width_m = m.width_m;
  h.height_m = m.height_m;
  h.distance_m = m.distance_m;
  h.nearest_z_m = m.nearest_z_m;
  h.nearest_z_sigma_m = m.nearest_z_sigma_m;
  h.disparity = m.disparity;
  h.num_stixels = m.num_stixels;
  return h;
}

normal_stats_t toMessage(const NormalStats& s) {
  normal_stats_t m{};
  m.roi_id = s.roi_id;
  m.num_samples = s.num_samples;
  m.num_normals = s.num_normals;
  m.density = s.density;
  m.ground_fraction = s.ground_fraction;
  m.object_fraction = s.object_fraction;
  m.error_fraction = s.error_fraction;
  m.normal_x = s.normal[0];
  m.normal_y = s.normal[1];
  m.normal_z = s.normal[2];
  m.pitch_deg = s.pitch_deg;
  m.yaw_deg = s.yaw_deg;
  m.tilt_from_ground_deg = s.tilt_from_ground_deg;
  return m;
}

NormalStats fromMessage(const normal_stats_t& m) {
  NormalStats s;
  s.roi_id = m.roi_id;
  s.num_samples = m.num_samples;
  s.num_normals = m.num_normals;
  s.density = m.density;
  s.ground_fraction = m.ground_fraction;
  s.object_fraction = m.object_fraction;
  s.error_fraction = m.error_fraction;
  s.normal[0] = m.normal_x;
  s.normal[1] = m.normal_y;
  s.normal[2] = m.normal_z;
  s.pitch_deg = m.pitch_deg;
  s.yaw_deg = m.yaw_deg;
  s.tilt_from_ground_deg = m.tilt_from_ground_deg;
  return s;
}

void fillExtrinsics(const PoseEstimate& p, extrinsics_t& m) {
  m.valid = p.valid;
  m.status = p.status;
  m.pitch_deg = p.pitch_deg;
  m.roll_deg = p.roll_deg;
  m.height_m = p.height_m;
  m.instant_pitch_deg = p.instant_pitch_deg;
  m.instant_roll_deg = p.instant_roll_deg;
  m.instant_height_m = p.instant_height_m;
  m.pitch_mode_deg = p.pitch_mode_deg;
  m.pitch_mean_deg = p.pitch_mean_deg;
  m.pitch_mean_shift_deg = p.pitch_mean_shift_deg;
  m.entropy = p.entropy;
  m.confidence = p.confidence;
  m.num_normals = p.num_normals;
  m.inliers = p.inliers;
  m.filter_pitch_var = p.filter_pitch_var;
}

PoseEstimate fromMessage(const extrinsics_t& m) {
  PoseEstimate p;
  p.valid = m.valid;
  p.status = m.status;
  p.pitch_deg = m.pitch_deg;
  p.roll_deg = m.roll_deg;
  p.height_m = m.height_m;
  p.instant_pitch_deg = m.instant_pitch_deg;
  p.instant_roll_deg = m.instant_roll_deg;
  p.instant_height_m = m.instant_height_m;
  p.pitch_mode_deg = m.pitch_mode_deg;
  p.pitch_mean_deg = m.pitch_mean_deg;
  p.pitch_mean_shift_deg = m.pitch_mean_shift_deg;
  p.entropy = m.entropy;
  p.confidence = m.confidence;
  p.num_normals = m.num_normals;
  p.inliers = m.inliers;
  p.filter_pitch_var = m.filter_pitch_var;
  return p;
}

detection_t toDetection(const Hypothesis& h, const Verdict& v) {
  detection_t d{};
  d.roi_id = h.id;
  d.x = h.box.x;
  d.y = h.box.y;
  d.w = h.box.w;
  d.h = h.box.h;
  d.x_m = h.x_m;
  d.y_m = h.y_m;
  d.z_m = h.z_m;
  d.width_m = h.width_m;
  d.height_m = h.height_m;
  d.distance_m = h.distance_m;
  d.nearest_z_m = h.nearest_z_m;
  d.nearest_z_sigma_m = h.nearest_z_sigma_m;
  d.label = v.label;
  d.score = v.score;
  d.kept = v.kept;
  d.reason = v.reason;
  return d;
}

stixels_t stixelsMessage(const header_t& header, const GroundModel& ground, const std::vector<Stixel>& stixels,
                         const std::vector<Hypothesis>& hypotheses, float processing_ms,
                         const ObservedFreeSpace& observed) {
  stixels_t out{};
  out.header = header;
  out.ground = toMessage(ground);
  for (const auto& s : stixels) out.stixels.push_back(toMessage(s));
  for (const auto& h : hypotheses) out.rois.push_back(toMessage(h));
  out.num_stixels = static_cast<int32_t>(out.stixels.size());
  out.num_rois = static_cast<int32_t>(out.rois.size());
  out.column_width_px = observed.column_width_px;
  out.observed = observed.observed;
  out.num_columns = static_cast<int32_t>(out.observed.size());
  out.min_observed = observed.min_observed;
  out.observed_share = observed.observed_share;
  out.num_unobserved = observed.num_unobserved;
  out.processing_ms = processing_ms;
  return out;
}

surface_normals_t surfaceNormalsMessage(const header_t& header, int interval_px, int ground_samples,
                                        const float ground_normal[3], const std::vector<NormalStats>& rois,
                                        float processing_ms) {
  surface_normals_t out{};
  out.header = header;
  out.interval_px = interval_px;
  out.ground_samples = ground_samples;
  out.ground_normal_x = ground_normal[0];
  out.ground_normal_y = ground_normal[1];
  out.ground_normal_z = ground_normal[2];
  for (const auto& s : rois) out.rois.push_back(toMessage(s));
  out.num_rois = static_cast<int32_t>(out.rois.size());
  out.processing_ms = processing_ms;
  return out;
}

}  // namespace nerv
