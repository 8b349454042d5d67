// nerv_misalign: a rectified sequence as a faulty rig delivers it, the calibration file
// unchanged: the right views moved by rows or turned (a rig that lost its calibration), moved
// sideways (a right camera turned about its vertical axis: every disparity off by the same), the
// views swapped (crossed cables or topics), the right view stopped (a stuck camera) or blank
// (a fogged lens). For
// measuring what each costs and testing that the stereo_matcher's checks notice (docs/stereo.md
// "Is the rig still rectified?", "Are the views the right way round?", "Has a camera stopped?",
// "Does one view show nothing?").
//
//   nerv_misalign --data DIR --out DIR [--rows PX] [--cols PX] [--roll-deg DEG] [--swap] [--freeze-right K] [--blank-right]
//                 [--frames N] [--from-frame K] [--interpolation linear|lanczos]
//
// Writes the plain layout: OUT/left (the left views as they are), OUT/right (turned by DEG
// about the principal point, positive = clockwise as seen from behind the camera, so points
// right of it move down; then moved by PX rows, positive = down, and by --cols PX columns to the
// left, so that every disparity grows by PX (negative: shrinks); bilinear, or with
// --interpolation lanczos OpenCV's 8 x 8 Lanczos kernel (the view keeps its fine texture, as a
// camera that moved does; bilinear blurs it at fractional shifts, docs/stereo.md "A sharper
// resampling"), the pixels moved in from outside repeat the border; --swap then writes each view as the other, as a rig with its
// cables or topics crossed delivers them; --freeze-right K repeats the right view of the K-th
// frame (from 0) in every later frame, as a stopped camera or driver delivers it; --blank-right
// replaces the right views by a fogged lens's: blurred to nothing, sigma 8 px; --from-frame K
// leaves the frames before the K-th (from 0) as they were, as a rig knocked mid-drive delivers
// them), OUT/calib.yaml
// (the first frame's rectified camera), OUT/label_2, OUT/disp_gt (the left view's true
// disparity, unchanged: it is the left view's) and OUT/extrinsics.txt when DIR has them.
// Exit 2 on bad arguments or data.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "dataset.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

int usage(const char* why) {
  std::fprintf(stderr, "nerv_misalign: %s\nusage: nerv_misalign --data DIR --out DIR [--rows PX] [--cols PX] [--roll-deg DEG] [--swap] [--freeze-right K] [--blank-right] [--frames N] [--from-frame K] [--interpolation linear|lanczos]\n", why);
  return 2;
}

