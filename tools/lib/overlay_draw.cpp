#include "overlay_draw.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "color_map.hpp"

namespace nerv::viz {

namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Rect clipped(int x, int y, int w, int h, const cv::Mat& img) {
  return cv::Rect(x, y, std::max(w, 0), std::max(h, 0)) & cv::Rect(0, 0, img.cols, img.rows);
}

// A finite value in a range that cv drawing calls accept.
int safeInt(double v, int lo, int hi) {
  if (!std::isfinite(v)) return lo;
  return static_cast<int>(std::clamp(v, double(lo), double(hi)));
}

}  // namespace

std::string removalCode(const detection_t& d) {
  std::string code;
  if (d.label == "ground") code = "GND";
  else if (d.label == "error") code = "ERR";
  else if (d.label == "unvalidated") code = "UNV";
  else if (d.label == "object") code = "OBJ";
  else {
    for (char c : d.label.substr(0, 3)) code += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (code.empty()) code = "?";
  }
  // What the validator's reason says, in a word: size limits and missing
  // evidence by name, normal fractions by their first "NN%".
  const std::string& r = d.reason;
  auto has = [&](const char* w) { return r.find(w) != std::string::npos; };
  if (has("height") && has("above")) return code + " tall";
  if (has("height") && has("below")) return code + " low";
  if (has("width") && has("above")) return code + " wide";
  if (has("no normals")) return code + " none";
  if (has("only ") && has("normals")) return code + " few";
  if (has("mixed")) return code + " mix";
  const size_t pct = d.reason.find('%');
  if (pct != std::string::npos) {
    size_t start = pct;
    while (start > 0 && (std::isdigit(static_cast<unsigned char>(d.reason[start - 1])) || d.reason[start - 1] == '.'))
      --start;
    if (start < pct) code += " " + d.reason.substr(start, pct - start + 1);
  }
  return code;
}

void drawLabel(cv::Mat& img, const std::string& text, cv::Point origin, const cv::Scalar& color,
               double scale) {
  int base = 0;
  const cv::Size s = cv::getTextSize(text, kFont, scale, 1, &base);
  origin.x = std::clamp(origin.x, 0, std::max(0, img.cols - s.width - 2));
  origin.y = std::clamp(origin.y, s.height + 2, std::max(s.height + 2, img.rows - base - 1));
  const cv::Rect box = clipped(origin.x - 1, origin.y - s.height - 2, s.width + 3, s.height + base + 3, img);
  if (box.area() > 0) img(box) *= 0.25;
  cv::putText(img, text, origin, kFont, scale, color, 1, cv::LINE_AA);
}

void drawDetections(cv::Mat& img, const detections_t& detections) {
  const int W = img.cols, H = img.rows;
  // Removed first, so kept boxes stay on top where they overlap.
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& d : detections.detections) {
      if (d.kept != (pass == 1)) continue;
      const cv::Point p1(safeInt(d.x, -W, 2 * W), safeInt(d.y, -H, 2 * H));
      const cv::Point p2(safeInt(double(d.x) + d.w - 1, -W, 2 * W), safeInt(double(d.y) + d.h - 1, -H, 2 * H));
      const cv::Scalar color = d.kept ? kKeptColor : kRemovedColor;
      cv::rectangle(img, p1, p2, color, d.kept ? 2 : 1);
      char text[96];
      if (d.kept)
        // The depth of the nearest part (what the car keeps its distance from);
        // logs from before that field show the distance of the base centre.
        std::snprintf(text, sizeof text, "%.1f m %s", d.nearest_z_m > 0 ? d.nearest_z_m : d.distance_m,
                      d.label.c_str());
      else
        std::snprintf(text, sizeof text, "%s", removalCode(d).c_str());
      // Kept labels above the box, removal codes inside its bottom edge.
      drawLabel(img, text, d.kept ? cv::Point(p1.x, p1.y - 4) : cv::Point(p1.x + 2, p2.y - 3), color,
                d.kept ? 0.45 : 0.38);
    }
  }
}

void drawGroundTruth(cv::Mat& img, const std::vector<KittiLabel>& labels) {
  const int W = img.cols, H = img.rows;
  for (const auto& l : labels) {
    const bool dontcare = l.type == "DontCare";
    const cv::Point p1(safeInt(l.x1, -W, 2 * W), safeInt(l.y1, -H, 2 * H));
    const cv::Point p2(safeInt(l.x2, -W, 2 * W), safeInt(l.y2, -H, 2 * H));
    cv::rectangle(img, p1, p2, dontcare ? kDontCareColor : kLabelColor, 1, cv::LINE_4);
  }
}

