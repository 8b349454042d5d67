#include "scene_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>

#include "config.hpp"

namespace nerv::synth {
namespace {


// Reads a key only when present. (Keeps defaults robust against ConfigSection
// versions that treat an absent key as an empty value.)
template <typename T, typename... Range>
void get(ConfigSection& c, const std::string& key, T& value, Range&&... range) {
  if (c.has(key))
    c.get(key, value, std::forward<Range>(range)...);
  else
    c.allow(key);
}

void get(ConfigSection& c, const std::string& key, std::string& value,
         std::initializer_list<const char*> allowed) {
  if (c.has(key))
    c.get(key, value, allowed);
  else
    c.allow(key);
}

ObstacleClass parseClass(const std::string& s) {
  if (s == "car") return ObstacleClass::Car;
  if (s == "van") return ObstacleClass::Van;
  if (s == "truck") return ObstacleClass::Truck;
  if (s == "pedestrian") return ObstacleClass::Pedestrian;
  if (s == "cyclist") return ObstacleClass::Cyclist;
  return ObstacleClass::Pole;
}

void readCamera(ConfigSection c, CameraRig& cam) {
  StereoCamera& k = cam.intrinsics;
  // Ranges are left open for the calibration: validateScene() reports a
  // non-positive focal length or baseline with the calibration's own message.
  get(c, "width", k.width, 16, 8192);
  get(c, "height", k.height, 16, 8192);
  get(c, "fx", k.fx);
  k.fy = k.fx;
  get(c, "fy", k.fy);
  get(c, "cx", k.cx);
  get(c, "cy", k.cy);
  get(c, "baseline_m", k.baseline_m);
  get(c, "height_m", cam.height_m, 0.05, 20);
  get(c, "pitch_deg", cam.pitch_deg, -20, 20);
  get(c, "roll_deg", cam.roll_deg, -20, 20);
  get(c, "lateral_m", cam.lateral_m, -50, 50);
  get(c, "speed_mps", cam.speed_mps, 0, 60);
  get(c, "fps", cam.fps, 0.1, 1000);
  get(c, "pitch_amplitude_deg", cam.pitch_amplitude_deg, 0, 10);
  get(c, "pitch_period_s", cam.pitch_period_s, 0.05, 100);
  get(c, "roll_amplitude_deg", cam.roll_amplitude_deg, 0, 10);
  get(c, "roll_period_s", cam.roll_period_s, 0.05, 100);
  get(c, "height_amplitude_m", cam.height_amplitude_m, 0, 0.5);
  get(c, "bump_interval_s", cam.bump_interval_s, 0, 100);
  get(c, "bump_pitch_deg", cam.bump_pitch_deg, -10, 10);
  get(c, "noise_sigma", cam.noise_sigma, 0, 30);
  get(c, "right_gain", cam.right_gain, 0.5, 2);
  get(c, "right_offset", cam.right_offset, -50, 50);
  c.finish();
}

void readRoad(ConfigSection c, RoadSpec& r) {
  get(c, "lanes_right", r.lanes_right, 0, 6);
  get(c, "lanes_left", r.lanes_left, 0, 6);
  get(c, "lane_width_m", r.lane_width_m, 2, 6);
  get(c, "sidewalk_width_m", r.sidewalk_width_m, 0, 10);
  get(c, "curb_height_m", r.curb_height_m, 0, 0.4);
  get(c, "slope_start_m", r.slope_start_m, 0, 10000);
  get(c, "grade_percent", r.grade_percent, -15, 15);
  get(c, "markings", r.markings);
  c.finish();
}

void readTraffic(ConfigSection c, TrafficSpec& t) {
  get(c, "parked_spacing_m", t.parked_spacing_m, 0, 200);
  get(c, "parked_side", t.parked_side, {"right", "left", "both"});
  get(c, "cars_ahead", t.cars_ahead, 0, 20);
  get(c, "oncoming", t.oncoming, 0, 50);
  get(c, "pedestrians", t.pedestrians, 0, 50);
  get(c, "cyclists", t.cyclists, 0, 20);
  get(c, "traffic_speed_mps", t.traffic_speed_mps, 0, 50);
  get(c, "truck_fraction", t.truck_fraction, 0, 1);
  c.finish();
}

void readBackground(ConfigSection c, BackgroundSpec& b) {
  get(c, "buildings", b.buildings);
  get(c, "building_setback_m", b.building_setback_m, 0, 100);
  get(c, "tree_spacing_m", b.tree_spacing_m, 0, 500);
  get(c, "pole_spacing_m", b.pole_spacing_m, 0, 500);
  get(c, "fence", b.fence, {"none", "left", "right", "both"});
  get(c, "guard_rails", b.guard_rails);
  c.finish();
}

void readObstacle(ConfigSection c, ObstacleSpec& o) {
  std::string cls = "car";
  get(c, "class", cls, {"car", "van", "truck", "pedestrian", "cyclist", "pole"});
  o.cls = parseClass(cls);
  // Position keys have no range here: validateScene() explains what is wrong
  // with a placement (behind the camera, below the road).
  get(c, "lateral_m", o.lateral_m);
  get(c, "distance_m", o.distance_m);
  get(c, "heading_deg", o.heading_deg, -360, 360);
  get(c, "speed_mps", o.speed_mps, -60, 60);
  get(c, "elevation_m", o.elevation_m);
  get(c, "textureless", o.textureless);
  get(c, "colour", o.colour, -1, 1000);
  c.finish();
}

void readWetPatch(ConfigSection c, WetPatch& w) {
  get(c, "lateral_m", w.lateral_m, -50, 50);
  get(c, "distance_m", w.distance_m, -100, 10000);
  get(c, "length_m", w.length_m, 0.5, 100);
  get(c, "width_m", w.width_m, 0.5, 30);
  c.finish();
}

void readTraps(ConfigSection c, const YAML::Node& node, TrapSpec& t) {
  c.allow("wet_patches");
  const YAML::Node list = node["wet_patches"];
  if (list.IsDefined() && !list.IsNull()) {
    if (!list.IsSequence()) throw ConfigError("config key 'traps.wet_patches' must be a list");
    for (size_t i = 0; i < list.size(); ++i) {
      WetPatch w;
      readWetPatch(ConfigSection(list[i], "traps.wet_patches[" + std::to_string(i) + "]"), w);
      t.wet_patches.push_back(w);
    }
  }
  get(c, "random_wet_patches", t.random_wet_patches, 0, 200);
  get(c, "reflectivity", t.reflectivity, 0, 1);
  get(c, "glitter", t.glitter, 0, 255);
  get(c, "repetitive_fence", t.repetitive_fence);
  get(c, "overexposed_sky", t.overexposed_sky);
  c.finish();
}

SceneSpec fromNode(const YAML::Node& root, const std::string& name) {
  SceneSpec spec;
  spec.name = name;
  try {
    ConfigSection c(root, "");
    get(c, "name", spec.name);
    int seed = 1;
    get(c, "seed", seed, 0, std::numeric_limits<int>::max());
    spec.seed = static_cast<uint64_t>(seed);
    readCamera(c.section("camera"), spec.camera);
    readRoad(c.section("road"), spec.road);
    readTraffic(c.section("traffic"), spec.traffic);
    readBackground(c.section("background"), spec.background);
    c.allow("obstacles");
    const YAML::Node list = root["obstacles"];
    if (list.IsDefined() && !list.IsNull()) {
      if (!list.IsSequence()) throw ConfigError("config key 'obstacles' must be a list");
      for (size_t i = 0; i < list.size(); ++i) {
        ObstacleSpec o;
        readObstacle(ConfigSection(list[i], "obstacles[" + std::to_string(i) + "]"), o);
        spec.obstacles.push_back(o);
      }
    }
    c.allow("traps");
    const YAML::Node traps = root["traps"].IsDefined() && !root["traps"].IsNull()
                                 ? root["traps"]
                                 : YAML::Node(YAML::NodeType::Map);
    readTraps(ConfigSection(traps, "traps"), traps, spec.traps);
    c.finish();
  } catch (const ConfigError& e) {
    throw SceneError("scene " + name + ": " + e.what());
  } catch (const YAML::Exception& e) {
    throw SceneError("scene " + name + ": " + e.msg);
  }
  validateScene(spec);
  return spec;
}

}  // namespace

SceneSpec loadScene(const std::string& yaml_path) {
  YAML::Node root;
  try {
    root = loadConfigFile(yaml_path);
  } catch (const ConfigError& e) {
    throw SceneError(e.what());
  }
  return fromNode(root, yaml_path);
}

SceneSpec parseScene(const std::string& yaml_text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneError("scene " + name + ": " + e.msg + " at line " + std::to_string(e.mark.line + 1));
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw SceneError("scene " + name + " is not a YAML map");
  return fromNode(root, name);
}

std::string resolveScenePath(const std::string& name_or_path, const std::string& scenes_dir) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       (name_or_path.size() > 5 &&
                        name_or_path.compare(name_or_path.size() - 5, 5, ".yaml") == 0);
  return is_path ? name_or_path : scenes_dir + "/" + name_or_path + ".yaml";
}

void resizeImage(SceneSpec& spec, int width, int height) {
  StereoCamera& k = spec.camera.intrinsics;
  if (width <= 0 || height <= 0)
    throw SceneError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is not positive");
  const double sx = double(width) / k.width, sy = double(height) / k.height;
  k.fx *= sx;
  k.fy *= sx;
  k.cx = (k.cx + 0.5) * sx - 0.5;
  k.cy = (k.cy + 0.5) * sy - 0.5;
  k.width = width;
  k.height = height;
}

}  // namespace nerv::synth
