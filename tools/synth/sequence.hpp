// A scene driven through time: the world, the camera pose per frame, and the
// rendered frames with their labels. writeSequence() is what the CLI runs.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "camera_pose.hpp"
#include "labels.hpp"
#include "renderer.hpp"
#include "scene.hpp"
#include "world.hpp"

namespace nerv::synth {

struct SynthFrame {
  int index = 0;
  CameraPose pose;
  RenderedFrame images;
  std::vector<Label> labels;
};

class SceneSequence {
 public:
  // Validates the scene (SceneError) and builds its world.
  explicit SceneSequence(const SceneSpec& spec);

  const SceneSpec& spec() const { return spec_; }
  const World& world() const { return world_; }
  const StereoCamera& camera() const { return spec_.camera.intrinsics; }

  CameraPose pose(int frame) const { return cameraPose(spec_.camera, world_, frame); }
  // Renders frame `frame` (time frame / fps) with its labels.
  SynthFrame render(int frame, const RenderOptions& options = {});

 private:
  SceneSpec spec_;
  World world_;
};

struct SequenceSummary {
  int frames = 0;
  size_t labels = 0;     // object labels (DontCare excluded)
  double seconds = 0;    // wall time of rendering and writing
};

// Renders `frames` frames into `out_dir` (KITTI object layout, see
// kitti_writer.hpp). `progress` is called after each frame is written.
SequenceSummary writeSequence(const SceneSpec& spec, int frames, const std::string& out_dir,
                              const RenderOptions& options = {},
                              const std::function<void(const SynthFrame&, double ms)>& progress = {});

}  // namespace nerv::synth
