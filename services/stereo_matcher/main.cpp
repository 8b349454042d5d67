// stereo_matcher service: STEREO_FRAME -> DISPARITY (with confidence).
// Raw pairs (calib.rectified = false) are undistorted and rectified on ingest
// with maps cached per calibration; the published calibration is the rectified one.
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <vector>

#include "message_convert.hpp"
#include "rectification.hpp"
#include "rig_check.hpp"
#include "rig_state.hpp"
#include "service_config.hpp"
#include "own_sgm.hpp"
#include "stereo_matcher.hpp"

using namespace nerv;

namespace {

cv::Mat toGray(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

// The calibration the rig's corrections are kept for (rig_state.hpp): FNV-1a over every field
// the frames carry, as encoded, and the ones a person reads.
stereo::RigCalibration rigCalibration(const stereo_calibration_t& calib) {
  std::vector<uint8_t> bytes(static_cast<size_t>(calib.getEncodedSize()));
  calib.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  uint64_t h = 14695981039346656037ull;
  for (uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return {h, calib.width, calib.height, calib.fx, calib.cx, calib.cy, calib.baseline_m, calib.rectified != 0};
}

std::string nowUtc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

int serve(ServiceConfig& config) {
  const stereo::Params params = stereo::readParams(config.section());
  // DISPARITY carries 1/256 px in 16 bits, at most 255.996 px: a search reaching further would
  // publish every nearer surface at that value, a depth too far that no receiver could tell.
  // (The in-process tools take longer searches; the wire does not.)
  if (params.min_disparity + params.num_disparities > 65536.0f / kDisparityScale)
    throw ConfigError("config key '" + config.section().path() + ".num_disparities' = " +
                      std::to_string(params.num_disparities) + " with min_disparity " +
                      std::to_string(params.min_disparity) +
                      " searches beyond the 256 px a DISPARITY message carries (1/256 px in 16 bits)");
  std::string encoding = "u16le";
  config.section().get("output_encoding", encoding, {"u16le", "png16", "delta16"});
  int queue = 1;  // the newest frame waits; older ones are dropped (docs/stereo.md "Queue of one")
  config.section().get("queue", queue, 1, 100);
  bool publish_confidence = true;
  config.section().get("publish_confidence", publish_confidence);
  // The rig's checks (rig_check.hpp): a stopped camera on every frame; the rows (is the rig
  // still rectified?) on the first 10 frames, then every row_check_every_frames (0 = never),
  // after the frame's DISPARITY is out, about 1.5 ms; and when the rows cannot be measured,
  // a blank view or swapped views. The median of the last 10 row checks beyond
  // max_row_offset_px is an error. Measured on urban seed 11 (nerv_misalign,
  // nerv_eval_disparity): D1 3.2 % aligned, 3.6 % at 0.25 px, 5.5 % at 0.5 px, 17 % at 1 px.
  // KITTI 2015 frame 5 sits at 0.19 px. On the same frames, while driving, the delay between
  // the two views' shutters (shutter_sync.hpp); the median of the last 10 beyond
  // max_view_delay_ms is an error. Urban seed 11 at 8 m/s: D1 3.2 % synchronised, 3.7 % at
  // 2 ms, 9.8 % at 5 ms, 23 % at 10 ms (docs/stereo.md "Were the views taken together?").
  stereo::RigCheckParams rig_params;
  config.section().get("row_check_every_frames", rig_params.check_every, 0, 100000);
  config.section().get("max_row_offset_px", rig_params.max_row_offset_px, 0.05, 100.0);
  config.section().get("max_view_delay_ms", rig_params.max_view_delay_ms, 0.1, 1000.0);
  config.section().get("max_disparity_offset_px", rig_params.max_disparity_offset_px, 0.05, 100.0);
  // Rows off since calibration are corrected until the rig is recalibrated (view_correction.hpp):
  // the right views resampled by the measured plane once a verdict finds the matched rows off by
  // more than row_correction_above_px; the error row_misaligned still asks for a recalibration.
  config.section().get("row_correction", rig_params.row_correction);
  config.section().get("row_correction_above_px", rig_params.row_correction_above_px, 0.05, 100.0);
  config.section().get("max_row_correction_px", rig_params.max_row_correction_px, 0.0, 100.0);
  // Likewise a disparity offset beyond max_disparity_offset_px (a camera turned about its
  // vertical axis): taken off every disparity, at most max_offset_correction_px.
  config.section().get("offset_correction", rig_params.offset_correction);
  config.section().get("max_offset_correction_px", rig_params.max_offset_correction_px, 0.0, 100.0);
  // Both corrections kept across restarts in this file (rig_state.hpp; "" = not kept): restored
  // from the first frame of the same calibration instead of measured again from the 11th / 21st.
  std::string rig_state_file;
  config.section().get("rig_state_file", rig_state_file);
  config.finish();

  Node node(config.nodeOptions());
  auto matcher = stereo::StereoMatcher::create(params);
  if (params.algorithm == "nerv_sgm") std::fprintf(stderr, "stereo_matcher: nerv_sgm: %s\n", stereo::ownSgmCodePaths());
  Rectifier rectifier;
  cv::Mat left, right, left_rect, right_rect, disparity, confidence;
  cv::Mat matched_left, matched_right;  // the gray views the matcher saw
  stereo::RigCheck rig(rig_params);
  stereo::RigStateKeeper rig_state(rig_state_file);
  const auto report = [&](const std::vector<stereo::RigFinding>& findings, const std::string& prefix) {
    for (const stereo::RigFinding& f : findings) {
      if (f.kind == stereo::RigFinding::Kind::Count) node.count(f.name);
      else if (f.kind == stereo::RigFinding::Kind::Error) node.error(f.name, prefix + f.message);
      else if (f.kind == stereo::RigFinding::Kind::Gauge) node.gauge(f.name, f.value);
      else std::fprintf(stderr, "stereo_matcher: %s%s\n", prefix.c_str(), f.message.c_str());
    }
  };
  // Kept across frames, every field set anew each time: its 0.9 + 0.5 MB arrays keep
  // their capacity instead of being allocated (and page-faulted) per frame.
  disparity_t out{};
  warmUp(config, [&](const WarmupSize& size) {
    warmupPair(size, left, right);
    matcher->compute(left, right, disparity, confidence);
    encodeDisparity(disparity, encoding, out);  // the message's arrays get their capacity
    encodeConfidence(publish_confidence ? confidence : cv::Mat(), out);
  });

  node.subscribe<stereo_frame_t>("STEREO_FRAME", [&](const stereo_frame_t& frame) {
    if (!node.ownsFrame(frame.header.seq)) return;  // another shard's frame
    const std::string what = "frame " + std::to_string(frame.header.seq) + ": ";
    if (Problem p = checkStereoFrame(frame, node.options().limits))
      return node.error(p.counter, what + p.message);
    RawStereoCalibration raw;
    if (!frame.calib.rectified) {
      raw = toRawCalibration(frame.calib);
      std::string why = raw.problem();
      if (why.empty()) {
        try {
          rectifier.get(raw);  // computes and caches the maps, or finds them unusable
        } catch (const std::invalid_argument& e) {
          why = e.what();
        }
      }
      if (!why.empty()) return node.error("bad_calibration", what + why);
    }
    std::string why = decodeImage(frame.left, left);
    if (why.empty()) why = decodeImage(frame.right, right);
    if (!why.empty()) return node.error("bad_image", what + why);
    if (left.size() != right.size() || left.cols != frame.calib.width ||
        left.rows != frame.calib.height)
      return node.error("size_mismatch", what + "decoded images do not match the calibration size");
    node.countIn();
    const auto rig_calibration = [&frame] { return rigCalibration(frame.calib); };  // when the keeper needs it
    report(rig_state.beforeMatching(rig_calibration, rig), "");  // the first frame: corrections restored
    report(rig.beforeMatching(left, right), what);  // the frame is matched whatever it says

    const auto start = std::chrono::steady_clock::now();
    out.header = frame.header;
    out.calib = frame.calib;
    // The right view as the rig's row correction has it (the same view while there is none).
    if (frame.calib.rectified) {
      matched_left = toGray(left);
      matched_right = rig.rightToMatch(toGray(right));
      matcher->compute(matched_left, matched_right, disparity, confidence);
    } else {
      const StereoCamera& cam = rectifier.rectify(raw, toGray(left), toGray(right), left_rect,
                                                  right_rect);
      matched_left = left_rect;
      matched_right = rig.rightToMatch(right_rect);
      matcher->compute(matched_left, matched_right, disparity, confidence);
      out.calib.fx = cam.fx;  // the disparity refers to the rectified pair
      out.calib.fy = cam.fy;
      out.calib.cx = cam.cx;
      out.calib.cy = cam.cy;
      out.calib.baseline_m = cam.baseline_m;
      out.calib.rectified = true;
    }
    rig.correctDisparity(disparity);  // the offset correction, if one is set
    // Something nearer than the main search reaches, filled by the near field: worth a
    // count in NERV_HEALTH (near_field_frames), as it is rare and safety-relevant.
    if (matcher->nearFieldPixels() > 0) node.count("near_field_frames");
    encodeDisparity(disparity, encoding, out);
    encodeConfidence(publish_confidence ? confidence : cv::Mat(), out);
    out.algorithm = matcher->name();
    out.min_disparity = static_cast<float>(params.min_disparity);
    out.max_disparity = static_cast<float>(params.min_disparity + params.num_disparities);
    out.processing_ms = std::chrono::duration<float, std::milli>(
                            std::chrono::steady_clock::now() - start).count();
    node.publish("DISPARITY", out);
    node.countOut(frame.header.utime, out.processing_ms);

    report(rig.afterMatching(matched_left, matched_right, disparity,
                             {frame.header.utime, out.calib.fx, out.calib.cx, out.calib.cy, out.calib.baseline_m}),
           what);
    report(rig_state.afterMatching(rig_calibration, rig, nowUtc), what);  // a changed correction kept
  }, queue);
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("stereo_matcher", argc, argv, serve); }
