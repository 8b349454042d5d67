// The stixel stage on real KITTI raw frames (../shared/data, skipped when absent):
// camera height from the v-disparity line, the car ahead, recall on the
// hand-made Car/Pole labels. Set NERV_STIXEL_OVERLAY_DIR to write overlays.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dataset.hpp"
#include "stixel_estimator.hpp"

namespace nerv::stixel {
namespace {

struct LabelBox {
  std::string type;
  cv::Rect2f box;
};

std::vector<LabelBox> readLabels(const std::string& path) {
  std::vector<LabelBox> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    LabelBox l;
    float trunc, occ, alpha, x0, y0, x1, y1;
    if (ss >> l.type >> trunc >> occ >> alpha >> x0 >> y0 >> x1 >> y1) {
      l.box = cv::Rect2f(x0, y0, x1 - x0, y1 - y0);
      out.push_back(l);
    }
  }
  return out;
}

float iou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float inter = (a & b).area();
  const float uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0f;
}

cv::Rect2f toRect(const Box& b) { return cv::Rect2f(b.x, b.y, b.w, b.h); }

// SGBM as the brief fixes it: gray, 128 levels, block 5, P1 8*25, P2 32*25, 3-way.
cv::Mat sgbmDisparity(const std::string& left_path, const std::string& right_path) {
  const cv::Mat l = cv::imread(left_path, cv::IMREAD_GRAYSCALE);
  const cv::Mat r = cv::imread(right_path, cv::IMREAD_GRAYSCALE);
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 0, 0, 0, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, disp;
  sgbm->compute(l, r, raw);
  raw.convertTo(disp, CV_32F, 1.0 / 16.0);
  cv::threshold(disp, disp, 0.0, 0.0, cv::THRESH_TOZERO);
  return disp;
}

struct Frame {
  DatasetFrame meta;
  cv::Mat disparity;
  StixelResult result;
};

// Disparities are computed once for all tests of this program.
const std::vector<Frame>& frames() {
  static std::vector<Frame> cache = [] {
    std::vector<Frame> out;
    const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
    if (!std::filesystem::exists(dir)) return out;
    const Dataset ds = openDataset(dir);
    for (const DatasetFrame& f : ds.frames) {
      Frame fr;
      fr.meta = f;
      fr.disparity = sgbmDisparity(f.left_path, f.right_path);
      fr.result = estimateStixels(fr.disparity, f.camera, Params{});
      out.push_back(std::move(fr));
    }
    return out;
  }();
  return cache;
}

void writeOverlay(const Frame& fr, const std::vector<LabelBox>& labels) {
  const char* dir = std::getenv("NERV_STIXEL_OVERLAY_DIR");
  if (!dir) return;
  cv::Mat img = cv::imread(fr.meta.left_path);
  for (const Stixel& s : fr.result.stixels)
    cv::rectangle(img, cv::Rect(s.u, s.top_row, s.width, s.bottom_row - s.top_row + 1),
                  cv::Scalar(0, 255 - std::min(255, static_cast<int>(s.depth_m * 5)), 255), 1);
  for (const LabelBox& l : labels)
    if (l.type != "DontCare") cv::rectangle(img, cv::Rect(l.box), cv::Scalar(0, 255, 0), 1);
  for (const Hypothesis& h : fr.result.hypotheses) {
    cv::rectangle(img, cv::Rect(h.box.x, h.box.y, h.box.w, h.box.h), cv::Scalar(255, 0, 0), 2);
    cv::putText(img, cv::format("%.1f", h.distance_m), cv::Point(h.box.x, h.box.y - 2),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(255, 255, 0));
  }
  const GroundModel& g = fr.result.ground;
  if (g.valid) cv::line(img, {0, int(g.horizon_row)}, {img.cols, int(g.horizon_row)}, {0, 0, 255});
  cv::imwrite(std::string(dir) + "/" + fr.meta.name + ".png", img);
}

