// KITTI object labels from a rendered frame: the 2D box is the tight box of
// the pixel centres that see the object (inclusive pixel indices), the 3D box
// and rotation are the object's, in the left camera frame.
#pragma once

#include <string>
#include <vector>

#include "camera_pose.hpp"
#include "renderer.hpp"
#include "world.hpp"

namespace nerv::synth {

struct Label {
  std::string type;        // Car, Van, Truck, Pedestrian, Cyclist, Pole, DontCare
  int solid = -1;          // index into World::solids
  double truncation = 0;   // 0..1, share of the projected 3D box outside the image
  int occlusion = 0;       // 0 fully visible, 1 partly, 2 largely occluded
  double alpha = -10;      // observation angle [rad]
  int left = 0, top = 0, right = 0, bottom = 0;  // 2D box, inclusive pixel indices
  double height_m = -1, width_m = -1, length_m = -1;
  Vec3 location = Vec3(-1000, -1000, -1000);     // bottom centre, camera frame [m]
  double rotation_y = -10;                       // [rad]
  int visible_px = 0;
};

// Objects and DontCare structures with at least `min_pixels` visible pixels.
// Obstacles more than 80 m ahead and background structure (buildings, trees,
// fences, guard rails) are DontCare. With min_run_px > 0 an object box's left
// and right edges are its outermost columns seeing at least min_run_px of its
// pixels: a sliver one or two rows thin (a parked car's roof seen above the
// next car of the row) no longer widens the box; top and bottom stay those of
// every visible pixel (a variant for measuring, not the default).
std::vector<Label> makeLabels(const World& world, const StereoCamera& camera, const CameraPose& pose,
                              const RenderedFrame& frame, int min_pixels = 1, int min_run_px = 0);

// One line of a KITTI label_2 file (no newline).
std::string formatLabel(const Label& label);

}  // namespace nerv::synth
