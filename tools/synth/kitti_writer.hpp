// Output in the KITTI object layout, readable by nerv::openDataset:
//   image_2/ image_3/ NNNNNN.png       left / right colour images
//   calib/NNNNNN.txt                   P0..P3, R0_rect, Tr_velo_to_cam, Tr_imu_to_velo
//   label_2/NNNNNN.txt                 KITTI labels
//   disp_occ_0/NNNNNN.png              uint16 left disparity x 256, 0 = none (sky)
//   trap_mask/NNNNNN.png               8-bit, 255 inside disparity traps
//   extrinsics.txt                     per frame: frame pitch_deg roll_deg height_m
#pragma once

#include <string>
#include <vector>

#include "camera_pose.hpp"
#include "labels.hpp"
#include "renderer.hpp"

namespace nerv::synth {

std::string frameName(int index);  // 000042

// Creates the folders; throws SceneError when it cannot.
void prepareOutput(const std::string& dir);

void writeCalibration(const std::string& path, const StereoCamera& camera);
void writeFrame(const std::string& dir, int index, const StereoCamera& camera,
                const RenderedFrame& frame, const std::vector<Label>& labels);
void writeExtrinsics(const std::string& path, const std::vector<CameraPose>& poses);

}  // namespace nerv::synth
