#include "frame_grid.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>

#include "color_map.hpp"
#include "message_convert.hpp"
#include "overlay_draw.hpp"
#include "rectification.hpp"

namespace nerv::viz {

namespace {

cv::Mat toBgr(const cv::Mat& img) {
  cv::Mat out;
  if (img.channels() == 1) cv::cvtColor(img, out, cv::COLOR_GRAY2BGR);
  else if (img.channels() == 4) cv::cvtColor(img, out, cv::COLOR_BGRA2BGR);
  else out = img.clone();
  if (out.depth() != CV_8U) out.convertTo(out, CV_8U);
  return out;
}

cv::Mat dimmed(const cv::Mat& bgr, double factor) {
  cv::Mat gray, out;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::cvtColor(gray, out, cv::COLOR_GRAY2BGR);
  return out * factor;
}

// Ground normal of the frame: SURFACE_NORMALS, else EXTRINSICS pitch/roll, else straight up.
cv::Vec3f groundNormal(const LogFrame& f) {
  if (f.normals) {
    cv::Vec3f g(f.normals->ground_normal_x, f.normals->ground_normal_y, f.normals->ground_normal_z);
    const double n = cv::norm(g);
    if (std::isfinite(n) && n > 0.5) return g / static_cast<float>(n);
  }
  if (f.extrinsics && f.extrinsics->valid && std::isfinite(f.extrinsics->pitch_deg) &&
      std::isfinite(f.extrinsics->roll_deg)) {
    // The inverse of pitch = atan2(-n_z, -n_y), roll = atan2(-n_x, -n_y) with n_y < 0.
    const double tp = std::tan(f.extrinsics->pitch_deg * CV_PI / 180), tr = std::tan(f.extrinsics->roll_deg * CV_PI / 180);
    cv::Vec3f g(float(-tr), -1.0f, float(-tp));
    return g / static_cast<float>(cv::norm(g));
  }
  return {0, -1, 0};
}

// Non-zero inside hypotheses whose normal statistics show upright support
// (the snv stage then counts their facing normals as object surfaces).
cv::Mat uprightMask(const LogFrame& f, cv::Size size) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8U);
  if (!f.normals || !f.stixels) return mask;
  for (const auto& s : f.normals->rois) {
    if (!(s.object_fraction > 0) || s.error_fraction > 0) continue;
    for (const auto& r : f.stixels->rois)
      if (r.id == s.roi_id) {
        const cv::Rect box = cv::Rect(r.x, r.y, std::max(0, r.w), std::max(0, r.h)) & cv::Rect({}, size);
        if (box.area() > 0) mask(box).setTo(255);
      }
  }
  return mask;
}

