#include "stereo_camera.hpp"

#include <sstream>

namespace nerv {

std::string StereoCamera::problem() const {
  std::ostringstream why;
  auto finite = [](double v) { return std::isfinite(v); };
  if (width <= 0 || height <= 0)
    why << "image size " << width << "x" << height << " is not positive";
  else if (!finite(fx) || !finite(fy) || fx <= 0 || fy <= 0)
    why << "focal length fx=" << fx << " fy=" << fy << " is not a positive finite number";
  else if (!finite(cx) || !finite(cy))
    why << "principal point cx=" << cx << " cy=" << cy << " is not finite";
  else if (!finite(baseline_m) || baseline_m <= 0)
    why << "baseline " << baseline_m << " m is not a positive finite number";
  return why.str();
}

}  // namespace nerv