TEST(stixelKitti, CameraHeightWithinTenCentimetresOnEveryFrame) {
  if (frames().empty()) GTEST_SKIP() << "no " << NERV_SHARED_DATA << "/kitti_raw_0926_seq";
  for (const Frame& fr : frames()) {
    const GroundModel& g = fr.result.ground;
    std::printf("frame %s  ground %s  height %.3f m  pitch %.2f deg  horizon %.1f  line d = %.4f v %+.2f"
                "  inliers %d  residual %.2f px\n",
                fr.meta.name.c_str(), g.source.c_str(), g.height_m, g.pitch_deg, g.horizon_row,
                g.vd_slope, g.vd_intercept, g.inliers, g.residual_px);
    ASSERT_TRUE(g.valid) << fr.meta.name;
    EXPECT_EQ(g.source, "v_disparity");
    EXPECT_NEAR(g.height_m, 1.65, 0.1) << fr.meta.name;
  }
}

TEST(stixelKitti, CarAheadInFrameZero) {
  if (frames().empty()) GTEST_SKIP() << "no " << NERV_SHARED_DATA << "/kitti_raw_0926_seq";
  const cv::Rect2f car(605, 176, 681 - 605, 234 - 176);
  float best = 0;
  const Hypothesis* match = nullptr;
  for (const Hypothesis& h : frames()[0].result.hypotheses)
    if (iou(toRect(h.box), car) > best) best = iou(toRect(h.box), car), match = &h;
  ASSERT_NE(match, nullptr);
  std::printf("car ahead: box %d %d %d %d  IoU %.2f  distance %.2f m (label 19.66 m)\n",
              match->box.x, match->box.y, match->box.w, match->box.h, best, match->distance_m);
  EXPECT_GT(best, 0.5f);
  EXPECT_NEAR(match->z_m, 19.66, 1.0);
}

TEST(stixelKitti, RecallOnCarAndPoleLabels) {
  if (frames().empty()) GTEST_SKIP() << "no " << NERV_SHARED_DATA << "/kitti_raw_0926_seq";
  int cars = 0, cars_hit = 0, poles = 0, poles_hit = 0, hyps = 0, hyps_on_label = 0;
  for (const Frame& fr : frames()) {
    const auto labels = readLabels(fr.meta.label_path);
    writeOverlay(fr, labels);
    for (const LabelBox& l : labels) {
      if (l.type != "Car" && l.type != "Pole") continue;
      float best = 0;
      for (const Hypothesis& h : fr.result.hypotheses) best = std::max(best, iou(toRect(h.box), l.box));
      const bool hit = best > 0.5f;
      (l.type == "Car" ? cars : poles)++;
      if (hit) (l.type == "Car" ? cars_hit : poles_hit)++;
      if (!hit)
        std::printf("  miss %s %s [%.0f %.0f %.0f %.0f] best IoU %.2f\n", fr.meta.name.c_str(),
                    l.type.c_str(), l.box.x, l.box.y, l.box.br().x, l.box.br().y, best);
    }
    // Precision-like figure: hypotheses overlapping any label (DontCare included).
    for (const Hypothesis& h : fr.result.hypotheses) {
      ++hyps;
      for (const LabelBox& l : labels)
        if ((toRect(h.box) & l.box).area() > 0.5f * toRect(h.box).area()) {
          ++hyps_on_label;
          break;
        }
    }
  }
  const double car_recall = cars ? double(cars_hit) / cars : 0.0;
  const double pole_recall = poles ? double(poles_hit) / poles : 0.0;
  std::printf("recall (IoU > 0.5): Car %d/%d = %.2f  Pole %d/%d = %.2f  all %.2f\n", cars_hit,
              cars, car_recall, poles_hit, poles, pole_recall,
              double(cars_hit + poles_hit) / std::max(1, cars + poles));
  std::printf("hypotheses: %d, of which %d mostly inside a labelled box (incl. DontCare)\n", hyps,
              hyps_on_label);
  EXPECT_GE(car_recall, 0.7);
}

}  // namespace
}  // namespace nerv::stixel
