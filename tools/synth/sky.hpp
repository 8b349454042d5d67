// Sky colour by view direction: horizon-to-zenith gradient, clouds on a layer
// 1 km up, and the sun's glare (saturating when the scene asks for an
// overexposed sky).
#pragma once

#include <opencv2/core.hpp>

#include "world.hpp"

namespace nerv::synth {

// `dir` need not be unit length. `footprint_rad` is the angular sample size.
cv::Vec3f skyColour(const World& w, const Vec3& dir, float footprint_rad);

}  // namespace nerv::synth
