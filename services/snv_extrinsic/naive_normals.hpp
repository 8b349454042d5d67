// Slow, obviously correct references for the integral-image normals (tests and
// the benchmark baseline), in the spirit of libSGM's reference.h.
#pragma once

#include <opencv2/core.hpp>

#include "integral_normals.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

// Per pixel cross product of raw 3D neighbour differences at a fixed radius:
// N = (P(u,v+r) - P(u,v-r)) x (P(u+r,v) - P(u-r,v)); no smoothing, no integral images.
NormalMap computeNaiveNormalMap(const cv::Mat& disparity, const StereoCamera& cam, int radius_px,
                                int interval_px);

// The integral-image normal at (u, v) with radius r, but every box mean summed
// pixel by pixel (no integral image). Returns false where any window holds an
// invalid pixel or a smoothed depth is not positive.
bool bruteForceSmoothedNormal(const cv::Mat& disparity, const StereoCamera& cam,
                              const IntegralNormalParams& params, int u, int v, int r,
                              cv::Vec3f& n);

// The full-frame map read pixel by pixel through the scalar reference path
// (IntegralNormalField::adaptiveRadius + normalAt, one division per box mean):
// what computeNormalMap computed before its row path was vectorised.
NormalMap computeNormalMapReference(const cv::Mat& disparity, const StereoCamera& cam,
                                    const IntegralNormalParams& params, int interval_px);

}  // namespace nerv::snv
