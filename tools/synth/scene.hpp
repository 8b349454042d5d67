// Description of a synthetic road scene: camera rig and its motion, road layout,
// obstacles, background population and disparity traps. Pure data; loaded from
// YAML by scene_yaml.hpp and turned into renderable solids by world_builder.hpp.
//
// Road coordinates (world): x right across the road (x = 0 on the centre line
// between the two directions), y up, z forward along the road; metres. The
// camera starts at z = 0.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "stereo_camera.hpp"

namespace nerv::synth {

// Every problem with a scene (bad key, impossible placement, bad calibration)
// is one of these, with a one-line message naming the problem.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CameraRig {
  // KITTI-like defaults (colour cameras 2/3 of the 2011-09-26 recordings).
  StereoCamera intrinsics{1242, 375, 721.5, 721.5, 609.5, 172.8, 0.54};
  double height_m = 1.65;           // over the road, along the road normal
  double pitch_deg = 0;             // positive = camera looks down
  double roll_deg = 0;              // positive = clockwise as seen from behind
  double lateral_m = 1.75;          // road x of the left camera at the start
  double speed_mps = 8;             // forward speed along the road
  double fps = 10;                  // frame rate of the sequence
  double pitch_amplitude_deg = 0;   // sinusoidal pitch swing (braking / pitching)
  double pitch_period_s = 1.6;
  double roll_amplitude_deg = 0;    // sinusoidal roll swing
  double roll_period_s = 3.0;
  double height_amplitude_m = 0;    // heave, in phase with the pitch swing
  double bump_interval_s = 0;       // 0 = no bumps; else a damped pitch kick this often
  double bump_pitch_deg = 0;        // peak pitch of a bump
  double noise_sigma = 1.5;         // per-camera Gaussian sensor noise [DN]
  double right_gain = 1.03;         // right camera gain relative to the left
  double right_offset = -2.0;       // right camera offset [DN]
};

struct RoadSpec {
  int lanes_right = 2;              // lanes in the camera's direction (x > 0)
  int lanes_left = 1;               // oncoming lanes (x < 0)
  double lane_width_m = 3.5;
  double sidewalk_width_m = 3.0;    // 0 = no sidewalk (shoulder of grass)
  double curb_height_m = 0.12;      // sidewalk and terrain stand this much above the road
  double slope_start_m = 60;        // road z where a constant grade begins
  double grade_percent = 0;         // rise per 100 m beyond slope_start_m (negative = down)
  bool markings = true;             // lane markings
  double roadLeft() const { return -lanes_left * lane_width_m; }
  double roadRight() const { return lanes_right * lane_width_m; }
};

enum class ObstacleClass { Car, Van, Truck, Pedestrian, Cyclist, Pole };
const char* className(ObstacleClass c);

struct ObstacleSpec {
  ObstacleClass cls = ObstacleClass::Car;
  double lateral_m = 0;     // relative to the camera at frame 0, right positive
  double distance_m = 20;   // forward distance of the object's centre from the camera at frame 0
  double heading_deg = 0;   // 0 = same direction as the camera, 180 = oncoming, 90 = crossing to the right
  double speed_mps = 0;     // along the heading
  double elevation_m = 0;   // base above the ground under it (>= 0)
  bool textureless = false; // plain white sides (a disparity trap)
  int colour = -1;          // palette index, -1 = chosen from the seed
};

struct TrafficSpec {        // random population, deterministic from the seed
  double parked_spacing_m = 0;      // 0 = no parked cars; mean gap between parked cars
  std::string parked_side = "right";// right | left | both
  int cars_ahead = 0;               // vehicles 12..40 m ahead in the camera's lanes
  int oncoming = 0;                 // vehicles approaching in the oncoming lanes
  int pedestrians = 0;              // on the sidewalks, within 8..45 m
  int cyclists = 0;                 // near the right road edge
  double traffic_speed_mps = 8;     // typical speed of moving vehicles
  double truck_fraction = 0.15;     // share of vans/trucks among moving vehicles
};

struct BackgroundSpec {
  bool buildings = true;
  double building_setback_m = 2.0;  // gap between sidewalk/shoulder and facades
  double tree_spacing_m = 0;        // 0 = no trees
  double pole_spacing_m = 0;        // 0 = no poles (poles are labelled obstacles)
  std::string fence = "none";       // none | left | right | both
  bool guard_rails = false;         // at both road edges and on the centre line
};

struct WetPatch {
  double lateral_m = 0;     // relative to the camera at frame 0
  double distance_m = 15;   // centre, forward from the camera at frame 0
  double length_m = 8;
  double width_m = 3;
};

struct TrapSpec {
  std::vector<WetPatch> wet_patches;
  int random_wet_patches = 0;       // extra patches spread along the route
  double reflectivity = 0.8;        // mirror share of a wet patch's colour
  double glitter = 60;              // per-view independent sparkle on wet patches [DN]
  bool repetitive_fence = false;    // fences/railings get a strictly periodic texture
  bool overexposed_sky = false;     // low sun ahead saturates part of the sky
};

struct SceneSpec {
  std::string name = "scene";
  uint64_t seed = 1;
  CameraRig camera;
  RoadSpec road;
  TrafficSpec traffic;
  BackgroundSpec background;
  std::vector<ObstacleSpec> obstacles;
  TrapSpec traps;
};

// Throws SceneError naming the first problem (calibration, placement).
void validateScene(const SceneSpec& spec);

}  // namespace nerv::synth
