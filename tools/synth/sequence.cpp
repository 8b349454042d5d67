#include "sequence.hpp"

#include <chrono>
#include <filesystem>

#include "kitti_writer.hpp"
#include "world_builder.hpp"

namespace nerv::synth {

SceneSequence::SceneSequence(const SceneSpec& spec) : spec_(spec), world_(buildWorld(spec)) {}

SynthFrame SceneSequence::render(int frame, const RenderOptions& options) {
  SynthFrame f;
  f.index = frame;
  const double t = frame / spec_.camera.fps;
  cv::Mat late_right;
  if (options.right_delay_s != 0) {
    world_.setTime(t + options.right_delay_s);
    const CameraPose later = cameraPoseAt(spec_.camera, world_, t + options.right_delay_s);
    late_right = renderFrame(world_, spec_.camera, later, frame, spec_.seed, options).right;
  }
  world_.setTime(t);
  f.pose = pose(frame);
  f.images = renderFrame(world_, spec_.camera, f.pose, frame, spec_.seed, options);
  if (!late_right.empty()) f.images.right = late_right;
  f.labels = makeLabels(world_, camera(), f.pose, f.images, 1, options.label_min_run_px);
  return f;
}

SequenceSummary writeSequence(const SceneSpec& spec, int frames, const std::string& out_dir,
                              const RenderOptions& options,
                              const std::function<void(const SynthFrame&, double ms)>& progress) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  if (frames < 1) throw SceneError("number of frames must be at least 1");
  SceneSequence seq(spec);
  prepareOutput(out_dir);
  SequenceSummary summary;
  std::vector<CameraPose> poses;
  for (int i = 0; i < frames; ++i) {
    const auto t0 = Clock::now();
    const SynthFrame f = seq.render(i, options);
    writeFrame(out_dir, i, seq.camera(), f.images, f.labels);
    poses.push_back(f.pose);
    for (const Label& l : f.labels) summary.labels += l.type != "DontCare";
    if (progress) progress(f, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  writeExtrinsics((std::filesystem::path(out_dir) / "extrinsics.txt").string(), poses);
  summary.frames = frames;
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace nerv::synth
