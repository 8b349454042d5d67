#include "raw_calibration_io.hpp"

#include <opencv2/core/persistence.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace nerv {
namespace {

template <std::size_t N>
void copyMat(const cv::Mat& m, std::array<double, N>& out, const std::string& what,
             const std::string& path, bool allow_shorter = false) {
  cv::Mat d;
  if (!m.empty()) m.convertTo(d, CV_64F);
  const std::size_t n = d.total();
  if (n != N && !(allow_shorter && n >= 4 && n < N))
    throw CalibrationError(path + ": " + what + " needs " + std::to_string(N) + " numbers, has " +
                           std::to_string(n));
  out.fill(0.0);
  const cv::Mat flat = d.reshape(1, 1);
  for (std::size_t i = 0; i < n; ++i) out[i] = flat.at<double>(0, static_cast<int>(i));
}

}  // namespace

RawStereoCalibration loadOpenCvStereoCalibration(const std::string& path, int width, int height) {
  if (!std::filesystem::exists(path)) throw CalibrationError(path + ": cannot open");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw CalibrationError(path + ": cannot parse (" + e.err + ")");
  }
  if (!fs.isOpened()) throw CalibrationError(path + ": cannot open");
  RawStereoCalibration c;
  auto mat = [&](const char* key) {
    cv::Mat m;
    if (fs[key].empty()) throw CalibrationError(path + ": key " + key + " is missing");
    fs[key] >> m;
    return m;
  };
  copyMat(mat("M1"), c.left_K, "M1", path);
  copyMat(mat("D1"), c.left_D, "D1", path, true);   // 4 or 5 coefficients
  copyMat(mat("M2"), c.right_K, "M2", path);
  copyMat(mat("D2"), c.right_D, "D2", path, true);
  copyMat(mat("R"), c.R, "R", path);
  copyMat(mat("T"), c.T, "T", path);
  if (!fs["image_width"].empty() && !fs["image_height"].empty()) {
    c.width = static_cast<int>(fs["image_width"]);
    c.height = static_cast<int>(fs["image_height"]);
  } else if (!fs["width"].empty() && !fs["height"].empty()) {
    c.width = static_cast<int>(fs["width"]);
    c.height = static_cast<int>(fs["height"]);
  } else if (!fs["imageSize"].empty()) {
    std::vector<int> s;
    fs["imageSize"] >> s;
    if (s.size() == 2) {
      c.width = s[0];
      c.height = s[1];
    }
  } else {
    c.width = width;
    c.height = height;
  }
  if (const std::string why = c.problem(); !why.empty()) throw CalibrationError(path + ": " + why);
  return c;
}

RawStereoCalibration loadKittiRawStereoCalibration(const std::string& path, int left_index,
                                                   int right_index) {
  std::ifstream in(path);
  if (!in) throw CalibrationError(path + ": cannot open");
  std::map<std::string, std::vector<double>> values;
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::istringstream numbers(line.substr(colon + 1));
    std::vector<double> v;
    double x;
    while (numbers >> x) v.push_back(x);
    values[line.substr(0, colon)] = v;
  }
  auto get = [&](const std::string& key, std::size_t n) {
    const auto it = values.find(key);
    if (it == values.end()) throw CalibrationError(path + ": " + key + " is missing");
    if (it->second.size() != n)
      throw CalibrationError(path + ": " + key + " needs " + std::to_string(n) + " numbers");
    return it->second;
  };
  auto id = [](int i) { return std::string(i < 10 ? "0" : "") + std::to_string(i); };
  const std::string l = id(left_index), r = id(right_index);
  RawStereoCalibration c;
  const auto Kl = get("K_" + l, 9), Kr = get("K_" + r, 9), Dl = get("D_" + l, 5),
             Dr = get("D_" + r, 5), Rl = get("R_" + l, 9), Rr = get("R_" + r, 9),
             Tl = get("T_" + l, 3), Tr = get("T_" + r, 3), S = get("S_" + l, 2);
  std::copy(Kl.begin(), Kl.end(), c.left_K.begin());
  std::copy(Kr.begin(), Kr.end(), c.right_K.begin());
  std::copy(Dl.begin(), Dl.end(), c.left_D.begin());
  std::copy(Dr.begin(), Dr.end(), c.right_D.begin());
  const cv::Matx33d rl(Rl.data()), rr(Rr.data());
  const cv::Vec3d tl(Tl[0], Tl[1], Tl[2]), tr(Tr[0], Tr[1], Tr[2]);
  const cv::Matx33d R = rr * rl.t();
  const cv::Vec3d T = tr - R * tl;
  for (int i = 0; i < 9; ++i) c.R[i] = R.val[i];
  for (int i = 0; i < 3; ++i) c.T[i] = T[i];
  c.width = static_cast<int>(S[0] + 0.5);
  c.height = static_cast<int>(S[1] + 0.5);
  if (const std::string why = c.problem(); !why.empty()) throw CalibrationError(path + ": " + why);
  return c;
}

}  // namespace nerv
