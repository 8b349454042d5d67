#include "object_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::synth {
namespace {

Part box(const Vec3& c, const Vec3& half, Material m, const cv::Vec3f& colour, bool trap = false) {
  Part p;
  p.shape = Shape::Box;
  p.c = c;
  p.e = half;
  p.surface = {m, colour};
  p.trap = trap;
  return p;
}

Part cylY(const Vec3& c, double radius, double half_h, Material m, const cv::Vec3f& colour) {
  Part p;
  p.shape = Shape::CylinderY;
  p.c = c;
  p.e = Vec3(radius, half_h, 0);
  p.surface = {m, colour};
  return p;
}

Part wheel(double x, double z, double radius, double half_w) {
  Part p;
  p.shape = Shape::CylinderX;
  p.c = Vec3(x, radius, z);
  p.e = Vec3(half_w, radius, 0);
  p.surface = {Material::Tire, {35, 35, 35}};
  return p;
}

Part sphere(const Vec3& c, double r, Material m, const cv::Vec3f& colour) {
  Part p;
  p.shape = Shape::Sphere;
  p.c = c;
  p.e = Vec3(r, 0, 0);
  p.surface = {m, colour};
  return p;
}

// BGR colour with each channel uniform in its range (drawn in B, G, R order).
cv::Vec3f randomColour(SceneRng& rng, double b0, double b1, double g0, double g1, double r0, double r1) {
  const float b = static_cast<float>(rng.uniform(b0, b1));
  const float g = static_cast<float>(rng.uniform(g0, g1));
  const float r = static_cast<float>(rng.uniform(r0, r1));
  return {b, g, r};
}

const cv::Vec3f kRed(40, 40, 200), kLamp(200, 225, 235), kPlate(225, 225, 225);

void lightsAndPlate(Solid& s, double w, double l, double y_lamp) {
  for (double side : {-1.0, 1.0}) {
    s.parts.push_back(box({side * (w / 2 - 0.22), y_lamp, -l / 2 - 0.012}, {0.15, 0.07, 0.012},
                          Material::Sign, kRed));
    s.parts.push_back(box({side * (w / 2 - 0.22), y_lamp, l / 2 + 0.012}, {0.15, 0.07, 0.012},
                          Material::Sign, kLamp));
  }
  s.parts.push_back(box({0, 0.5, -l / 2 - 0.012}, {0.26, 0.06, 0.012}, Material::Sign, kPlate));
}

Solid car(const cv::Vec3f& paint, SceneRng& rng) {
  Solid s;
  s.type = "Car";
  const double l = rng.uniform(3.9, 4.6), w = rng.uniform(1.70, 1.85), h = rng.uniform(1.42, 1.55);
  s.length_m = l + 0.024;
  s.width_m = w;
  s.height_m = h;
  s.parts.push_back(box({0, 0.6, 0}, {w / 2, 0.35, l / 2}, Material::Paint, paint));
  s.parts.push_back(box({0, (0.95 + h) / 2, -0.15}, {w / 2 - 0.1, (h - 0.95) / 2, l * 0.27},
                        Material::Cabin, paint));
  for (double sx : {-1.0, 1.0})
    for (double sz : {-1.0, 1.0}) s.parts.push_back(wheel(sx * (w / 2 - 0.13), sz * (l / 2 - 0.8), 0.32, 0.11));
  lightsAndPlate(s, w, l, 0.8);
  s.casts_shadow = true;
  return s;
}

Solid van(const cv::Vec3f& paint, bool textureless, SceneRng& rng) {
  Solid s;
  s.type = "Van";
  const double l = rng.uniform(4.8, 5.4), w = 1.95, h = rng.uniform(2.0, 2.3);
  s.length_m = l + 0.024;
  s.width_m = w + 0.02;
  s.height_m = h;
  const Material m = textureless ? Material::PlainWhite : Material::Paint;
  s.parts.push_back(box({0, (0.3 + h) / 2, 0}, {w / 2, (h - 0.3) / 2, l / 2}, m, paint, textureless));
  // Side and front windows of the cab, proud of the body by 1 cm.
  s.parts.push_back(box({0, (1.25 + h - 0.2) / 2, l / 2 - 0.9}, {w / 2 + 0.01, (h - 1.45) / 2, 0.7},
                        Material::Cabin, paint));
  for (double sx : {-1.0, 1.0})
    for (double sz : {-1.0, 1.0}) s.parts.push_back(wheel(sx * (w / 2 - 0.14), sz * (l / 2 - 0.85), 0.35, 0.12));
  lightsAndPlate(s, w, l, 0.9);
  s.casts_shadow = true;
  return s;
}

Solid truck(const cv::Vec3f& paint, bool textureless, SceneRng& rng) {
  Solid s;
  s.type = "Truck";
  const double l = rng.uniform(7.5, 10.0), w = 2.5, h = rng.uniform(3.2, 3.7);
  s.length_m = l + 0.024;
  s.width_m = w;
  s.height_m = h;
  const double cab = 2.2;
  // Cab at the front, box body behind it on a dark chassis.
  s.parts.push_back(box({0, 1.75, l / 2 - cab / 2}, {w / 2 - 0.05, 1.25, cab / 2}, Material::Paint, paint));
  s.parts.push_back(box({0, 2.35, l / 2 + 0.005}, {w / 2 - 0.15, 0.45, 0.005}, Material::Cabin, paint));
  const cv::Vec3f body = textureless ? cv::Vec3f(236, 236, 236) : vehicleColour(rng.index(kVehiclePaletteSize));
  const Material m = textureless ? Material::PlainWhite : Material::Paint;
  const double body_len = l - cab - 0.2;
  s.parts.push_back(box({0, (1.0 + h) / 2, -l / 2 + body_len / 2}, {w / 2, (h - 1.0) / 2, body_len / 2},
                        m, body, textureless));
  s.parts.push_back(box({0, 0.75, 0}, {w / 2 - 0.35, 0.25, l / 2 - 0.3}, Material::Tire, {45, 45, 45}));
  for (double sx : {-1.0, 1.0}) {
    for (double z : {l / 2 - 1.3, -l / 2 + 1.0, -l / 2 + 2.2})
      s.parts.push_back(wheel(sx * (w / 2 - 0.2), z, 0.5, 0.18));
  }
  lightsAndPlate(s, w, l, 0.75);
  s.casts_shadow = true;
  return s;
}

Solid pedestrian(SceneRng& rng) {
  Solid s;
  s.type = "Pedestrian";
  const double h = rng.uniform(1.6, 1.9), k = h / 1.75;
  s.height_m = h;
  s.width_m = 0.62;
  s.length_m = 0.4;
  const cv::Vec3f shirt = randomColour(rng, 30, 200, 30, 200, 30, 200);
  const cv::Vec3f trousers = randomColour(rng, 30, 110, 30, 90, 20, 80);
  const cv::Vec3f skin = randomColour(rng, 90, 140, 120, 165, 160, 210);
  const double stride = rng.uniform(-0.12, 0.12);
  for (double side : {-1.0, 1.0})
    s.parts.push_back(cylY({side * 0.1, 0.43 * k, side * stride}, 0.075, 0.43 * k, Material::Cloth, trousers));
  s.parts.push_back(box({0, 1.15 * k, 0}, {0.2, 0.3 * k, 0.12}, Material::Cloth, shirt));
  for (double side : {-1.0, 1.0})
    s.parts.push_back(cylY({side * 0.26, 1.12 * k, -side * stride}, 0.05, 0.3 * k, Material::Cloth, shirt));
  s.parts.push_back(sphere({0, h - 0.115, 0}, 0.115, Material::Skin, skin));
  return s;
}

Solid cyclist(SceneRng& rng) {
  Solid s;
  s.type = "Cyclist";
  s.height_m = 1.76;
  s.width_m = 0.6;
  s.length_m = 1.76;
  const cv::Vec3f jacket = randomColour(rng, 30, 220, 30, 220, 30, 220);
  for (double z : {-0.53, 0.53}) s.parts.push_back(wheel(0, z, 0.34, 0.025));
  s.parts.push_back(box({0, 0.62, 0}, {0.025, 0.17, 0.42}, Material::Metal, {60, 60, 170}));
  for (double side : {-1.0, 1.0})
    s.parts.push_back(cylY({side * 0.11, 0.78, -0.05}, 0.07, 0.3, Material::Cloth, {60, 50, 45}));
  s.parts.push_back(box({0, 1.3, -0.02}, {0.19, 0.27, 0.14}, Material::Cloth, jacket));
  for (double side : {-1.0, 1.0})
    s.parts.push_back(box({side * 0.22, 1.25, 0.22}, {0.045, 0.045, 0.25}, Material::Cloth, jacket));
  s.parts.push_back(sphere({0, 1.64, 0.02}, 0.12, Material::Sign, {40, 40, 40}));
  return s;
}

Solid pole(SceneRng& rng) {
  Solid s;
  s.type = "Pole";
  const bool post = rng.chance(0.35);  // a short delineator post, else a sign pole
  if (post) {
    s.height_m = 1.1;
    s.parts.push_back(cylY({0, 0.55, 0}, 0.06, 0.55, Material::StripedPost, {200, 200, 200}));
    s.width_m = s.length_m = 0.12;
    return s;
  }
  const double h = rng.uniform(2.8, 4.0);
  s.height_m = h;
  s.parts.push_back(cylY({0, h / 2, 0}, 0.055, h / 2, Material::Metal, {150, 150, 148}));
  static const cv::Vec3f signs[] = {{170, 90, 30}, {40, 40, 190}, {40, 190, 220}};
  s.parts.push_back(box({0, h - 0.35, -0.08}, {0.3, 0.3, 0.02}, Material::Sign, signs[rng.index(3)]));
  s.width_m = 0.6;
  s.length_m = 0.2;
  return s;
}

}  // namespace