void drawGroundOnDisparity(cv::Mat& panel, const cv::Mat& disparity, const ground_model_t& ground) {
  if (!ground.valid || !std::isfinite(ground.vd_slope) || !std::isfinite(ground.vd_intercept)) {
    drawLabel(panel, "no valid ground model", {8, panel.rows - 10}, cv::Scalar::all(255));
    return;
  }
  if (disparity.size() == panel.size()) {
    for (int v = 0; v < panel.rows; ++v) {
      const float dg = ground.vd_slope * v + ground.vd_intercept;
      if (!(dg > 0)) continue;
      const float tol = std::max(1.0f, 0.05f * dg);
      const float* d = disparity.ptr<float>(v);
      cv::Vec3b* o = panel.ptr<cv::Vec3b>(v);
      for (int u = 0; u < panel.cols; ++u)
        if (d[u] > 0 && std::abs(d[u] - dg) <= tol)
          o[u] = cv::Vec3b(static_cast<uint8_t>(o[u][0] / 3 + 170), static_cast<uint8_t>(o[u][1] / 3 + 170),
                           static_cast<uint8_t>(o[u][2] / 3 + 170));
    }
  }
  if (std::isfinite(ground.horizon_row)) {
    const int h = safeInt(ground.horizon_row, -1, panel.rows);
    if (h >= 0 && h < panel.rows) {
      cv::line(panel, {0, h}, {panel.cols - 1, h}, kHorizonColor, 1);
      char text[64];
      std::snprintf(text, sizeof text, "horizon v=%.0f", ground.horizon_row);
      drawLabel(panel, text, {8, h - 4}, kHorizonColor);
    }
  }
  char text[128];
  std::snprintf(text, sizeof text, "ground (%s): d = %.4f v %+.2f, pitch %.2f deg, h %.2f m",
                ground.source.c_str(), ground.vd_slope, ground.vd_intercept, ground.pitch_deg,
                ground.height_m);
  drawLabel(panel, text, {8, panel.rows - 10}, cv::Scalar::all(255));
}

