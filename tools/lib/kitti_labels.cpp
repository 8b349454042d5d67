#include "kitti_labels.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace nerv {

std::vector<KittiLabel> readKittiLabels(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("label file " + path + " cannot be read");
  std::vector<KittiLabel> labels;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream s(line);
    KittiLabel l;
    if (!(s >> l.type >> l.truncated >> l.occluded >> l.alpha >> l.x1 >> l.y1 >> l.x2 >> l.y2 >>
          l.h >> l.w >> l.l >> l.x >> l.y >> l.z >> l.rotation_y))
      throw std::runtime_error("label file " + path + " line " + std::to_string(number) +
                               " is not a KITTI label (15 fields)");
    labels.push_back(l);
  }
  return labels;
}

}  // namespace nerv