cv::Vec3f vehicleColour(int index) {
  static const cv::Vec3f palette[kVehiclePaletteSize] = {
      {180, 178, 172}, {70, 70, 72}, {38, 36, 36}, {45, 45, 165}, {150, 85, 40},
      {95, 45, 25},    {65, 100, 55}, {150, 175, 195}, {205, 205, 200}, {40, 175, 210}};
  return palette[((index % kVehiclePaletteSize) + kVehiclePaletteSize) % kVehiclePaletteSize];
}

Solid makeObstacle(ObstacleClass cls, int colour, bool textureless, SceneRng& rng) {
  const cv::Vec3f paint = textureless ? cv::Vec3f(236, 236, 236)
                                      : vehicleColour(colour >= 0 ? colour : rng.index(kVehiclePaletteSize));
  Solid s;
  switch (cls) {
    case ObstacleClass::Car: s = car(paint, rng); break;
    case ObstacleClass::Van: s = van(paint, textureless, rng); break;
    case ObstacleClass::Truck: s = truck(paint, textureless, rng); break;
    case ObstacleClass::Pedestrian: s = pedestrian(rng); break;
    case ObstacleClass::Cyclist: s = cyclist(rng); break;
    case ObstacleClass::Pole: s = pole(rng); break;
  }
  s.seed = static_cast<uint32_t>(rng.next());
  s.computeBounds();
  return s;
}

