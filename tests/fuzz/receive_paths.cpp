#include "receive_paths.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <exception>
#include <initializer_list>

#include "prior_selection.hpp"
#include "rectification.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"
#include "validator.hpp"

namespace nerv::fuzz {
namespace {

Outcome reject(const std::string& counter, const std::string& message) {
  Outcome o;
  o.counter = counter;
  o.message = message;
  return o;
}
Outcome reject(const Problem& p) { return reject(p.counter, p.message); }

// As Node::subscribe: a negative result or a thrown exception is "decode_failed".
template <class T>
bool decodeLikeNode(T& msg, const uint8_t* data, size_t size) {
  try {
    return msg.decode(data, 0, static_cast<int>(size)) >= 0;
  } catch (const std::exception&) {
    return false;
  }
}

bool finite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

StereoCamera smallCamera() {
  StereoCamera c;
  c.width = 192;
  c.height = 96;
  c.fx = c.fy = 180;
  c.cx = 96;
  c.cy = 44;
  c.baseline_m = 0.54;
  return c;
}

stereo::Params matcherParams() {
  stereo::Params p;  // the service default algorithm, at the small image's range
  p.num_disparities = 32;
  p.threads = 1;
  return p;
}

stereo::StereoMatcher& matcher() {
  static const std::unique_ptr<stereo::StereoMatcher> m = stereo::StereoMatcher::create(matcherParams());
  return *m;
}

cv::Mat toGray(const cv::Mat& image) {  // as stereo_matcher/main.cpp
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

// The STIXELS message stixel/main.cpp makes of a result (same builder).
stixels_t stixelsMessage(const header_t& header, const stixel::StixelResult& result) {
  return nerv::stixelsMessage(header, result.ground, result.stixels, result.hypotheses, 1);
}

// snv_extrinsic/main.cpp's process(): the decoded disparity and the stixels of one frame.
void snvMessages(const cv::Mat& disparity, const disparity_t& dmsg, const stixels_t& smsg,
                 extrinsics_t& ext, surface_normals_t& normals) {
  snv::SnvExtrinsicEstimator estimator{snv::Params{}};
  std::vector<Hypothesis> rois;
  for (const auto& r : smsg.rois) rois.push_back(fromMessage(r));
  const snv::SnvResult result =
      estimator.process(disparity, toCamera(dmsg.calib), rois, fromMessage(smsg.ground));
  ext = extrinsics_t{};
  ext.header = dmsg.header;
  fillExtrinsics(result.pose, ext);
  ext.processing_ms = 1;
  normals = surfaceNormalsMessage(dmsg.header, result.interval_px, result.ground_samples, result.ground_normal,
                                  result.rois, 1);
}

// --- what an accepted input's outputs must satisfy ---------------------------

std::string disparityOutputBug(const disparity_t& out) {
  if (Problem p = checkDisparity(out, fuzzLimits()))
    return "published DISPARITY is rejected downstream (" + p.counter + "): " + p.message;
  cv::Mat d;
  if (std::string why = decodeDisparity(out, d); !why.empty())
    return "published DISPARITY does not decode: " + why;
  return "";
}

std::string stixelsOutputBug(const stixels_t& out) {
  if (Problem p = checkStixels(out, fuzzLimits()))
    return "published STIXELS is rejected downstream (" + p.counter + "): " + p.message;
  const auto& g = out.ground;
  if (!finite({g.residual_px})) return "published STIXELS: ground residual not finite";
  for (const auto& s : out.stixels)
    if (!finite({s.disparity, s.depth_m, s.base_x_m, s.base_y_m, s.base_z_m}))
      return "published STIXELS: stixel at u=" + std::to_string(s.u) + " has non-finite numbers (d " +
             std::to_string(s.disparity) + ", z " + std::to_string(s.depth_m) + ", base " +
             std::to_string(s.base_x_m) + " " + std::to_string(s.base_y_m) + " " +
             std::to_string(s.base_z_m) + ")";
  return "";
}

std::string snvOutputBug(const extrinsics_t& ext, const surface_normals_t& normals,
                         size_t num_rois) {
  if (Problem p = checkExtrinsics(ext))
    return "published EXTRINSICS is rejected downstream (" + p.counter + "): " + p.message;
  if (!finite({ext.instant_pitch_deg, ext.instant_roll_deg, ext.instant_height_m,
               ext.pitch_mode_deg, ext.pitch_mean_deg, ext.pitch_mean_shift_deg, ext.entropy,
               ext.confidence, ext.filter_pitch_var}))
    return "published EXTRINSICS has non-finite numbers (status " + ext.status + ")";
  if (!(ext.confidence >= 0 && ext.confidence <= 1))
    return "published EXTRINSICS confidence " + std::to_string(ext.confidence) + " outside 0..1";
  if (Problem p = checkSurfaceNormals(normals))
    return "published SURFACE_NORMALS is rejected downstream (" + p.counter + "): " + p.message;
  if (!finite({normals.ground_normal_x, normals.ground_normal_y, normals.ground_normal_z}))
    return "published SURFACE_NORMALS: ground normal not finite";
  if (normals.rois.size() != num_rois) return "SURFACE_NORMALS: not one statistic per ROI";
  return "";
}

std::string verdictsBug(const std::vector<Hypothesis>& hypotheses,
                        const std::vector<NormalStats>& stats) {
  const std::vector<Verdict> verdicts = validator::validate(hypotheses, stats, validator::Params{});
  if (verdicts.size() != hypotheses.size()) return "validator: not one verdict per hypothesis";
  for (const Verdict& v : verdicts) {
    if (v.label != "object" && v.label != "ground" && v.label != "error" && v.label != "unvalidated")
      return "validator: unknown label '" + v.label + "'";
    if (!(v.score >= 0 && v.score <= 1))
      return "validator: score " + std::to_string(v.score) + " outside 0..1 for roi " +
             std::to_string(v.roi_id);
  }
  return "";
}

std::vector<Hypothesis> hypothesesOf(const stixels_t& s) {
  std::vector<Hypothesis> h;
  for (const auto& r : s.rois) h.push_back(fromMessage(r));
  return h;
}

std::vector<NormalStats> statsOf(const surface_normals_t& n) {
  std::vector<NormalStats> s;
  for (const auto& r : n.rois) s.push_back(fromMessage(r));
  return s;
}

// The processing a service runs inside Node::guarded: an exception there is
// counted as "processing_failed", but after the checks it means a check is missing.
template <class F>
Outcome processed(F&& body) {
  Outcome o;
  o.accepted = true;
  try {
    o.bug = body();
  } catch (const std::exception& e) {
    o.bug = std::string("exception after the checks (processing_failed): ") + e.what();
  } catch (...) {
    o.bug = "unknown exception after the checks (processing_failed)";
  }
  return o;
}

Scene makeScene() {
  Scene s;
  s.camera = smallCamera();
  stixel::RoadScene road;
  road.camera_height_m = 1.65f;
  road.pitch_deg = 1.0f;
  road.boxes = {{8.0f, -1.6f, 0.2f, 1.5f}, {14.0f, 1.0f, 2.6f, 1.8f}};
  s.disparity = stixel::renderDisparity(road, s.camera);

  // Texture on the left view, the right view warped by the exact disparity.
  cv::RNG rng(12345);
  s.left.create(s.camera.height, s.camera.width, CV_8U);
  rng.fill(s.left, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(s.left, s.left, cv::Size(3, 3), 0.8);
  cv::Mat map_x(s.left.size(), CV_32F), map_y(s.left.size(), CV_32F);
  for (int v = 0; v < s.left.rows; ++v)
    for (int u = 0; u < s.left.cols; ++u) {
      map_x.at<float>(v, u) = u + s.disparity.at<float>(v, u);
      map_y.at<float>(v, u) = static_cast<float>(v);
    }
  cv::remap(s.left, s.right, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);

  header_t header;
  header.seq = 7;
  header.utime = 1700000000000000;
  header.frame_id = "fuzz/0000000007";
  s.frame.header = header;
  s.frame.calib = toCalibration(s.camera);
  s.frame.left = encodeImage(s.left, "gray8");
  s.frame.right = encodeImage(s.right, "gray8");

  s.disparity_msg.header = header;
  s.disparity_msg.calib = s.frame.calib;
  encodeDisparity(s.disparity, "u16le", s.disparity_msg);
  encodeConfidence(cv::Mat(s.disparity.size(), CV_32F, cv::Scalar(0.75)), s.disparity_msg);
  s.disparity_msg.algorithm = "nerv_sgm";
  s.disparity_msg.min_disparity = 0;
  s.disparity_msg.max_disparity = 32;

  cv::Mat decoded;
  decodeDisparity(s.disparity_msg, decoded);
  s.stixels = stixelsMessage(header, stixel::estimateStixels(decoded, s.camera, stixel::Params{}));
  snvMessages(decoded, s.disparity_msg, s.stixels, s.extrinsics, s.normals);
  return s;
}

}  // namespace

const Scene& scene() {
  static const Scene s = makeScene();
  return s;
}

const cv::Mat& weakGroundDisparity() {
  static const cv::Mat d = [] {
    const Scene& s = scene();
    cv::Mat out = s.disparity.clone();
    const cv::Mat flat = stixel::renderDisparity(stixel::RoadScene{1.65f, 1.0f, true, {}}, s.camera);
    for (int v = 0; v < out.rows; ++v)
      for (int u = 0; u < out.cols; ++u)
        if (out.at<float>(v, u) == flat.at<float>(v, u)) out.at<float>(v, u) = 0;  // road pixel
    return out;
  }();
  return d;
}

Limits fuzzLimits() {
  Limits l;
  l.max_width = 512;
  l.max_height = 256;
  return l;
}

std::vector<std::vector<uint8_t>> seedMessages(const std::string& type) {
  const Scene& s = scene();
  std::vector<std::vector<uint8_t>> out;
  if (type == "stereo_frame") {
    out.push_back(encode(s.frame));
    stereo_frame_t f = s.frame;
    f.left = encodeImage(s.left, "png");
    f.right = encodeImage(s.right, "png");
    out.push_back(encode(f));
    cv::Mat left_bgr, right_bgr;
    cv::cvtColor(s.left, left_bgr, cv::COLOR_GRAY2BGR);
    cv::cvtColor(s.right, right_bgr, cv::COLOR_GRAY2BGR);
    f.left = encodeImage(left_bgr, "bgr8");
    f.right = encodeImage(right_bgr, "jpeg");
    out.push_back(encode(f));
    // A raw pair: the matcher rectifies on ingest (here an already aligned rig).
    f = s.frame;
    f.calib.rectified = false;
    const double K[9] = {s.camera.fx, 0, s.camera.cx, 0, s.camera.fy, s.camera.cy, 0, 0, 1};
    const double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::copy(K, K + 9, f.calib.left_K);
    std::copy(K, K + 9, f.calib.right_K);
    std::copy(R, R + 9, f.calib.R);
    f.calib.T[0] = -s.camera.baseline_m;
    out.push_back(encode(f));
  } else if (type == "disparity") {
    out.push_back(encode(s.disparity_msg));
    for (const char* encoding : {"png16", "delta16"}) {  // the compressed encodings, seeds of their own
      disparity_t d = s.disparity_msg;
      encodeDisparity(s.disparity, encoding, d);
      encodeConfidence(cv::Mat(), d);
      out.push_back(encode(d));
    }
  } else if (type == "stixels") {
    out.push_back(encode(s.stixels));
  } else if (type == "surface_normals") {
    out.push_back(encode(s.normals));
  } else if (type == "extrinsics") {
    out.push_back(encode(s.extrinsics));
    extrinsics_t e = s.extrinsics;
    e.valid = true;
    e.status = "ok";
    e.pitch_deg = 1.0f;
    e.height_m = 1.65f;
    e.confidence = 0.9f;
    out.push_back(encode(e));
  }
  return out;
}

static Outcome receiveStereoFrameUnguarded(const uint8_t* data, size_t size) {
  stereo_frame_t frame;
  if (!decodeLikeNode(frame, data, size)) return reject("decode_failed", "does not decode");
  // stereo_matcher/main.cpp, in order.
  if (Problem p = checkStereoFrame(frame, fuzzLimits())) return reject(p);
  RawStereoCalibration raw;
  Rectifier rectifier;
  if (!frame.calib.rectified) {
    raw = toRawCalibration(frame.calib);
    std::string why = raw.problem();
    if (why.empty()) {
      try {
        rectifier.get(raw);
      } catch (const std::invalid_argument& e) {
        why = e.what();
      }
    }
    if (!why.empty()) return reject("bad_calibration", why);
  }
  cv::Mat left, right;
  std::string why = decodeImage(frame.left, left);
  if (why.empty()) why = decodeImage(frame.right, right);
  if (!why.empty()) return reject("bad_image", why);
  if (left.size() != right.size() || left.cols != frame.calib.width ||
      left.rows != frame.calib.height)
    return reject("size_mismatch", "decoded images do not match the calibration size");
  return processed([&]() -> std::string {
    cv::Mat left_rect, right_rect, disparity, confidence;
    disparity_t out;
    out.header = frame.header;
    out.calib = frame.calib;
    if (frame.calib.rectified) {
      matcher().compute(toGray(left), toGray(right), disparity, confidence);
    } else {
      const StereoCamera& cam = rectifier.rectify(raw, toGray(left), toGray(right), left_rect, right_rect);
      matcher().compute(left_rect, right_rect, disparity, confidence);
      out.calib.fx = cam.fx;
      out.calib.fy = cam.fy;
      out.calib.cx = cam.cx;
      out.calib.cy = cam.cy;
      out.calib.baseline_m = cam.baseline_m;
      out.calib.rectified = true;
    }
    if (disparity.type() != CV_32F || disparity.size() != left.size())
      return "matcher output is not CV_32F of the image size";
    for (int v = 0; v < disparity.rows; ++v)
      for (int u = 0; u < disparity.cols; ++u) {
        const float d = disparity.at<float>(v, u);
        if (!std::isfinite(d) || d < 0) return "matcher output has disparity " + std::to_string(d);
      }
    encodeDisparity(disparity, "u16le", out);
    encodeConfidence(confidence, out);
    out.algorithm = matcher().name();
    out.min_disparity = 0;
    out.max_disparity = 32;
    return disparityOutputBug(out);
  });
}

static Outcome receiveDisparityUnguarded(const uint8_t* data, size_t size) {
  disparity_t msg;
  if (!decodeLikeNode(msg, data, size)) return reject("decode_failed", "does not decode");
  // stixel/main.cpp (snv_extrinsic/main.cpp runs the same check and decode).
  if (Problem p = checkDisparity(msg, fuzzLimits())) return reject(p);
  cv::Mat disparity;
  if (std::string why = decodeDisparity(msg, disparity); !why.empty())
    return reject("bad_disparity", why);
  return processed([&]() -> std::string {
    const stixels_t stixels = stixelsMessage(
        msg.header, stixel::estimateStixels(disparity, toCamera(msg.calib), stixel::Params{}));
    if (std::string bug = stixelsOutputBug(stixels); !bug.empty()) return bug;
    // snv_extrinsic joins it with the STIXELS the stixel stage made of it.
    extrinsics_t ext;
    surface_normals_t normals;
    snvMessages(disparity, msg, stixels, ext, normals);
    if (std::string bug = snvOutputBug(ext, normals, stixels.rois.size()); !bug.empty()) return bug;
    return verdictsBug(hypothesesOf(stixels), statsOf(normals));
  });
}

static Outcome receiveStixelsUnguarded(const uint8_t* data, size_t size) {
  stixels_t msg{};
  if (!decodeLikeNode(msg, data, size)) return reject("decode_failed", "does not decode");
  // snv_extrinsic/main.cpp and validator/main.cpp run the same check.
  if (Problem p = checkStixels(msg, fuzzLimits())) return reject(p);
  return processed([&]() -> std::string {
    // snv_extrinsic: joined with the scene's DISPARITY.
    const disparity_t& dmsg = scene().disparity_msg;
    cv::Mat disparity;
    if (std::string why = decodeDisparity(dmsg, disparity); !why.empty()) return "scene: " + why;
    extrinsics_t ext;
    surface_normals_t normals;
    snvMessages(disparity, dmsg, msg, ext, normals);
    if (std::string bug = snvOutputBug(ext, normals, msg.rois.size()); !bug.empty()) return bug;
    // validator: with those normals, and without (normals never came).
    if (std::string bug = verdictsBug(hypothesesOf(msg), statsOf(normals)); !bug.empty()) return bug;
    return verdictsBug(hypothesesOf(msg), {});
  });
}

static Outcome receiveSurfaceNormalsUnguarded(const uint8_t* data, size_t size) {
  surface_normals_t msg;
  if (!decodeLikeNode(msg, data, size)) return reject("decode_failed", "does not decode");
  if (Problem p = checkSurfaceNormals(msg)) return reject(p);
  // validator/main.cpp: joined with the scene's STIXELS.
  return processed([&] { return verdictsBug(hypothesesOf(scene().stixels), statsOf(msg)); });
}

static Outcome receiveExtrinsicsUnguarded(const uint8_t* data, size_t size) {
  extrinsics_t e;
  if (!decodeLikeNode(e, data, size)) return reject("decode_failed", "does not decode");
  // stixel/main.cpp (defaults: min_prior_confidence 0.3, max_prior_age_frames 30,
  // max_prior_age_ms 3000).
  if (Problem p = checkExtrinsics(e)) return reject(p);
  return processed([&]() -> std::string {
    if (!e.valid || e.confidence < 0.3f) return "";
    stixel::PriorSelection priors(30, 3'000'000);
    priors.offer(e.header.seq, e.header.utime, {true, e.pitch_deg, e.roll_deg, e.height_m});
    // The scene's frame may use this pose only when it is 1..30 frames older and
    // captured 0..3 s before it (unsigned: far-apart values must not wrap into range).
    const header_t& frame = scene().disparity_msg.header;
    const bool recent = e.header.seq < frame.seq && e.header.seq >= frame.seq - 30 &&
                        e.header.utime <= frame.utime &&
                        static_cast<uint64_t>(frame.utime) - static_cast<uint64_t>(e.header.utime) <= 3'000'000u;
    if (priors.forFrame(frame.seq, frame.utime).valid != recent)
      return "prior of frame " + std::to_string(e.header.seq) + " offered to frame " +
             std::to_string(frame.seq) + (recent ? " is lost" : " is used");
    // The next frame, captured at the same time, uses it.
    header_t header = frame;
    header.seq = static_cast<int64_t>(static_cast<uint64_t>(e.header.seq) + 1);  // wraps, no UB
    header.utime = e.header.utime;
    const stixel::GroundPrior prior = priors.forFrame(header.seq, header.utime);
    const stixels_t stixels = stixelsMessage(
        header, stixel::estimateStixels(weakGroundDisparity(), scene().camera, stixel::Params{}, prior));
    return stixelsOutputBug(stixels);
  });
}

// Decoding and the checks must not throw either (in a service the exception
// would be counted as processing_failed instead of the problem's own counter).
template <class F>
Outcome guardedPath(F&& path, const uint8_t* data, size_t size) {
  try {
    return path(data, size);
  } catch (const std::exception& e) {
    Outcome o;
    o.bug = std::string("exception while decoding or checking: ") + e.what();
    return o;
  }
}
Outcome receiveStereoFrame(const uint8_t* data, size_t size) { return guardedPath(receiveStereoFrameUnguarded, data, size); }
Outcome receiveDisparity(const uint8_t* data, size_t size) { return guardedPath(receiveDisparityUnguarded, data, size); }
Outcome receiveStixels(const uint8_t* data, size_t size) { return guardedPath(receiveStixelsUnguarded, data, size); }
Outcome receiveSurfaceNormals(const uint8_t* data, size_t size) { return guardedPath(receiveSurfaceNormalsUnguarded, data, size); }
Outcome receiveExtrinsics(const uint8_t* data, size_t size) { return guardedPath(receiveExtrinsicsUnguarded, data, size); }

}  // namespace nerv::fuzz
