// KITTI label_2 text files: one object per line,
//   type truncated occluded alpha x1 y1 x2 y2 h w l x y z rotation_y [score]
#pragma once

#include <string>
#include <vector>

namespace nerv {

struct KittiLabel {
  std::string type;            // "Car", "Pedestrian", "DontCare", ...
  float truncated = 0;
  int occluded = 0;
  float alpha = 0;
  float x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // 2D box [px], right/bottom exclusive edges as in KITTI
  float h = -1, w = -1, l = -1;          // 3D size [m], -1 unknown
  float x = -1000, y = -1000, z = -1000; // 3D bottom centre, camera frame [m]; z may be a distance
  float rotation_y = 0;
};

// Throws std::runtime_error naming the file and line when a line is malformed.
std::vector<KittiLabel> readKittiLabels(const std::string& path);

}  // namespace nerv