Solid makeTree(SceneRng& rng) {
  Solid s;
  s.type = "DontCare";
  const double trunk = rng.uniform(2.0, 3.0), r = rng.uniform(1.4, 2.4);
  s.parts.push_back(cylY({0, trunk / 2 + 0.3, 0}, rng.uniform(0.12, 0.2), trunk / 2 + 0.3, Material::Bark,
                         {45, 65, 85}));
  s.parts.push_back(sphere({0, trunk + r * 0.8, 0}, r, Material::Foliage,
                           randomColour(rng, 30, 50, 85, 120, 45, 70)));
  s.height_m = trunk + r * 1.8;
  s.width_m = s.length_m = 2 * r;
  s.seed = static_cast<uint32_t>(rng.next());
  s.computeBounds();
  return s;
}

Solid makeBuilding(double depth_m, double length_m, double height_m, SceneRng& rng) {
  Solid s;
  s.type = "DontCare";
  static const cv::Vec3f walls[] = {{150, 165, 185}, {120, 130, 150}, {170, 170, 165},
                                    {95, 110, 140},  {185, 195, 200}, {110, 120, 120}};
  // Reaches 2 m below its base so that it meets a sloping road without a gap.
  s.parts.push_back(box({0, (height_m - 2) / 2, 0}, {depth_m / 2, (height_m + 2) / 2, length_m / 2},
                        Material::Facade, walls[rng.index(6)]));
  s.height_m = height_m;
  s.width_m = depth_m;
  s.length_m = length_m;
  s.seed = static_cast<uint32_t>(rng.next());
  s.computeBounds();
  return s;
}

Solid makeFence(double length_m, bool repetitive, SceneRng& rng) {
  Solid s;
  s.type = "DontCare";
  const double h = repetitive ? 1.1 : rng.uniform(1.0, 1.6);
  s.parts.push_back(box({0, h / 2, 0}, {0.03, h / 2, length_m / 2},
                        repetitive ? Material::Railing : Material::Fence,
                        randomColour(rng, 50, 80, 90, 120, 120, 160), repetitive));
  s.height_m = h;
  s.width_m = 0.06;
  s.length_m = length_m;
  s.seed = static_cast<uint32_t>(rng.next());
  s.computeBounds();
  return s;
}

Solid makeGuardRail(double length_m, bool repetitive, SceneRng& rng) {
  Solid s;
  s.type = "DontCare";
  const cv::Vec3f steel(165, 168, 170);
  s.parts.push_back(box({0, 0.6, 0}, {0.05, 0.17, length_m / 2}, Material::GuardRail, steel, repetitive));
  for (double z = -length_m / 2 + 1.0; z < length_m / 2; z += 2.0) {
    Part post = box({0, 0.36, z}, {0.04, 0.36, 0.04}, Material::Metal, {120, 120, 118}, repetitive);
    post.c.x() = 0.09;  // behind the beam, away from the road when the rail faces -x
    s.parts.push_back(post);
  }
  s.height_m = 0.77;
  s.width_m = 0.2;
  s.length_m = length_m;
  s.seed = static_cast<uint32_t>(rng.next());
  s.computeBounds();
  return s;
}

}  // namespace nerv::synth
