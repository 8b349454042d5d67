// A textured gray view for the stereo_matcher's rig checks: uniform noise blurred at several
// scales and summed, as a scene has texture at several scales (fine grain alone vanishes in
// the coarse pyramid levels that a large shift needs).
#pragma once

#include <opencv2/imgproc.hpp>

namespace nerv::stereo {

inline cv::Mat multiScaleTexture(int width, int height, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat sum = cv::Mat::zeros(height, width, CV_32FC1);
  for (const double sigma : {1.5, 4.0, 10.0}) {
    cv::Mat noise(height, width, CV_32FC1), smooth;
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::GaussianBlur(noise, smooth, cv::Size(0, 0), sigma);
    cv::normalize(smooth, smooth, 0, 1, cv::NORM_MINMAX);
    sum += smooth;
  }
  cv::Mat out;
  cv::normalize(sum, sum, 0, 255, cv::NORM_MINMAX);
  sum.convertTo(out, CV_8UC1);
  return out;
}

}  // namespace nerv::stereo