void drawStixels(cv::Mat& panel, const stixels_t& stixels) {
  cv::Mat overlay = panel.clone();
  for (const auto& s : stixels.stixels) {
    const cv::Rect r = clipped(s.u, s.top_row, s.width, s.bottom_row - s.top_row + 1, panel);
    if (r.area() <= 0) continue;
    const cv::Vec3b c = depthColor(s.depth_m);
    cv::rectangle(overlay, r, cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  cv::addWeighted(overlay, 0.6, panel, 0.4, 0, panel);
  for (const auto& s : stixels.stixels) {  // foot points: where free space ends
    const cv::Rect r = clipped(s.u, s.bottom_row - 1, s.width, 2, panel);
    if (r.area() > 0) panel(r).setTo(cv::Scalar::all(255));
  }
  // Strips whose free space was not measured (unknown, not free): a magenta band
  // along the lower edge (stixels_t.observed).
  for (int k = 0; k < stixels.num_columns && k < static_cast<int>(stixels.observed.size()); ++k) {
    if (stixels.observed[k] >= stixels.min_observed) continue;
    const cv::Rect r = clipped(k * stixels.column_width_px, panel.rows - kUnobservedBandPx, stixels.column_width_px,
                               kUnobservedBandPx, panel);
    if (r.area() > 0) panel(r).setTo(kUnobservedColor);
  }
  drawColorBar(panel, {panel.cols - 230, 18, 200, 10}, true, 3, 60, "m");
}

void drawNeedles(cv::Mat& panel, const std::vector<Needle>& needles, const StereoCamera& cam) {
  for (const auto& nd : needles) {
    const cv::Scalar color = nd.cls == NeedleClass::kGround   ? kGroundColor
                             : nd.cls == NeedleClass::kObject ? kObjectColor
                             : nd.cls == NeedleClass::kError  ? kErrorColor
                                                              : kOtherColor;
    // Needle length grows with depth so it projects to about 12 px.
    const double s = 12.0 * nd.p[2] / std::max(1.0, cam.fx);
    const Point3 tip{nd.p[0] + s * nd.n[0], nd.p[1] + s * nd.n[1], nd.p[2] + s * nd.n[2]};
    double u = 0, v = 0;
    cv::circle(panel, {nd.u, nd.v}, 1, color, cv::FILLED);
    if (cam.project(tip, u, v) && std::abs(u - nd.u) < 40 && std::abs(v - nd.v) < 40)
      cv::line(panel, {nd.u, nd.v}, {int(std::lround(u)), int(std::lround(v))}, color, 1, cv::LINE_AA);
  }
  int x = 8;
  for (const auto& [name, color] : {std::pair<const char*, cv::Scalar>{"ground", kGroundColor},
                                    {"object", kObjectColor}, {"error", kErrorColor}, {"other", kOtherColor}}) {
    drawLabel(panel, name, {x, panel.rows - 10}, color);
    x += 70;
  }
}

cv::Mat vDisparityPanel(const cv::Mat& disparity, float max_disparity, const ground_model_t* ground,
                        cv::Size size) {
  cv::Mat panel(size, CV_8UC3, cv::Scalar::all(0));
  if (disparity.empty() || size.width < 40 || size.height < 20) return panel;
  if (!(max_disparity > 1) || !std::isfinite(max_disparity) || max_disparity > 4096) max_disparity = 128;
  const int bins = static_cast<int>(std::ceil(max_disparity)) + 1;
  cv::Mat counts = cv::Mat::zeros(disparity.rows, bins, CV_32F);
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    float* c = counts.ptr<float>(v);
    for (int u = 0; u < disparity.cols; ++u)
      if (d[u] > 0 && d[u] < bins) c[static_cast<int>(d[u] + 0.5f) % bins] += 1;
  }
  double max_count = 0;
  cv::minMaxLoc(counts, nullptr, &max_count);
  cv::Mat gray;
  cv::log(counts + 1, counts);
  counts.convertTo(gray, CV_8U, max_count > 0 ? 255.0 / std::log(max_count + 1) : 0);
  // Plot area: left margin for the row axis, bottom margin for the disparity axis.
  const int left = 36, bottom = 34;
  const cv::Rect plot(left, 0, std::min(size.width - left - 4, bins * 4), size.height - bottom);
  cv::Mat stretched;
  cv::resize(gray, stretched, plot.size(), 0, 0, cv::INTER_AREA);
  cv::cvtColor(stretched, panel(plot), cv::COLOR_GRAY2BGR);
  const double kx = double(plot.width) / bins, ky = double(plot.height) / disparity.rows;
  auto at = [&](double d, double v) { return cv::Point(plot.x + int(std::lround(d * kx)), int(std::lround(v * ky))); };
  // Axes and ticks: disparity every 16 px, rows every 100.
  cv::rectangle(panel, plot, cv::Scalar::all(200), 1);
  for (int d = 0; d < bins; d += 16) {
    const cv::Point p = at(d, disparity.rows);
    cv::line(panel, p, p + cv::Point(0, 4), cv::Scalar::all(200));
    cv::putText(panel, std::to_string(d), p + cv::Point(-6, 16), kFont, 0.35, cv::Scalar::all(220), 1, cv::LINE_AA);
  }
  cv::putText(panel, "disparity d [px]", {plot.x + plot.width / 2 - 50, size.height - 4}, kFont, 0.4,
              cv::Scalar::all(220), 1, cv::LINE_AA);
  for (int v = 0; v < disparity.rows; v += 100) {
    const cv::Point p = at(0, v);
    cv::line(panel, p, p - cv::Point(4, 0), cv::Scalar::all(200));
    cv::putText(panel, std::to_string(v), {2, std::max(10, p.y + 4)}, kFont, 0.35, cv::Scalar::all(220), 1, cv::LINE_AA);
  }
  cv::putText(panel, "row v", {2, plot.height / 2}, kFont, 0.35, cv::Scalar::all(220), 1, cv::LINE_AA);
  if (ground && ground->valid && std::isfinite(ground->vd_slope) && std::isfinite(ground->vd_intercept)) {
    // d = slope * v + intercept, drawn over the rows where 0 <= d < bins.
    std::vector<cv::Point> line;
    for (int v = 0; v < disparity.rows; ++v) {
      const double d = ground->vd_slope * v + ground->vd_intercept;
      if (d >= 0 && d < bins) line.push_back(at(d, v));
    }
    if (line.size() >= 2) cv::polylines(panel, line, false, kGroundColor, 2, cv::LINE_AA);
    if (std::isfinite(ground->horizon_row) && ground->horizon_row >= 0 && ground->horizon_row < disparity.rows) {
      const int h = at(0, ground->horizon_row).y;
      cv::line(panel, {plot.x, h}, {plot.x + plot.width - 1, h}, kHorizonColor, 1);
    }
    char text[96];
    std::snprintf(text, sizeof text, "d = %.4f v %+.2f", ground->vd_slope, ground->vd_intercept);
    drawLabel(panel, text, {plot.x + 6, 16}, kGroundColor);
  } else {
    drawLabel(panel, "no valid ground line", {plot.x + 6, 16}, cv::Scalar::all(255));
  }
  return panel;
}

cv::Mat emptyPanel(cv::Size size, const std::string& why) {
  cv::Mat panel(size, CV_8UC3, cv::Scalar::all(30));
  drawLabel(panel, why, {16, size.height / 2}, cv::Scalar::all(255), 0.6);
  return panel;
}

}  // namespace nerv::viz
