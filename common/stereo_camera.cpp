#include "stereo_camera.hpp"

#include <sstream>

namespace nerv {

std::string StereoCamera::problem() const {
  std::ostringstream why;
  auto finite = [](double v) { return std::isfinite(v); };
  if (width <= 0 || height <= 0)
    why << "image size " << width << "x" << height << " is not positive";
  // Beyond finite: numbers no real rig has (a corrupt message) overflow the 3D
  // relations, e.g. (u - cx) * B / d cast to float, into inf.
  else if (!finite(fx) || !finite(fy) || !(fx >= 1 && fx <= 1e6) || !(fy >= 1 && fy <= 1e6))
    why << "focal length fx=" << fx << " fy=" << fy << " is not a finite number in 1..1e6 px";
  else if (!finite(cx) || !finite(cy) || !(cx >= -width && cx <= 2.0 * width) ||
           !(cy >= -height && cy <= 2.0 * height))
    why << "principal point cx=" << cx << " cy=" << cy << " is not finite or far outside the image";
  else if (!finite(baseline_m) || !(baseline_m > 0 && baseline_m <= 100))
    why << "baseline " << baseline_m << " m is not a finite number in (0, 100] m";
  return why.str();
}

}  // namespace nerv
