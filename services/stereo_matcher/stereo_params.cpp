#include "stereo_matcher.hpp"

namespace nerv::stereo {

Params readParams(ConfigSection& c) {
  Params p;
  c.get("algorithm", p.algorithm, {"sgbm", "sgbm_full", "bm"});
  c.get("num_disparities", p.num_disparities, 16, 512);
  if (p.num_disparities % 16 != 0)
    throw ConfigError("config key '" + c.path() + ".num_disparities' = " +
                      std::to_string(p.num_disparities) + " is not a multiple of 16");
  c.get("min_disparity", p.min_disparity, 0, 256);
  c.get("block_size", p.block_size, 1, 31);
  if (p.block_size % 2 == 0)
    throw ConfigError("config key '" + c.path() + ".block_size' = " +
                      std::to_string(p.block_size) + " is not odd");
  c.get("p1", p.p1, 0, 100000);
  c.get("p2", p.p2, 0, 100000);
  if (p.p2 <= p.p1)
    throw ConfigError("config key '" + c.path() + ".p2' must be larger than p1");
  c.get("uniqueness_ratio", p.uniqueness_ratio, 0, 100);
  c.get("speckle_window_size", p.speckle_window_size, 0, 100000);
  c.get("speckle_range", p.speckle_range, 0, 64);
  c.get("lr_max_diff", p.lr_max_diff, -1, 64);
  return p;
}

}  // namespace nerv::stereo