void drawInfo(cv::Mat& panel, const LogFrame& f) {
  std::vector<std::pair<std::string, cv::Scalar>> lines;
  char buf[160];
  const cv::Scalar white = cv::Scalar::all(235);
  std::snprintf(buf, sizeof buf, "seq %lld  %s", static_cast<long long>(f.seq), f.frame_id.c_str());
  lines.push_back({buf, white});
  if (f.detections) {
    std::snprintf(buf, sizeof buf, "hypotheses %d, kept %d", f.detections->num_detections, f.detections->num_kept);
    lines.push_back({buf, white});
    if (f.detections->num_columns > 0) {  // free or unseen (magenta band in panel 3)
      std::snprintf(buf, sizeof buf, "free space measured %.0f %%, %d of %d strips unobserved",
                    100.0 * f.detections->observed_share, f.detections->num_unobserved, f.detections->num_columns);
      lines.push_back({buf, white});
    }
  } else {
    lines.push_back({"no DETECTIONS for this frame", kRemovedColor});
  }
  if (f.extrinsics) {
    const auto& e = *f.extrinsics;
    std::snprintf(buf, sizeof buf, "pitch %.2f deg  roll %.2f deg  height %.2f m  (%s)", e.pitch_deg, e.roll_deg,
                  e.height_m, e.status.c_str());
    lines.push_back({buf, white});
    std::snprintf(buf, sizeof buf, "instant pitch %.2f  mode %.2f  mean %.2f  mean-shift %.2f deg", e.instant_pitch_deg,
                  e.pitch_mode_deg, e.pitch_mean_deg, e.pitch_mean_shift_deg);
    lines.push_back({buf, white});
    std::snprintf(buf, sizeof buf, "entropy %.2f bits  confidence %.2f  inliers %d / %d", e.entropy, e.confidence,
                  e.inliers, e.num_normals);
    lines.push_back({buf, white});
  } else {
    lines.push_back({"no EXTRINSICS for this frame", kRemovedColor});
  }
  if (f.disparity) {
    std::snprintf(buf, sizeof buf, "disparity: %s, %.0f..%.0f px", f.disparity->algorithm.c_str(),
                  f.disparity->min_disparity, f.disparity->max_disparity);
    lines.push_back({buf, white});
  }
  std::string ms = "stage ms:";
  if (f.disparity) ms += " matcher " + cv::format("%.1f", f.disparity->processing_ms);
  if (f.stixels) ms += " stixel " + cv::format("%.1f", f.stixels->processing_ms);
  if (f.normals) ms += " snv " + cv::format("%.1f", f.normals->processing_ms);
  if (f.detections) ms += " validator " + cv::format("%.2f", f.detections->processing_ms);
  lines.push_back({ms, white});
  if (f.detections && f.detections_log_utime >= 0)
    lines.push_back({cv::format("latency capture -> DETECTIONS %.1f ms",
                                (f.detections_log_utime - f.detections->header.utime) / 1000.0), white});
  lines.push_back({"", white});
  lines.push_back({"boxes: kept detection (distance, class)", kKeptColor});
  lines.push_back({"       removed hypothesis: GND ground, ERR error, UNV unvalidated;", kRemovedColor});
  lines.push_back({"       tall/low/wide: size limit, none/few/mix: normal evidence, NN%: share", kRemovedColor});
  lines.push_back({"       ground truth (DontCare grey)", kLabelColor});
  lines.push_back({"ground model / horizon row", kGroundColor});
  lines.push_back({"band along the lower edge: free space not measured (unknown, not free)", kUnobservedColor});
  int y = 24;
  for (const auto& [text, color] : lines) {
    cv::putText(panel, text, {12, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, color, 1, cv::LINE_AA);
    y += 22;
  }
}

}  // namespace

cv::Point panelOrigin(int index, cv::Size cell) {
  return {(index % kGridColumns) * cell.width, (index / kGridColumns) * (cell.height + kTitleBarPx) + kTitleBarPx};
}

cv::Mat leftImage(const LogFrame& frame, std::string* problem) {
  if (!frame.stereo) {
    if (problem) *problem = "no STEREO_FRAME";
    return {};
  }
  cv::Mat img;
  const std::string why = decodeImage(frame.stereo->left, img);
  if (!why.empty() || img.empty()) {
    if (problem) *problem = "left image: " + (why.empty() ? std::string("empty") : why);
    return {};
  }
  if (!frame.stereo->calib.rectified) {
    // A raw view: everything drawn on it (boxes, stixels, disparity) refers to the pair the
    // stereo_matcher rectified, so the view is rectified the same way first.
    static Rectifier rectifier;
    try {
      img = rectifier.rectifyLeft(toRawCalibration(frame.stereo->calib), img);
    } catch (const std::invalid_argument& e) {
      if (problem) *problem = std::string("raw left image cannot be rectified: ") + e.what();
      return {};
    }
  }
  return toBgr(img);
}

