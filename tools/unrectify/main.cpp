// nerv_unrectify: the raw views of a rectified sequence, for testing rectification on
// ingest with real frames (unrectify.hpp says how the rig is built).
//
//   nerv_unrectify --data DIR --out DIR [--frames N]
//
// Writes OUT/left, OUT/right (raw views, same size and channels), OUT/raw_calib.yaml (the
// rig, OpenCV stereo_calib format: a plain folder with it is played as raw frames by
// nerv_source), OUT/label_2 (the labels moved into the frame the receiver rectifies to),
// and extrinsics.txt when DIR has one (the rectified camera keeps the original pose).
// Prints the receiver's rectified camera. Exit 2 on bad arguments or data.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "dataset.hpp"
#include "unrectify.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

// KITTI label lines with their box (fields 5-8) moved into the receiver's rectified frame.
void moveLabels(const std::string& in, const std::string& out, const StereoCamera& cam, const RawRig& rig) {
  std::ifstream is(in);
  std::ofstream os(out);
  if (!is || !os) throw std::runtime_error("cannot read " + in + " or write " + out);
  for (std::string line; std::getline(is, line);) {
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string w; fields >> w;) f.push_back(w);
    if (f.size() < 8) {
      os << line << '\n';
      continue;
    }
    const cv::Point2d a = toReceiverRectified({std::stod(f[4]), std::stod(f[5])}, cam, rig);
    const cv::Point2d b = toReceiverRectified({std::stod(f[6]), std::stod(f[7])}, cam, rig);
    const double w = rig.rectified.width - 1, h = rig.rectified.height - 1;
    char box[128];
    std::snprintf(box, sizeof box, "%.2f %.2f %.2f %.2f", std::clamp(a.x, 0.0, w), std::clamp(a.y, 0.0, h),
                  std::clamp(b.x, 0.0, w), std::clamp(b.y, 0.0, h));
    std::string moved = f[0] + " " + f[1] + " " + f[2] + " " + f[3] + " " + box;
    for (size_t i = 8; i < f.size(); ++i) moved += " " + f[i];
    os << moved << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, out;
  int frames = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--data" && i + 1 < argc) data = argv[++i];
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: nerv_unrectify --data DIR --out DIR [--frames N]\n");
      return 2;
    }
  }
  if (data.empty() || out.empty()) {
    std::fprintf(stderr, "nerv_unrectify: --data and --out are required\n");
    return 2;
  }
  try {
    const Dataset ds = openDataset(data);
    if (ds.frames.front().raw) throw std::runtime_error(data + " holds raw views already");
    const StereoCamera& cam = ds.frames.front().camera;
    const RawRig rig = makeRawRig(cam);
    fs::create_directories(out + "/left");
    fs::create_directories(out + "/right");
    size_t n = ds.frames.size();
    if (frames >= 0) n = std::min(n, static_cast<size_t>(frames));
    bool labels = false;
    for (size_t i = 0; i < n; ++i) {
      const DatasetFrame& f = ds.frames[i];
      if (!(f.camera.fx == cam.fx && f.camera.cx == cam.cx && f.camera.cy == cam.cy))
        throw std::runtime_error(f.name + ": the calibration changes within the sequence");
      const cv::Mat left = cv::imread(f.left_path, cv::IMREAD_UNCHANGED);
      const cv::Mat right = cv::imread(f.right_path, cv::IMREAD_UNCHANGED);
      if (left.empty() || right.empty()) throw std::runtime_error("cannot read " + f.left_path + " or its right view");
      if (!cv::imwrite(out + "/left/" + f.name + ".png", unrectifyView(left, cam, rig, true)) ||
          !cv::imwrite(out + "/right/" + f.name + ".png", unrectifyView(right, cam, rig, false)))
        throw std::runtime_error("cannot write into " + out);
      if (!f.label_path.empty()) {
        fs::create_directories(out + "/label_2");
        moveLabels(f.label_path, out + "/label_2/" + f.name + ".txt", cam, rig);
        labels = true;
      }
    }
    writeOpenCvStereoCalibration(out + "/raw_calib.yaml", rig.raw);
    if (fs::exists(data + "/extrinsics.txt"))
      fs::copy_file(data + "/extrinsics.txt", out + "/extrinsics.txt", fs::copy_options::overwrite_existing);
    const StereoCamera& r = rig.rectified;
    std::printf("%zu raw frames in %s%s\n", n, out.c_str(), labels ? " with labels" : "");
    std::printf("rectified camera: fx %.6f fy %.6f cx %.6f cy %.6f baseline %.6f m (original fx %.6f cx %.6f cy %.6f)\n",
                r.fx, r.fy, r.cx, r.cy, r.baseline_m, cam.fx, cam.cx, cam.cy);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_unrectify: %s\n", e.what());
    return 2;
  }
  return 0;
}
