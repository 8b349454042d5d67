#include "kitti_writer.hpp"

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "scene.hpp"

namespace fs = std::filesystem;

namespace nerv::synth {
namespace {

const char* const kFolders[] = {"image_2", "image_3", "calib", "label_2", "disp_occ_0", "trap_mask"};

void writePng(const std::string& path, const cv::Mat& image) {
  // Fast compression: the images are noisy and barely compress anyway.
  if (!cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 1}))
    throw SceneError("cannot write " + path);
}

std::ofstream openText(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw SceneError("cannot write " + path);
  return f;
}

}  // namespace

std::string frameName(int index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06d", index);
  return buf;
}

void prepareOutput(const std::string& dir) {
  std::error_code ec;
  for (const char* sub : kFolders) {
    fs::create_directories(fs::path(dir) / sub, ec);
    if (ec) throw SceneError("cannot create " + (fs::path(dir) / sub).string() + ": " + ec.message());
  }
}

void writeCalibration(const std::string& path, const StereoCamera& k) {
  std::ofstream f = openText(path);
  char buf[512];
  auto projection = [&](const char* name, double tx) {
    std::snprintf(buf, sizeof buf, "%s: %.12e 0 %.12e %.12e 0 %.12e %.12e 0 0 0 1 0\n", name, k.fx, k.cx, tx,
                  k.fy, k.cy);
    f << buf;
  };
  // Cameras 0/1 (gray) and 2/3 (colour) share the rectified rig here; the
  // left camera is the reference, so P2 has no offset and P3[0][3] = -fx B.
  projection("P0", 0.0);
  projection("P1", -k.fx * k.baseline_m);
  projection("P2", 0.0);
  projection("P3", -k.fx * k.baseline_m);
  f << "R0_rect: 1 0 0 0 1 0 0 0 1\n";
  f << "Tr_velo_to_cam: 0 -1 0 0 0 0 -1 0 1 0 0 0\n";
  f << "Tr_imu_to_velo: 1 0 0 0 0 1 0 0 0 0 1 0\n";
  if (!f) throw SceneError("cannot write " + path);
}

void writeFrame(const std::string& dir, int index, const StereoCamera& camera, const RenderedFrame& frame,
                const std::vector<Label>& labels) {
  const std::string name = frameName(index);
  const fs::path root(dir);
  writePng((root / "image_2" / (name + ".png")).string(), frame.left);
  writePng((root / "image_3" / (name + ".png")).string(), frame.right);
  writeCalibration((root / "calib" / (name + ".txt")).string(), camera);
  cv::Mat disp16;
  frame.disparity.convertTo(disp16, CV_16U, 256.0);  // rounds and saturates; sky stays 0
  writePng((root / "disp_occ_0" / (name + ".png")).string(), disp16);
  writePng((root / "trap_mask" / (name + ".png")).string(), frame.trap_mask);
  std::ofstream f = openText((root / "label_2" / (name + ".txt")).string());
  for (const Label& l : labels) f << formatLabel(l) << "\n";
  if (!f) throw SceneError("cannot write labels of frame " + name);
}

void writeExtrinsics(const std::string& path, const std::vector<CameraPose>& poses) {
  std::ofstream f = openText(path);
  f << "# frame pitch_deg roll_deg height_m  (left camera against the road plane under it; "
       "pitch > 0 = looks down, roll > 0 = clockwise seen from behind, height along the road normal)\n";
  char buf[128];
  for (size_t i = 0; i < poses.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%06zu %.6f %.6f %.6f\n", i, poses[i].pitch_deg, poses[i].roll_deg,
                  poses[i].height_m);
    f << buf;
  }
  if (!f) throw SceneError("cannot write " + path);
}

}  // namespace nerv::synth
