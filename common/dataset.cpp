#include "dataset.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>

#include "calibration_io.hpp"
#include "raw_calibration_io.hpp"

namespace fs = std::filesystem;

namespace nerv {
namespace {

bool isImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pgm";
}

std::string optionalFile(const fs::path& dir, const std::string& stem, const char* ext) {
  const fs::path p = dir / (stem + ext);
  return fs::exists(p) ? p.string() : std::string();
}

void imageSize(const std::string& path, int& width, int& height) {
  const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (img.empty()) throw DatasetError("image " + path + " cannot be read");
  width = img.cols;
  height = img.rows;
}

// Frames from two image folders with matching names.
std::vector<DatasetFrame> pairImages(const fs::path& left_dir, const fs::path& right_dir) {
  std::vector<DatasetFrame> frames;
  for (const auto& entry : fs::directory_iterator(left_dir)) {
    if (!entry.is_regular_file() || !isImage(entry.path())) continue;
    DatasetFrame f;
    f.name = entry.path().stem().string();
    f.left_path = entry.path().string();
    const fs::path right = right_dir / entry.path().filename();
    if (!fs::exists(right))
      throw DatasetError("right image " + right.string() + " is missing for " + f.left_path);
    f.right_path = right.string();
    frames.push_back(f);
  }
  std::sort(frames.begin(), frames.end(),
            [](const DatasetFrame& a, const DatasetFrame& b) { return a.name < b.name; });
  if (frames.empty()) throw DatasetError("no images in " + left_dir.string());
  return frames;
}

// The camera a raw rig rectifies to (what the receiver computes), or a DatasetError.
StereoCamera rectifiedCamera(const RawStereoCalibration& rig, const fs::path& calib) {
  try {
    return computeRectification(rig).camera;
  } catch (const std::invalid_argument& e) {
    throw DatasetError("calibration " + calib.string() + " cannot rectify: " + e.what());
  }
}

}  // namespace

Dataset openDataset(const std::string& dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root)) throw DatasetError("data folder " + dir + " does not exist");
  Dataset ds;
  ds.root = dir;
  try {
    if (fs::is_directory(root / "left") && fs::is_directory(root / "right")) {
      ds.layout = "plain";
      const fs::path calib = root / "calib.yaml", raw_calib = root / "raw_calib.yaml";
      const bool raw = fs::exists(raw_calib);
      if (raw && fs::exists(calib))
        throw DatasetError("data folder " + dir + " has both calib.yaml (rectified views) and " +
                           "raw_calib.yaml (raw views): keep the one that describes its images");
      if (!raw && !fs::exists(calib))
        throw DatasetError("calibration " + calib.string() + " is missing (or raw_calib.yaml for raw views)");
      ds.frames = pairImages(root / "left", root / "right");
      std::optional<RawStereoCalibration> rig;
      StereoCamera cam;
      if (raw) {
        int width = 0, height = 0;
        imageSize(ds.frames.front().left_path, width, height);
        rig = loadOpenCvStereoCalibration(raw_calib.string(), width, height);
        if (rig->width != width || rig->height != height)
          throw DatasetError("calibration " + raw_calib.string() + " is for " + std::to_string(rig->width) +
                             "x" + std::to_string(rig->height) + " images, " + ds.frames.front().left_path +
                             " is " + std::to_string(width) + "x" + std::to_string(height));
        cam = rectifiedCamera(*rig, raw_calib);
      } else {
        cam = loadPlainCalibration(calib.string());
      }
      for (auto& f : ds.frames) {
        f.camera = cam;
        f.raw = rig;
        f.label_path = optionalFile(root / "label_2", f.name, ".txt");
        f.disp_gt_path = optionalFile(root / "disp_gt", f.name, ".png");
      }
    } else if (fs::is_directory(root / "image_02" / "data")) {
      ds.layout = "kitti_raw";
      fs::path calib = root / "calib_cam_to_cam.txt";
      if (!fs::exists(calib)) calib = root.parent_path() / "calib_cam_to_cam.txt";
      if (!fs::exists(calib))
        throw DatasetError("calibration calib_cam_to_cam.txt is missing in " + dir +
                           " and its parent");
      StereoCamera cam = loadKittiRawCalibration(calib.string());
      ds.frames = pairImages(root / "image_02" / "data", root / "image_03" / "data");
      // KITTI's unrectified downloads ("extract") have the same folders, with the
      // cameras' own image size S_02 instead of S_rect_02: raw views, rectified on ingest.
      int width = 0, height = 0;
      imageSize(ds.frames.front().left_path, width, height);
      std::optional<RawStereoCalibration> rig;
      if (width != cam.width || height != cam.height) {
        rig = loadKittiRawStereoCalibration(calib.string(), 2, 3);
        if (rig->width != width || rig->height != height)
          throw DatasetError(ds.frames.front().left_path + " is " + std::to_string(width) + "x" +
                             std::to_string(height) + ": neither the rectified size " +
                             std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                             " (S_rect_02) nor the raw size " + std::to_string(rig->width) + "x" +
                             std::to_string(rig->height) + " (S_02) of " + calib.string());
        cam = rectifiedCamera(*rig, calib);
      }
      for (auto& f : ds.frames) {
        f.camera = cam;
        f.raw = rig;
      }
    } else if (fs::is_directory(root / "image_2") && fs::is_directory(root / "image_3")) {
      ds.layout = "kitti_object";
      ds.frames = pairImages(root / "image_2", root / "image_3");
      int width = 0, height = 0;
      imageSize(ds.frames.front().left_path, width, height);
      for (auto& f : ds.frames) {
        // KITTI stereo names frames NNNNNN_10; its calibration is NNNNNN.txt.
        const std::string id = f.name.substr(0, f.name.find('_'));
        const fs::path calib = root / "calib" / (id + ".txt");
        if (!fs::exists(calib)) throw DatasetError("calibration " + calib.string() + " is missing");
        f.camera = loadKittiObjectCalibration(calib.string(), width, height);
        f.label_path = optionalFile(root / "label_2", f.name, ".txt");
        f.disp_gt_path = optionalFile(root / "disp_occ_0", f.name, ".png");
      }
    } else {
      throw DatasetError("data folder " + dir +
                         " has no known layout (left/+right/+calib.yaml, image_02/data, or "
                         "image_2/+image_3/+calib/)");
    }
  } catch (const CalibrationError& e) {
    throw DatasetError(e.what());
  } catch (const fs::filesystem_error& e) {
    throw DatasetError(std::string("data folder ") + dir + ": " + e.what());
  }
  return ds;
}

}  // namespace nerv
