#include "calibration_io.hpp"

#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "config.hpp"

namespace nerv {
namespace {

// "key: v1 v2 ..." lines; the key ends at the first ':'.
std::map<std::string, std::vector<double>> readKeyedNumbers(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CalibrationError("calibration file " + path + " cannot be read");
  std::map<std::string, std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::istringstream values(line.substr(colon + 1));
    std::vector<double> numbers;
    double v;
    while (values >> v) numbers.push_back(v);
    rows[line.substr(0, colon)] = numbers;
  }
  return rows;
}

const std::vector<double>& need(const std::map<std::string, std::vector<double>>& rows,
                                const std::string& key, size_t count, const std::string& path) {
  auto it = rows.find(key);
  if (it == rows.end()) throw CalibrationError("calibration file " + path + " has no " + key);
  if (it->second.size() != count)
    throw CalibrationError("calibration file " + path + ": " + key + " has " +
                           std::to_string(it->second.size()) + " numbers, expected " +
                           std::to_string(count));
  return it->second;
}

StereoCamera fromProjections(const std::vector<double>& pl, const std::vector<double>& pr,
                             int width, int height, const std::string& path) {
  StereoCamera cam;
  cam.width = width;
  cam.height = height;
  cam.fx = pl[0];
  cam.cx = pl[2];
  cam.fy = pl[5];
  cam.cy = pl[6];
  cam.baseline_m = (pl[3] - pr[3]) / cam.fx;
  if (const std::string p = cam.problem(); !p.empty())
    throw CalibrationError("calibration file " + path + ": " + p);
  return cam;
}

std::string twoDigits(int i) { return (i < 10 ? "0" : "") + std::to_string(i); }

}  // namespace

StereoCamera loadPlainCalibration(const std::string& path) {
  StereoCamera cam;
  try {
    ConfigSection c(loadConfigFile(path), "");
    for (const char* key : {"width", "height", "fx", "fy", "cx", "cy", "baseline_m"})
      if (!c.has(key)) throw CalibrationError("calibration file " + path + " has no " + key);
    c.get("width", cam.width, 1, 1 << 16);
    c.get("height", cam.height, 1, 1 << 16);
    c.get("fx", cam.fx);
    c.get("fy", cam.fy);
    c.get("cx", cam.cx);
    c.get("cy", cam.cy);
    c.get("baseline_m", cam.baseline_m);
    double camera_height_m = 0;
    c.get("camera_height_m", camera_height_m);
    c.finish();
  } catch (const ConfigError& e) {
    throw CalibrationError(std::string("calibration: ") + e.what());
  }
  if (const std::string p = cam.problem(); !p.empty())
    throw CalibrationError("calibration file " + path + ": " + p);
  return cam;
}

StereoCamera loadKittiRawCalibration(const std::string& path, int left_index, int right_index) {
  const auto rows = readKeyedNumbers(path);
  const std::string l = twoDigits(left_index), r = twoDigits(right_index);
  const auto& pl = need(rows, "P_rect_" + l, 12, path);
  const auto& pr = need(rows, "P_rect_" + r, 12, path);
  const auto& size = need(rows, "S_rect_" + l, 2, path);
  return fromProjections(pl, pr, static_cast<int>(size[0]), static_cast<int>(size[1]), path);
}

StereoCamera loadKittiObjectCalibration(const std::string& path, int width, int height) {
  const auto rows = readKeyedNumbers(path);
  return fromProjections(need(rows, "P2", 12, path), need(rows, "P3", 12, path), width, height,
                         path);
}

}  // namespace nerv
