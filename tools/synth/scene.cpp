#include "scene.hpp"

#include <cmath>
#include <sstream>

namespace nerv::synth {

const char* className(ObstacleClass c) {
  switch (c) {
    case ObstacleClass::Car: return "Car";
    case ObstacleClass::Van: return "Van";
    case ObstacleClass::Truck: return "Truck";
    case ObstacleClass::Pedestrian: return "Pedestrian";
    case ObstacleClass::Cyclist: return "Cyclist";
    case ObstacleClass::Pole: return "Pole";
  }
  return "Misc";
}

void validateScene(const SceneSpec& spec) {
  const CameraRig& cam = spec.camera;
  if (const std::string p = cam.intrinsics.problem(); !p.empty())
    throw SceneError("camera calibration: " + p);
  if (!(cam.height_m > 0)) throw SceneError("camera height_m must be positive");
  if (!(cam.fps > 0)) throw SceneError("camera fps must be positive");
  for (size_t i = 0; i < spec.obstacles.size(); ++i) {
    const ObstacleSpec& o = spec.obstacles[i];
    std::ostringstream who;
    who << "obstacle " << i << " (" << className(o.cls) << ")";
    if (!std::isfinite(o.distance_m) || !std::isfinite(o.lateral_m))
      throw SceneError(who.str() + " has a non-finite position");
    if (o.distance_m <= 0) {
      std::ostringstream m;
      m << who.str() << " is behind the camera (distance_m = " << o.distance_m << ")";
      throw SceneError(m.str());
    }
    if (o.elevation_m < 0) {
      std::ostringstream m;
      m << who.str() << " is below the road (elevation_m = " << o.elevation_m << ")";
      throw SceneError(m.str());
    }
  }
  const RoadSpec& r = spec.road;
  if (r.lanes_left + r.lanes_right < 1) throw SceneError("road must have at least one lane");
}

}  // namespace nerv::synth