void writeCalibration(const std::string& path, const StereoCamera& c) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "# rectified calibration as the rig was calibrated (nerv_misalign moved the right views)\n");
  std::fprintf(f, "width: %d\nheight: %d\nfx: %.6f\nfy: %.6f\ncx: %.6f\ncy: %.6f\nbaseline_m: %.6f\n", c.width,
               c.height, c.fx, c.fy, c.cx, c.cy, c.baseline_m);
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, out;
  double rows = 0, cols = 0, roll_deg = 0;
  int max_frames = -1, freeze_right = -1, from_frame = 0;
  bool swap = false, blank_right = false;
  int interpolation = cv::INTER_LINEAR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--swap" || a == "--blank-right") {
      (a == "--swap" ? swap : blank_right) = true;
      continue;
    }
    if (i + 1 >= argc) return usage(("missing value after " + a).c_str());
    const std::string v = argv[++i];
    char* end = nullptr;
    if (a == "--data") data = v;
    else if (a == "--out") out = v;
    else if (a == "--rows") rows = std::strtod(v.c_str(), &end);
    else if (a == "--cols") cols = std::strtod(v.c_str(), &end);
    else if (a == "--roll-deg") roll_deg = std::strtod(v.c_str(), &end);
    else if (a == "--frames") max_frames = static_cast<int>(std::strtol(v.c_str(), &end, 10));
    else if (a == "--from-frame") from_frame = static_cast<int>(std::strtol(v.c_str(), &end, 10));
    else if (a == "--freeze-right") freeze_right = static_cast<int>(std::strtol(v.c_str(), &end, 10));
    else if (a == "--interpolation" && (v == "linear" || v == "lanczos"))
      interpolation = v == "lanczos" ? cv::INTER_LANCZOS4 : cv::INTER_LINEAR;
    else if (a == "--interpolation") return usage(("--interpolation must be linear or lanczos, not " + v).c_str());
    else return usage(("unknown argument " + a).c_str());
    if (end && *end) return usage(("not a number: " + a + " " + v).c_str());
  }
  if (data.empty() || out.empty()) return usage("--data and --out are required");
  if (!std::isfinite(rows) || std::fabs(rows) > 100) return usage("--rows must be a number of rows within +-100");
  if (!std::isfinite(cols) || std::fabs(cols) > 100) return usage("--cols must be a number of columns within +-100");
  if (!std::isfinite(roll_deg) || std::fabs(roll_deg) > 10) return usage("--roll-deg must be within +-10");
  if (from_frame < 0) return usage("--from-frame must be a frame number from 0");
  try {
    const Dataset ds = openDataset(data);
    if (ds.frames.front().raw) throw DatasetError(data + " holds raw views: misalign a rectified sequence");
    fs::create_directories(out + "/left");
    fs::create_directories(out + "/right");
    const bool labels = !ds.frames.front().label_path.empty();
    if (labels) fs::create_directories(out + "/label_2");
    const bool truth = !ds.frames.front().disp_gt_path.empty();
    if (truth) fs::create_directories(out + "/disp_gt");
    int n = 0;
    for (const DatasetFrame& f : ds.frames) {
      if (max_frames >= 0 && n >= max_frames) break;
      const DatasetFrame& rf = freeze_right >= 0 && n > freeze_right
                                   ? ds.frames[std::min<size_t>(static_cast<size_t>(freeze_right), ds.frames.size() - 1)]
                                   : f;
      const cv::Mat left = cv::imread(f.left_path, cv::IMREAD_UNCHANGED);
      const cv::Mat right = cv::imread(rf.right_path, cv::IMREAD_UNCHANGED);
      if (left.empty() || right.empty()) throw DatasetError("cannot read " + f.left_path + " or " + f.right_path);
      const bool faulty = n >= from_frame;
      // Content at (x, y) moves to the point turned by roll_deg about (cx, cy), then rows lower:
      // x' = cx + c (x - cx) - s (y - cy), y' = cy + s (x - cx) + c (y - cy) + rows.
      const double th = faulty ? roll_deg * CV_PI / 180 : 0.0, c = std::cos(th), sn = std::sin(th);
      const double cx = f.camera.cx, cy = f.camera.cy;
      const cv::Mat shift = (cv::Mat_<double>(2, 3) << c, -sn, cx - c * cx + sn * cy - (faulty ? cols : 0.0),  //
                             sn, c, cy - sn * cx - c * cy + (faulty ? rows : 0.0));
      cv::Mat moved;
      cv::warpAffine(right, moved, shift, right.size(), interpolation, cv::BORDER_REPLICATE);
      if (blank_right && faulty) cv::GaussianBlur(moved, moved, cv::Size(0, 0), 8);
      const bool swapped = swap && faulty;
      if (!cv::imwrite(out + "/left/" + f.name + ".png", swapped ? moved : left) ||
          !cv::imwrite(out + "/right/" + f.name + ".png", swapped ? left : moved))
        throw DatasetError("cannot write the images of " + f.name + " under " + out);
      if (labels && fs::exists(f.label_path))
        fs::copy_file(f.label_path, out + "/label_2/" + f.name + ".txt", fs::copy_options::overwrite_existing);
      if (truth && fs::exists(f.disp_gt_path))
        fs::copy_file(f.disp_gt_path, out + "/disp_gt/" + f.name + ".png", fs::copy_options::overwrite_existing);
      ++n;
    }
    writeCalibration(out + "/calib.yaml", ds.frames.front().camera);
    if (fs::exists(data + "/extrinsics.txt"))
      fs::copy_file(data + "/extrinsics.txt", out + "/extrinsics.txt", fs::copy_options::overwrite_existing);
    std::printf("%d frames, right views%s turned by %+.3f deg, moved by %+.2f rows and %+.2f columns to the left%s%s%s: %s\n", n,
                from_frame > 0 ? cv::format(" from frame %d on", from_frame).c_str() : "", roll_deg, rows, cols,
                freeze_right >= 0 ? cv::format(", frozen from frame %d on", freeze_right).c_str() : "",
                blank_right ? ", blurred to nothing" : "",
                swap ? ", then left and right swapped" : "", out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_misalign: %s\n", e.what());
    return 2;
  }
  return 0;
}
