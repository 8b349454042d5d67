// A group holds both stixel layers, so a strip can hold two stixels (an
// occluder and the object seen above it). Shape rules that read a group as a
// silhouette along u take one per strip: the nearest.
#pragma once

#include <vector>

#include "perception_types.hpp"

namespace nerv::stixel {

// group: stixels sorted by u. Returns one stixel per strip, the nearest, in u order.
std::vector<const Stixel*> nearestPerStrip(const std::vector<const Stixel*>& group);

}  // namespace nerv::stixel