cv::Mat renderFrameGrid(const LogFrame& f, const GridOptions& options, std::string* problem) {
  const cv::Mat left = leftImage(f, problem);
  if (left.empty()) return {};
  const cv::Size cell = left.size();
  std::vector<cv::Mat> panels(kPanelCount);
  std::vector<std::string> titles(kPanelCount);

  // 0: detections and ground truth
  panels[0] = left.clone();
  if (options.labels) drawGroundTruth(panels[0], *options.labels);
  if (f.detections) drawDetections(panels[0], *f.detections);
  else drawLabel(panels[0], "no DETECTIONS for this frame", {12, 24}, kRemovedColor, 0.6);
  titles[0] = f.detections ? cv::format("detections: %d kept (green), %d removed (red)%s", f.detections->num_kept,
                                        f.detections->num_detections - f.detections->num_kept,
                                        options.labels ? ", ground truth (light blue)" : "")
                           : std::string("detections");

  // 1, 3, 4: from the disparity
  cv::Mat disparity;
  std::string disparity_problem = "no DISPARITY for this frame";
  if (f.disparity) {
    disparity_problem = decodeDisparity(*f.disparity, disparity);
    if (disparity_problem.empty() && disparity.size() != cell) cv::resize(disparity, disparity, cell, 0, 0, cv::INTER_NEAREST);
    if (!disparity_problem.empty()) {
      disparity_problem = "DISPARITY: " + disparity_problem;
      disparity.release();
    }
  }
  float max_d = f.disparity ? f.disparity->max_disparity : 0;
  if (!(max_d > 1) || !std::isfinite(max_d) || max_d > 4096) max_d = 128;
  if (!disparity.empty()) {
    panels[1] = colorizeDisparity(disparity, max_d);
    if (f.stixels) drawGroundOnDisparity(panels[1], disparity, f.stixels->ground);
    else drawLabel(panels[1], "no STIXELS: no ground model", {8, cell.height - 10}, cv::Scalar::all(255));
    drawColorBar(panels[1], {cell.width - 230, 18, 200, 10}, false, 0, max_d, "px");
  } else {
    panels[1] = emptyPanel(cell, disparity_problem);
  }
  titles[1] = "disparity (turbo, near = red) + ground model (light) + horizon (yellow)";

  panels[2] = dimmed(left, 0.8);
  if (f.stixels) drawStixels(panels[2], *f.stixels);
  else drawLabel(panels[2], "no STIXELS for this frame", {12, 24}, kRemovedColor, 0.6);
  titles[2] = f.stixels ? cv::format("stixels by depth: %d stixels, %d hypotheses", f.stixels->num_stixels,
                                     f.stixels->num_rois)
                        : std::string("stixels");

  if (!disparity.empty()) {
    panels[3] = dimmed(left, 0.5);
    const StereoCamera cam = toCamera(f.disparity->calib);
    if (cam.problem().empty()) {
      const auto needles = computeNeedles(disparity, cam, groundNormal(f), uprightMask(f, cell), options.needles);
      drawNeedles(panels[3], needles, cam);
      titles[3] = cv::format("surface normals (recomputed, every %d px) vs ground normal%s", options.needles.interval_px,
                             f.normals ? " of SURFACE_NORMALS" : " (no SURFACE_NORMALS: from pose)");
    } else {
      panels[3] = emptyPanel(cell, "DISPARITY calibration: " + cam.problem());
      titles[3] = "surface normals";
    }
  } else {
    panels[3] = emptyPanel(cell, disparity_problem);
    titles[3] = "surface normals";
  }

  panels[4] = disparity.empty() ? emptyPanel(cell, disparity_problem)
                                : vDisparityPanel(disparity, max_d, f.stixels ? &f.stixels->ground : nullptr, cell);
  titles[4] = "v-disparity (log count) + fitted ground line (orange) + horizon";

  panels[5] = cv::Mat(cell, CV_8UC3, cv::Scalar::all(20));
  drawInfo(panels[5], f);
  titles[5] = "frame";

  cv::Mat grid(kGridRows * (cell.height + kTitleBarPx), kGridColumns * cell.width, CV_8UC3, cv::Scalar::all(45));
  for (int i = 0; i < kPanelCount; ++i) {
    const cv::Point o = panelOrigin(i, cell);
    panels[i].copyTo(grid(cv::Rect(o, cell)));
    cv::putText(grid, cv::format("%d  %s", i + 1, titles[i].c_str()), {o.x + 8, o.y - 8}, cv::FONT_HERSHEY_SIMPLEX,
                0.55, cv::Scalar::all(255), 1, cv::LINE_AA);
  }
  return grid;
}

}  // namespace nerv::viz
