// Configuration of the stereo matcher: keys, ranges and cross-key checks.
#include "stereo_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace nerv::stereo {

namespace {
std::string key(const std::string& path, const char* name) { return "config key '" + path + "." + name + "'"; }
}  // namespace

void checkParams(const Params& p, const std::string& path) {
  static const char* kAlgorithms[] = {"nerv_sgm", "sgbm", "sgbm_full", "sgbm_wls", "bm"};
  bool known = false;
  for (const char* a : kAlgorithms) known = known || p.algorithm == a;
  if (!known)
    throw ConfigError(key(path, "algorithm") + " = '" + p.algorithm +
                      "' is not one of nerv_sgm, sgbm, sgbm_full, sgbm_wls, bm");
  if (p.num_disparities <= 0 || p.num_disparities % 16 != 0)
    throw ConfigError(key(path, "num_disparities") + " = " + std::to_string(p.num_disparities) +
                      " is not a positive multiple of 16");
  if (p.min_disparity < 0)
    throw ConfigError(key(path, "min_disparity") + " = " + std::to_string(p.min_disparity) +
                      " is negative");
  if (p.downscale != 1 && p.downscale != 2)
    throw ConfigError(key(path, "downscale") + " = " + std::to_string(p.downscale) + " is not 1 or 2");
  if (p.downscale == 2 && (p.num_disparities % 32 != 0 || p.min_disparity % 2 != 0))
    throw ConfigError(key(path, "downscale") +
                      " = 2 needs num_disparities a multiple of 32 and an even min_disparity");
  if (p.block_size % 2 == 0 || p.block_size < 1)
    throw ConfigError(key(path, "block_size") + " = " + std::to_string(p.block_size) + " is not odd");
  if (p.bm_block_size % 2 == 0 || p.bm_block_size < 5)
    throw ConfigError(key(path, "bm_block_size") + " = " + std::to_string(p.bm_block_size) +
                      " is not odd and >= 5");
  if (p.p2 <= p.p1) throw ConfigError(key(path, "p2") + " must be larger than p1");
  auto checkWindow = [&](const char* width_key, int w, int h) {
    if (w % 2 == 0 || h % 2 == 0 || w < 3 || h < 1 || (w * h - 1) / 2 > 32)
      throw ConfigError(key(path, width_key) + " x height = " + std::to_string(w) + "x" +
                        std::to_string(h) + " must be odd and hold at most 32 symmetric pairs");
  };
  checkWindow("census_width", p.census_width, p.census_height);
  checkWindow("road_census_width", p.road_census_width, p.road_census_height);
  if (!(p.road_census_from >= 0.0 && p.road_census_from <= 1.0))
    throw ConfigError(key(path, "road_census_from") + " must be within 0..1");
  const int max_cost = std::max((p.census_width * p.census_height - 1) / 2,
                                (p.road_census_width * p.road_census_height - 1) / 2);
  if (p.sgm_p1 < 0 || p.sgm_p2 <= p.sgm_p1 || max_cost + p.sgm_p2 > 255)
    throw ConfigError(key(path, "sgm_p2") + " = " + std::to_string(p.sgm_p2) +
                      " must exceed sgm_p1 and keep census bits (" + std::to_string(max_cost) +
                      ") + sgm_p2 <= 255 (8-bit path costs)");
  if (p.threads < 1) throw ConfigError(key(path, "threads") + " must be >= 1");

}

int roadCensusRow(const Params& p, int rows) {
  return p.road_census_from >= 1.0
             ? rows
             : std::clamp(static_cast<int>(std::lround(p.road_census_from * rows)), 0, rows);
}

std::string describeParams(const Params& p) {
  std::ostringstream s;
  s << "algorithm=" << p.algorithm << ";num_disparities=" << p.num_disparities << ";min_disparity=" << p.min_disparity
    << ";downscale=" << p.downscale << ";uniqueness_ratio=" << p.uniqueness_ratio
    << ";speckle=" << p.speckle_window_size << '/' << p.speckle_range << ";lr_max_diff=" << p.lr_max_diff
    << ";sgbm=" << p.block_size << '/' << p.p1 << '/' << p.p2 << ";bm_block_size=" << p.bm_block_size
    << ";wls=" << p.wls_lambda << '/' << p.wls_sigma << ";census=" << p.census_width << 'x' << p.census_height
    << ";road_census=" << p.road_census_width << 'x' << p.road_census_height << '@' << p.road_census_from
    << ";sgm=" << p.sgm_p1 << '/' << p.sgm_p2 << ";subpixel=" << p.subpixel << ";boundary_snap_px=" << p.boundary_snap_px
    << ";gated_mean=" << p.gated_mean_radius << '/' << p.gated_mean_range_px << '/' << p.gated_mean_range_rel
    << ";near_field=" << p.near_field << ";flat_census_invalid=" << p.flat_census_invalid;
  return s.str();
}

Params readParams(ConfigSection& c) {
  Params p;
  c.get("algorithm", p.algorithm, {"nerv_sgm", "sgbm", "sgbm_full", "sgbm_wls", "bm"});
  c.get("num_disparities", p.num_disparities, 16, 512);
  c.get("min_disparity", p.min_disparity, 0, 256);
  c.get("downscale", p.downscale, 1, 2);
  c.get("block_size", p.block_size, 1, 31);
  c.get("bm_block_size", p.bm_block_size, 5, 255);
  c.get("p1", p.p1, 0, 100000);
  c.get("p2", p.p2, 0, 100000);
  c.get("uniqueness_ratio", p.uniqueness_ratio, 0, 100);
  c.get("speckle_window_size", p.speckle_window_size, 0, 100000);
  c.get("speckle_range", p.speckle_range, 0, 64);
  c.get("lr_max_diff", p.lr_max_diff, -1, 64);
  c.get("wls_lambda", p.wls_lambda, 0.0, 1e6);
  c.get("wls_sigma", p.wls_sigma, 0.01, 100.0);
  c.get("census_width", p.census_width, 3, 15);
  c.get("census_height", p.census_height, 1, 15);
  c.get("road_census_width", p.road_census_width, 3, 31);
  c.get("road_census_height", p.road_census_height, 1, 15);
  c.get("road_census_from", p.road_census_from, 0.0, 1.0);
  c.get("sgm_p1", p.sgm_p1, 0, 254);
  c.get("sgm_p2", p.sgm_p2, 1, 255);
  c.get("subpixel", p.subpixel);
  c.get("threads", p.threads, 1, 64);
  c.get("boundary_snap_px", p.boundary_snap_px, -1, 32);
  c.get("gated_mean_radius", p.gated_mean_radius, 0, 7);
  c.get("gated_mean_range_px", p.gated_mean_range_px, 0.0, 16.0);
  c.get("gated_mean_range_rel", p.gated_mean_range_rel, 0.0, 1.0);
  c.get("near_field", p.near_field);
  c.get("flat_census_invalid", p.flat_census_invalid);
  checkParams(p, c.path());
  return p;
}

}  // namespace nerv::stereo
