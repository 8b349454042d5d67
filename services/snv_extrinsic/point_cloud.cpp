#include "point_cloud.hpp"

#include <limits>

namespace nerv::snv {

PointCloud computePointCloud(const cv::Mat& disparity, const StereoCamera& cam) {
  CV_Assert(disparity.type() == CV_32F);
  PointCloud pc;
  pc.x.create(disparity.size(), CV_32F);
  pc.y.create(disparity.size(), CV_32F);
  pc.z.create(disparity.size(), CV_32F);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float fb = static_cast<float>(cam.fx * cam.baseline_m);
  const float b = static_cast<float>(cam.baseline_m);
  const float yscale = static_cast<float>(cam.fx / cam.fy);
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    float* px = pc.x.ptr<float>(v);
    float* py = pc.y.ptr<float>(v);
    float* pz = pc.z.ptr<float>(v);
    const float dv = static_cast<float>(v - cam.cy) * yscale;
    for (int u = 0; u < disparity.cols; ++u) {
      if (!validDisparity(d[u])) {
        px[u] = py[u] = pz[u] = nan;
        continue;
      }
      const float k = b / d[u];  // toPoint(): X = (u-cx) B/d, Y = (v-cy) B/d fx/fy, Z = fx B/d
      px[u] = static_cast<float>(u - cam.cx) * k;
      py[u] = dv * k;
      pz[u] = fb / d[u];
    }
  }
  return pc;
}

}  // namespace nerv::snv
