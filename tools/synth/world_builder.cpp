#include "world_builder.hpp"

#include <cmath>

#include "object_shapes.hpp"

namespace nerv::synth {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Footprints taken at t = 0, so random objects do not overlap placed ones.
struct Occupancy {
  struct Disc { double x, z, r; };
  std::vector<Disc> discs;
  bool free(double x, double z, double r) const {
    for (const Disc& d : discs)
      if (std::hypot(d.x - x, d.z - z) < d.r + r) return false;
    return true;
  }
  void add(double x, double z, double r) { discs.push_back({x, z, r}); }
};

double footprintRadius(const Solid& s) { return 0.5 * std::hypot(s.width_m, s.length_m); }

void place(World& w, Solid s, double x, double z, double yaw_deg, double speed, double lift = 0) {
  s.base0 = Vec3(x, w.groundHeight(x, z) + lift, z);
  s.yaw = yaw_deg * kPi / 180.0;
  s.speed_mps = speed;
  w.solids.push_back(std::move(s));
}

}  // namespace

World buildWorld(const SceneSpec& spec) {
  validateScene(spec);
  World w;
  w.road = spec.road;
  w.traps = spec.traps;
  w.seed = static_cast<uint32_t>(spec.seed * 2654435761u + 1u);
  if (spec.traps.overexposed_sky) w.sun_dir = Vec3(-0.25, 0.2, 0.95).normalized();
  SceneRng rng(spec.seed);
  Occupancy occ;
  const RoadSpec& road = spec.road;
  const double x0 = spec.camera.lateral_m;
  const double xl = road.roadLeft(), xr = road.roadRight(), lw = road.lane_width_m;
  const double sw = road.sidewalk_width_m;
  const double z_end = 200.0 + spec.camera.speed_mps * kRouteSeconds;
  const double z_begin = -40.0;

  // 1. Obstacles given by the scene, relative to the camera at frame 0.
  for (const ObstacleSpec& o : spec.obstacles) {
    Solid s = makeObstacle(o.cls, o.colour, o.textureless, rng);
    const double x = x0 + o.lateral_m, z = o.distance_m;
    occ.add(x, z, footprintRadius(s));
    place(w, std::move(s), x, z, o.heading_deg, o.speed_mps, o.elevation_m);
  }

  // 2. Parked cars along the curb(s).
  const TrafficSpec& tr = spec.traffic;
  const bool park_right = tr.parked_spacing_m > 0 && tr.parked_side != "left";
  const bool park_left = tr.parked_spacing_m > 0 && tr.parked_side != "right" && road.lanes_left > 0;
  for (int side = 0; side < 2; ++side) {
    if ((side == 0 && !park_right) || (side == 1 && !park_left)) continue;
    double z = rng.uniform(4, 10);
    while (z < z_end) {
      Solid s = makeObstacle(rng.chance(0.12) ? ObstacleClass::Van : ObstacleClass::Car, -1, false, rng);
      const double len = s.length_m;
      const double x = side == 0 ? xr - 0.2 - s.width_m / 2 : xl + 0.2 + s.width_m / 2;
      const double zc = z + len / 2;
      if (!rng.chance(0.15) && occ.free(x, zc, footprintRadius(s) - 0.5)) {
        occ.add(x, zc, footprintRadius(s) - 0.5);
        place(w, std::move(s), x, zc, (side == 0 ? 0 : 180) + rng.uniform(-2, 2), 0);
      }
      z += len + tr.parked_spacing_m * rng.uniform(0.4, 1.6);
    }
  }

  // 3. Moving traffic. Vehicles in one lane share its speed so they never collide.
  auto vehicleClass = [&]() {
    if (!rng.chance(tr.truck_fraction)) return ObstacleClass::Car;
    return rng.chance(0.5) ? ObstacleClass::Van : ObstacleClass::Truck;
  };
  const int first_free_lane = 0;
  const int lanes_ahead = std::max(1, road.lanes_right - (park_right ? 1 : 0));
  const int ego_lane = std::clamp(static_cast<int>(std::floor(x0 / lw)), 0, road.lanes_right - 1);
  for (int i = 0, tries = 0; i < tr.cars_ahead && tries < 200; ++tries) {
    const int lane = first_free_lane + rng.index(lanes_ahead);
    const double speed = lane == ego_lane ? spec.camera.speed_mps
                                          : tr.traffic_speed_mps * (1.0 + 0.08 * lane);
    Solid s = makeObstacle(vehicleClass(), -1, false, rng);
    const double x = (lane + 0.5) * lw + rng.uniform(-0.3, 0.3);
    const double z = rng.uniform(12, 40) + s.length_m / 2;
    if (!occ.free(x, z, footprintRadius(s) + 2.0)) continue;
    occ.add(x, z, footprintRadius(s) + 2.0);
    place(w, std::move(s), x, z, 0, speed);
    ++i;
  }
  const double closing = spec.camera.speed_mps + tr.traffic_speed_mps;
  for (int i = 0, tries = 0; i < tr.oncoming && road.lanes_left > 0 && tries < 400; ++tries) {
    const int lane = rng.index(road.lanes_left);
    Solid s = makeObstacle(vehicleClass(), -1, false, rng);
    const double x = -(lane + 0.5) * lw + rng.uniform(-0.3, 0.3);
    const double z = 25 + rng.uniform(0, std::max(20.0, closing * 10.0));
    if (!occ.free(x, z, footprintRadius(s) + 3.0)) continue;
    occ.add(x, z, footprintRadius(s) + 3.0);
    place(w, std::move(s), x, z, 180, tr.traffic_speed_mps * (1.0 + 0.05 * lane));
    ++i;
  }
  for (int i = 0, tries = 0; i < tr.cyclists && tries < 200; ++tries) {
    Solid s = makeObstacle(ObstacleClass::Cyclist, -1, false, rng);
    const double x = park_right ? xr - 2.7 : xr - 0.8;
    const double z = rng.uniform(10, 40);
    if (!occ.free(x, z, 1.5)) continue;
    occ.add(x, z, 1.5);
    place(w, std::move(s), x, z, 0, rng.uniform(3.5, 5.5));
    ++i;
  }

  // 4. Pedestrians on the sidewalks, walking or standing.
  for (int i = 0, tries = 0; i < tr.pedestrians && sw > 1.2 && tries < 400; ++tries) {
    const bool right = road.lanes_left == 0 || rng.chance(0.6);
    const double off = rng.uniform(0.6, sw - 0.6);
    const double x = right ? xr + off : xl - off;
    const double z = rng.uniform(8, 45 + spec.camera.speed_mps * 4);
    if (!occ.free(x, z, 0.6)) continue;
    occ.add(x, z, 0.6);
    Solid s = makeObstacle(ObstacleClass::Pedestrian, -1, false, rng);
    const double heading = rng.chance(0.5) ? 0 : 180;
    const double speed = rng.chance(0.7) ? rng.uniform(1.0, 1.6) : 0.0;
    place(w, std::move(s), x, z, heading, speed);
    ++i;
  }

  // 5. Poles near the curb and trees behind them.
  const double edge_r = sw > 0 ? xr + 0.45 : xr + 1.2, edge_l = sw > 0 ? xl - 0.45 : xl - 1.2;
  if (spec.background.pole_spacing_m > 0) {
    for (double z = rng.uniform(8, 15); z < z_end; z += spec.background.pole_spacing_m * rng.uniform(0.6, 1.4)) {
      for (int side = 0; side < (road.lanes_left > 0 ? 2 : 1); ++side) {
        const double x = side == 0 ? edge_r : edge_l;
        if (rng.chance(0.4) || !occ.free(x, z, 0.8)) continue;
        occ.add(x, z, 0.8);
        place(w, makeObstacle(ObstacleClass::Pole, -1, false, rng), x, z, side == 0 ? 0 : 180, 0);
      }
    }
  }
  if (spec.background.tree_spacing_m > 0) {
    const double inset_r = sw > 1.5 ? xr + sw - 0.9 : xr + 4.0, inset_l = sw > 1.5 ? xl - sw + 0.9 : xl - 4.0;
    for (double z = rng.uniform(5, 12); z < z_end; z += spec.background.tree_spacing_m * rng.uniform(0.7, 1.3)) {
      for (int side = 0; side < 2; ++side) {
        const double x = (side == 0 ? inset_r : inset_l) + rng.uniform(-0.2, 0.2);
        if (rng.chance(0.25) || !occ.free(x, z, 1.0)) continue;
        occ.add(x, z, 1.0);
        place(w, makeTree(rng), x, z, 0, 0);
      }
    }
  }

  // 6. Fences and guard rails in segments (so each gets a sensible DontCare box).
  const std::string& fence = spec.background.fence;
  const bool repetitive = spec.traps.repetitive_fence;
  for (int side = 0; side < 2; ++side) {
    if (fence == "none" || (side == 0 && fence == "left") || (side == 1 && fence == "right")) continue;
    const double x = side == 0 ? xr + sw + 0.3 : xl - sw - 0.3;
    for (double z = z_begin; z < z_end;) {
      const double len = rng.uniform(8, 14);
      place(w, makeFence(len, repetitive, rng), x, z + len / 2, 0, 0);
      z += len + (rng.chance(0.3) ? rng.uniform(1, 3) : 0.0);
    }
  }
  if (spec.background.guard_rails) {
    std::vector<std::pair<double, double>> rails = {{xr + 0.7, 0}, {xl - 0.7, 180}};
    if (road.lanes_left > 0 && road.lanes_right > 0) rails.push_back({0.0, 0});
    for (const auto& [x, yaw] : rails)
      for (double z = z_begin; z < z_end; z += 16.0)
        place(w, makeGuardRail(16.0, repetitive, rng), x, z + 8.0, yaw, 0);
  }

  // 7. Buildings behind the sidewalk, with gaps that show the sky.
  if (spec.background.buildings) {
    for (int side = 0; side < 2; ++side) {
      const double front = side == 0 ? xr + sw + spec.background.building_setback_m
                                     : xl - sw - spec.background.building_setback_m;
      for (double z = z_begin + rng.uniform(0, 8); z < z_end;) {
        const double len = rng.uniform(8, 24), depth = rng.uniform(10, 16), h = rng.uniform(7, 24);
        const double x = side == 0 ? front + depth / 2 : front - depth / 2;
        place(w, makeBuilding(depth, len, h, rng), x, z + len / 2, 0, 0);
        z += len + (rng.chance(0.35) ? rng.uniform(2, 10) : 0.0);
      }
    }
  }

  // 8. Wet patches (puddles) on the carriageway.
  for (const WetPatch& p : spec.traps.wet_patches)
    w.wet.push_back({x0 + p.lateral_m, p.distance_m, p.width_m / 2, p.length_m / 2});
  for (int i = 0; i < spec.traps.random_wet_patches; ++i) {
    const double lane = rng.index(std::max(1, road.lanes_right));
    const double x = (lane + 0.5) * lw + rng.uniform(-0.8, 0.8);
    const double z = rng.uniform(8, 40 + spec.camera.speed_mps * 12);
    w.wet.push_back({x, z, rng.uniform(1.0, 1.8), rng.uniform(2.5, 7.0)});
  }

  w.setTime(0);
  return w;
}

}  // namespace nerv::synth
