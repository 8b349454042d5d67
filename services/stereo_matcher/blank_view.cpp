#include "blank_view.hpp"

#include "textured_points.hpp"

namespace nerv::stereo {

ViewTexture compareViewTexture(const cv::Mat& left, const cv::Mat& right, const BlankViewParams& p) {
  ViewTexture out;
  const TexturedPointsParams tp{p.grid_px, p.window_px, p.max_points, p.min_score};
  out.left = static_cast<int>(texturedPoints(left, tp).size());
  out.right = static_cast<int>(texturedPoints(right, tp).size());
  if (left.empty() || right.empty() || left.size() != right.size()) return out;
  if (out.left >= p.min_textured && out.right < p.max_share * out.left) out.blank = "right";
  else if (out.right >= p.min_textured && out.left < p.max_share * out.right) out.blank = "left";
  return out;
}

}  // namespace nerv::stereo
