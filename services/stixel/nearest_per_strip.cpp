#include "nearest_per_strip.hpp"

namespace nerv::stixel {

std::vector<const Stixel*> nearestPerStrip(const std::vector<const Stixel*>& group) {
  std::vector<const Stixel*> s;
  for (const Stixel* x : group)
    if (!s.empty() && s.back()->u == x->u) {
      if (x->depth_m < s.back()->depth_m) s.back() = x;
    } else {
      s.push_back(x);
    }
  return s;
}

}  // namespace nerv::stixel
