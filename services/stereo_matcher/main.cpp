// stereo_matcher service: STEREO_FRAME -> DISPARITY (with confidence).
// Raw pairs (calib.rectified = false) are undistorted and rectified on ingest
// with maps cached per calibration; the published calibration is the rectified one.
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "blank_view.hpp"
#include "frozen_view.hpp"
#include "message_convert.hpp"
#include "rectification.hpp"
#include "rectification_check.hpp"
#include "service_config.hpp"
#include "stereo_matcher.hpp"
#include "view_order_check.hpp"

using namespace nerv;

namespace {

cv::Mat toGray(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

int serve(ServiceConfig& config) {
  const stereo::Params params = stereo::readParams(config.section());
  std::string encoding = "u16le";
  config.section().get("output_encoding", encoding, {"u16le", "png16", "delta16"});
  int queue = 1;  // the newest frame waits; older ones are dropped (docs/stereo.md "Queue of one")
  config.section().get("queue", queue, 1, 100);
  bool publish_confidence = true;
  config.section().get("publish_confidence", publish_confidence);
  // Is the rig still rectified (rectification_check.hpp)? Every this many frames the
  // rows of the two views are compared, after the frame's DISPARITY is out (about 2 ms);
  // 0 = never. The median of the last 10 checks beyond max_row_offset_px is an error.
  int row_check_every = 10;
  config.section().get("row_check_every_frames", row_check_every, 0, 100000);
  // Measured on urban seed 11 (nerv_misalign, nerv_eval_disparity): D1 3.2 % aligned,
  // 3.6 % at 0.25 px, 5.5 % at 0.5 px, 17 % at 1 px. KITTI 2015 frame 5 sits at 0.19 px.
  float max_row_offset = 0.4f;
  config.section().get("max_row_offset_px", max_row_offset, 0.05, 100.0);
  config.finish();

  Node node(config.nodeOptions());
  auto matcher = stereo::StereoMatcher::create(params);
  Rectifier rectifier;
  cv::Mat left, right, left_rect, right_rect, disparity, confidence;
  cv::Mat matched_left, matched_right;  // the gray views the matcher saw
  stereo::RowOffsetMonitor row_offsets(10, max_row_offset);
  // An aligned verdict is logged the first time and whenever the rows moved by 0.1 px or
  // more since the last line, so a log shows a drift (heat, a loosening mount) before it
  // becomes an error; misaligned verdicts are errors every time.
  float row_worst_said = -1.0f;
  int swapped_in_a_row = 0;  // view-order checks in a row that found the views swapped
  int blank_in_a_row = 0;    // checks in a row that found one view blank
  int64_t row_checks_done = 0;
  stereo::FrozenViewCheck frozen(3);  // one view repeating while the other changes (frozen_view.hpp)
  // Kept across frames, every field set anew each time: its 0.9 + 0.5 MB arrays keep
  // their capacity instead of being allocated (and page-faulted) per frame.
  disparity_t out;
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
    // A camera that stopped: every frame of it counted, the error said when it starts and
    // every 100 frames while it lasts. The frame is still matched.
    if (const std::string stopped = frozen.push(left, right); !stopped.empty()) {
      node.count("frozen_view_frames");
      if (frozen.framesStopped() == 3 || frozen.framesStopped() % 100 == 0)
        node.error("view_frozen", what + "the " + stopped + " camera's image has not changed for " +
                                      std::to_string(frozen.framesStopped()) +
                                      " frames while the other's has: a stopped camera or driver; the disparity "
                                      "compares images taken at different times");
    }

    const auto start = std::chrono::steady_clock::now();
    out.header = frame.header;
    out.calib = frame.calib;
    if (frame.calib.rectified) {
      matched_left = toGray(left);
      matched_right = toGray(right);
      matcher->compute(matched_left, matched_right, disparity, confidence);
    } else {
      const StereoCamera& cam = rectifier.rectify(raw, toGray(left), toGray(right), left_rect,
                                                  right_rect);
      matcher->compute(left_rect, right_rect, disparity, confidence);
      matched_left = left_rect;
      matched_right = right_rect;
      out.calib.fx = cam.fx;  // the disparity refers to the rectified pair
      out.calib.fy = cam.fy;
      out.calib.cx = cam.cx;
      out.calib.cy = cam.cy;
      out.calib.baseline_m = cam.baseline_m;
      out.calib.rectified = true;
    }
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

    // The first 10 checks on every frame, so the first verdict comes a second after start
    // (at 10 Hz), before a drive records bad disparity; then every row_check_every frames.
    // Not while one view repeats (frozen_view.hpp): the two images are from different
    // moments, and their rows would differ by the vehicle's motion, not the rig's.
    if (row_check_every > 0 && frozen.framesStopped() == 0 &&
        (row_checks_done < 10 || node.framesIn() % row_check_every == 0)) {
      ++row_checks_done;
      const stereo::RowOffset m = stereo::measureRowOffset(matched_left, matched_right, disparity);
      node.count(m.valid ? "row_checks" : "row_checks_unmeasured");
      // Too few matched points to measure the rows: does one view show nothing
      // (blank_view.hpp), else are the views the right way round (view_order_check.hpp)?
      // Only then, as a rig that matches needs neither.
      const stereo::ViewTexture texture =
          m.valid ? stereo::ViewTexture{} : stereo::compareViewTexture(matched_left, matched_right);
      blank_in_a_row = texture.blank.empty() ? 0 : blank_in_a_row + 1;
      if (blank_in_a_row >= 2)
        node.error("view_blank", cv::format("the %s view shows almost no texture (%d textured points against the "
                                            "other's %d): a lens cap, a covered, fogged or iced lens, or a dead "
                                            "sensor",
                                            texture.blank.c_str(), texture.blank == "left" ? texture.left : texture.right,
                                            texture.blank == "left" ? texture.right : texture.left));
      const stereo::ViewOrder order = m.valid || !texture.blank.empty()
                                          ? stereo::ViewOrder{}
                                          : stereo::measureViewOrder(matched_left, matched_right);
      swapped_in_a_row = order.swapped ? swapped_in_a_row + 1 : 0;
      if (swapped_in_a_row >= 2)  // two checks in a row: not one odd frame
        node.error("views_swapped",
                   cv::format("the left and right views look swapped: %.0f %% of %d tracked points lie farther right "
                              "in the right view than in the left (the right way round they lie farther left); check "
                              "which camera feeds which side (cables, driver, topics)",
                              100.0 * order.share_rightward, order.votes));
      if (row_offsets.add(m)) {
        if (row_offsets.misaligned()) {
          node.error("row_misaligned", "rectification: " + row_offsets.describe() +
                                           ": the rig no longer matches its calibration (max_row_offset_px " +
                                           cv::format("%.2f", max_row_offset) +
                                           "); disparity and detections degrade, recalibrate it");
          row_worst_said = -1.0f;  // back within the limit: said again
        } else if (row_worst_said < 0 || std::abs(row_offsets.median().worst_px - row_worst_said) >= 0.1f) {
          std::fprintf(stderr, "stereo_matcher: rectification check: %s: aligned\n", row_offsets.describe().c_str());
          row_worst_said = row_offsets.median().worst_px;
        }
      }
    }
  }, queue);
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("stereo_matcher", argc, argv, serve); }
