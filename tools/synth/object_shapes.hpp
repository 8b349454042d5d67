// Obstacles and background structure as solids built from primitives, in
// their local frame (x right, y up from the base, z along the heading).
#pragma once

#include <cstdint>

#include "world.hpp"

namespace nerv::synth {

// Deterministic random numbers (splitmix64), identical on every platform.
class SceneRng {
 public:
  explicit SceneRng(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo = 0, double hi = 1) {
    return lo + (hi - lo) * static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0);
  }
  int index(int n) { return static_cast<int>(uniform(0, n)) % n; }
  bool chance(double p) { return uniform() < p; }

 private:
  uint64_t state_;
};

constexpr int kVehiclePaletteSize = 10;
cv::Vec3f vehicleColour(int index);

// `colour` indexes the vehicle palette (-1: pick with rng); `textureless`
// paints the large sides plain white and marks them as a trap.
Solid makeObstacle(ObstacleClass cls, int colour, bool textureless, SceneRng& rng);
Solid makeTree(SceneRng& rng);
Solid makeBuilding(double depth_m, double length_m, double height_m, SceneRng& rng);
Solid makeFence(double length_m, bool repetitive, SceneRng& rng);
Solid makeGuardRail(double length_m, bool repetitive, SceneRng& rng);

}  // namespace nerv::synth
