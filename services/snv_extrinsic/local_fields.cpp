#include "local_fields.hpp"

#include "local_normals.hpp"

namespace nerv::snv {

void LocalFields::prepare(const cv::Mat& disparity, const StereoCamera& cam, const IntegralNormalParams& params,
                          cv::Range ground_rows, const std::vector<cv::Rect>& rois) {
  // The ground rows, all columns, with the margin their windows reach (empty: no ground).
  const cv::Rect ground_rect =
      ground_rows.empty() ? cv::Rect() : cv::Rect(0, ground_rows.start, disparity.cols, ground_rows.size());
  ground_.prepare(disparity, cam, params, regionFor(ground_rect, disparity.size(), params.max_radius_px));
  which_.assign(rois.size(), -1);
  used_ = 0;
  for (size_t i = 0; i < rois.size(); ++i) {
    const cv::Rect& r = rois[i];
    const bool in_band = !ground_rows.empty() && r.y >= ground_rows.start && r.y + r.height <= ground_rows.end;
    if (in_band || r.empty()) continue;
    if (own_.size() <= static_cast<size_t>(used_)) own_.emplace_back();
    own_[used_].prepare(disparity, cam, params, regionFor(r, disparity.size(), params.max_radius_px));
    which_[i] = used_++;
  }
}

}  // namespace nerv::snv
