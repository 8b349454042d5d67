// Ground truth of the synthetic scenes against geometry computed here
// independently: road and obstacle disparity, label boxes, extrinsics, and
// bit-identical rendering for a seed.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene_yaml.hpp"
#include "sequence.hpp"

namespace {

using namespace nerv::synth;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// An empty straight road (no traffic, no background) at a small image size.
SceneSpec emptyRoad(double pitch_deg, double roll_deg, double height_m) {
  SceneSpec s = parseScene(
      "camera: {lateral_m: 1.75, speed_mps: 0}\n"
      "road: {lanes_right: 2, lanes_left: 2, sidewalk_width_m: 2}\n"
      "background: {buildings: false}\n",
      "empty_road");
  s.camera.pitch_deg = pitch_deg;
  s.camera.roll_deg = roll_deg;
  s.camera.height_m = height_m;
  resizeImage(s, 414, 125);
  return s;
}

// The road plane's "up" direction in the camera frame for a camera pitched
// down by `pitch` and rolled clockwise by `roll` (built with Eigen rotations,
// not with the generator's code): camera-to-world R = Rx(pitch) Rz(-roll) diag(1, -1, 1).
Eigen::Vector3d upInCamera(double pitch_deg, double roll_deg) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(-roll_deg * kDeg, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix() *
                            Eigen::Vector3d(1, -1, 1).asDiagonal();
  return R.transpose() * Eigen::Vector3d::UnitY();
}

// Disparity of the road plane at pixel (u, v); 0 above the horizon.
double roadDisparity(const nerv::StereoCamera& k, double pitch_deg, double roll_deg, double height_m,
                     int u, int v) {
  const Eigen::Vector3d ray((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
  const double down = -upInCamera(pitch_deg, roll_deg).dot(ray);  // metres down per metre of depth
  if (down <= 0) return 0;
  const double Z = height_m / down;
  return k.fx * k.baseline_m / Z;
}

// Checks every carriageway pixel (ground point 0.3 m inside the road edges, Z < 40 m).
void expectRoadDisparity(const SceneSpec& spec, const SynthFrame& f, double pitch, double roll,
                         double height, double lateral_m) {
  const nerv::StereoCamera& k = spec.camera.intrinsics;
  const Eigen::Vector3d up = upInCamera(pitch, roll);
  int checked = 0;
  double worst = 0;
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      if (f.images.object_id.at<int>(v, u) >= 0) continue;
      const double d = roadDisparity(k, pitch, roll, height, u, v);
      if (d <= 0) continue;
      const double Z = k.fx * k.baseline_m / d;
      if (Z > 40) continue;
      // Lateral road coordinate of the ground point (camera x along the road's right axis).
      const Eigen::Vector3d X = Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0) * Z;
      const Eigen::Vector3d x_axis = (Eigen::Vector3d::UnitX() - up * up.x()).normalized();
      const double x_road = lateral_m + x_axis.dot(X);
      if (x_road < spec.road.roadLeft() + 0.3 || x_road > spec.road.roadRight() - 0.3) continue;
      worst = std::max(worst, std::abs(f.images.disparity.at<float>(v, u) - d));
      ++checked;
    }
  EXPECT_GT(checked, 2000);
  EXPECT_LT(worst, 0.01) << "largest road disparity error [px]";
}

TEST(synthGeometry, RoadDisparityIsFxBOverZ) {
  for (const auto& [pitch, roll, height] : {std::tuple{0.0, 0.0, 1.65}, std::tuple{2.5, 1.2, 1.4},
                                           std::tuple{-1.5, -2.0, 2.0}}) {
    const SceneSpec spec = emptyRoad(pitch, roll, height);
    SceneSequence seq(spec);
    const SynthFrame f = seq.render(0);
    SCOPED_TRACE(testing::Message() << "pitch " << pitch << " roll " << roll << " height " << height);
    expectRoadDisparity(spec, f, pitch, roll, height, spec.camera.lateral_m);
    // Level camera: the textbook relation d = B (v - cy) / h per row.
    if (pitch == 0 && roll == 0) {
      const auto& k = spec.camera.intrinsics;
      const int v = k.height - 5, u = static_cast<int>(k.cx);
      EXPECT_NEAR(f.images.disparity.at<float>(v, u), k.baseline_m * (v - k.cy) / height, 0.01);
    }
  }
}

TEST(synthGeometry, ObstacleDisparityMatchesItsPosition) {
  SceneSpec spec = emptyRoad(0, 0, 1.65);
  ObstacleSpec car;
  car.cls = ObstacleClass::Car;
  car.distance_m = 15;
  car.lateral_m = 0.4;
  spec.obstacles.push_back(car);
  SceneSequence seq(spec);
  const SynthFrame f = seq.render(0);
  const auto& k = spec.camera.intrinsics;
  const Solid& s = seq.world().solids.at(0);
  const Part& body = s.parts.at(0);  // the lower body box
  const double z_rear = s.base.z() + body.c.z() - body.e.z();
  // A point on the rear face, above the plate and beside the lamps.
  const double x = s.base.x() - spec.camera.lateral_m + 0.25, y_up = 0.66;
  const double Z = z_rear;
  const int u = static_cast<int>(std::lround(k.fx * x / Z + k.cx));
  const int v = static_cast<int>(std::lround(k.fy * (spec.camera.height_m - y_up) / Z + k.cy));
  ASSERT_EQ(f.images.object_id.at<int>(v, u), 0);
  EXPECT_NEAR(f.images.disparity.at<float>(v, u), k.fx * k.baseline_m / z_rear, 0.01);
  // The label's 3D position is the object's bottom centre.
  ASSERT_FALSE(f.labels.empty());
  const Label& l = f.labels.front();
  EXPECT_EQ(l.type, "Car");
  EXPECT_NEAR(l.location.z(), 15.0, 1e-9);
  EXPECT_NEAR(l.location.x(), 0.4, 1e-9);
  EXPECT_NEAR(l.location.y(), 1.65, 1e-9);
  EXPECT_NEAR(l.rotation_y, -3.14159265358979 / 2, 1e-9);
}

TEST(synthGeometry, LabelBoxesAreTightBoxesOfVisiblePixels) {
  SceneSpec spec = loadScene(resolveScenePath("urban", NERV_SOURCE_DIR "/config/scenes"));
  resizeImage(spec, 621, 188);
  SceneSequence seq(spec);
  for (int frame : {0, 7}) {
    const SynthFrame f = seq.render(frame);
    int objects = 0;
    for (const Label& l : f.labels) {
      int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1, n = 0;
      for (int v = 0; v < f.images.object_id.rows; ++v)
        for (int u = 0; u < f.images.object_id.cols; ++u)
          if (f.images.object_id.at<int>(v, u) == l.solid) {
            x0 = std::min(x0, u), x1 = std::max(x1, u), y0 = std::min(y0, v), y1 = std::max(y1, v);
            ++n;
          }
      ASSERT_GT(n, 0) << "label of an invisible object";
      EXPECT_EQ(l.left, x0);
      EXPECT_EQ(l.right, x1);
      EXPECT_EQ(l.top, y0);
      EXPECT_EQ(l.bottom, y1);
      objects += l.type != "DontCare";
    }
    EXPECT_GE(objects, 5);
    // Every labelled obstacle within 40 m stands inside the image with its feet visible.
    int near = 0, feet = 0;
    for (const Label& l : f.labels) {
      if (l.type == "DontCare" || l.location.z() > 40 || l.truncation > 0) continue;
      ++near;
      const auto& k = spec.camera.intrinsics;
      const double v_foot = k.fy * l.location.y() / l.location.z() + k.cy;
      feet += v_foot < k.height;
    }
    EXPECT_GE(near, 3);
    EXPECT_EQ(feet, near);
  }
}

TEST(synthGeometry, LabelMinRunDropsColumnsThinnerThanIt) {
  // --label-min-run 3: an object box's left and right are its outermost
  // columns with at least 3 of its pixels (a parked car's 1-2 row roof sliver
  // above the next car no longer widens it); top and bottom stay tight.
  SceneSpec spec = loadScene(resolveScenePath("urban", NERV_SOURCE_DIR "/config/scenes"));
  resizeImage(spec, 621, 188);
  SceneSequence seq(spec);
  RenderOptions trimmed;
  trimmed.label_min_run_px = 3;
  int narrowed = 0;
  for (int frame : {0, 7}) {
    const SynthFrame f = seq.render(frame, trimmed);
    for (const Label& l : f.labels) {
      std::vector<int> cols(static_cast<size_t>(f.images.object_id.cols), 0);
      int y0 = 1 << 30, y1 = -1, x0 = 1 << 30, x1 = -1;
      for (int v = 0; v < f.images.object_id.rows; ++v)
        for (int u = 0; u < f.images.object_id.cols; ++u)
          if (f.images.object_id.at<int>(v, u) == l.solid)
            ++cols[static_cast<size_t>(u)], y0 = std::min(y0, v), y1 = std::max(y1, v), x0 = std::min(x0, u),
                x1 = std::max(x1, u);
      EXPECT_EQ(l.top, y0);
      EXPECT_EQ(l.bottom, y1);
      if (l.type == "DontCare") continue;
      int c0 = -1, c1 = -1;
      for (int u = 0; u < static_cast<int>(cols.size()); ++u)
        if (cols[static_cast<size_t>(u)] >= 3) c1 = u, c0 = c0 < 0 ? u : c0;
      EXPECT_EQ(l.left, c0 < 0 ? x0 : c0);
      EXPECT_EQ(l.right, c0 < 0 ? x1 : c1);
      narrowed += l.left != x0 || l.right != x1;
    }
  }
  EXPECT_GE(narrowed, 1) << "no label lost a thin column on two urban frames";
}

TEST(synthGeometry, ExtrinsicsFileMatchesCameraAndRenderedRoad) {
  SceneSpec spec = loadScene(resolveScenePath("pitch_oscillation", NERV_SOURCE_DIR "/config/scenes"));
  resizeImage(spec, 310, 94);
  const std::string dir = (std::filesystem::temp_directory_path() / "nerv_test_synth_extrinsics").string();
  std::filesystem::remove_all(dir);
  writeSequence(spec, 8, dir);
  std::ifstream in(dir + "/extrinsics.txt");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("# frame pitch_deg roll_deg height_m", 0), 0u);
  SceneSequence seq(spec);
  const CameraRig& rig = spec.camera;
  double max_pitch = 0;
  for (int i = 0; i < 8; ++i) {
    int frame;
    double pitch, roll, height;
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream(line) >> frame >> pitch >> roll >> height;
    EXPECT_EQ(frame, i);
    // The configured motion: sinusoidal pitch swing + heave, roll swing, bumps.
    const double t = i / rig.fps;
    const double phase = 2 * M_PI * t / rig.pitch_period_s;
    const double since = std::fmod(t, rig.bump_interval_s);
    const double want_pitch = rig.pitch_deg + rig.pitch_amplitude_deg * std::sin(phase) +
                              rig.bump_pitch_deg * std::exp(-since / 0.35) * std::sin(2 * M_PI * 1.5 * since);
    EXPECT_NEAR(pitch, want_pitch, 1e-5);
    EXPECT_NEAR(roll, rig.roll_amplitude_deg * std::sin(2 * M_PI * t / rig.roll_period_s), 1e-5);
    EXPECT_NEAR(height, rig.height_m - rig.height_amplitude_m * std::sin(phase), 1e-5);
    max_pitch = std::max(max_pitch, std::abs(pitch));
    // The rendered road agrees with the written pose (camera still on the flat part).
    const SynthFrame f = seq.render(i);
    expectRoadDisparity(spec, f, pitch, roll, height, spec.camera.lateral_m);
  }
  EXPECT_GT(max_pitch, 1.5);  // the swing is really there
  std::filesystem::remove_all(dir);
}

TEST(synthGeometry, RenderingIsBitIdenticalForASeed) {
  SceneSpec spec = loadScene(resolveScenePath("wet_road", NERV_SOURCE_DIR "/config/scenes"));
  resizeImage(spec, 414, 125);
  RenderOptions single;
  single.threads = 1;
  SceneSequence a(spec), b(spec);
  const SynthFrame fa = a.render(3), fb = b.render(3, single);
  EXPECT_EQ(cv::norm(fa.images.left, fb.images.left, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(fa.images.right, fb.images.right, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(fa.images.disparity, fb.images.disparity, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(fa.images.trap_mask, fb.images.trap_mask, cv::NORM_INF), 0);
  ASSERT_EQ(fa.labels.size(), fb.labels.size());
  for (size_t i = 0; i < fa.labels.size(); ++i) EXPECT_EQ(formatLabel(fa.labels[i]), formatLabel(fb.labels[i]));
  spec.seed += 1;
  SceneSequence c(spec);
  EXPECT_GT(cv::norm(fa.images.left, c.render(3).images.left, cv::NORM_L1), 0);
}

}  // namespace
