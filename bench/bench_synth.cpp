// Rendering speed of the synthetic scene generator: ms per frame of the
// `urban` preset at 1242x375, rendered on OpenCV's thread pool (the default)
// and, as the baseline measured in the same run, on the calling thread only.
// Also times the full write path (render + PNG + labels) for the CLI's case.
//   bench_synth [frames=20] [scene=urban]
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <opencv2/core/utility.hpp>

#include "scene_yaml.hpp"
#include "kitti_writer.hpp"
#include "sequence.hpp"


namespace {

// Process CPU time [ms]: with other jobs on the machine, wall time alone says little.
double cpuMs() { return 1000.0 * std::clock() / CLOCKS_PER_SEC; }

struct Timing {
  double wall_ms, cpu_ms;  // per frame
};

Timing perFrame(nerv::synth::SceneSequence& seq, int frames, const nerv::synth::RenderOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpuMs();
  for (int i = 0; i < frames; ++i) seq.render(i, opt);
  const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return {wall / frames, (cpuMs() - c0) / frames};
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::string scene = argc > 2 ? argv[2] : "urban";
  // The scenes live next to this source file's repository root.
  const std::string scenes_dir = std::filesystem::path(__FILE__).parent_path().parent_path() / "config" / "scenes";
  try {
    const nerv::synth::SceneSpec spec =
        nerv::synth::loadScene(nerv::synth::resolveScenePath(scene, scenes_dir));
    nerv::synth::SceneSequence seq(spec);
    nerv::synth::RenderOptions pool, single;
    single.threads = 1;
    seq.render(0, pool);  // warm-up (thread pool start)
    const Timing t_single = perFrame(seq, frames, single);
    const Timing t_pool = perFrame(seq, frames, pool);
    const std::string out = (std::filesystem::temp_directory_path() / "nerv_bench_synth").string();
    // Writing one frame (PNGs, calibration, labels) on its own.
    nerv::synth::prepareOutput(out);
    const nerv::synth::SynthFrame one = seq.render(0, pool);
    const auto w0 = std::chrono::steady_clock::now();
    const double wc0 = cpuMs();
    for (int i = 0; i < frames; ++i) nerv::synth::writeFrame(out, i, seq.camera(), one.images, one.labels);
    const double write_wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count() / frames;
    const double write_cpu = (cpuMs() - wc0) / frames;
    std::filesystem::remove_all(out);
    const auto summary = nerv::synth::writeSequence(spec, frames, out, pool);
    std::filesystem::remove_all(out);
    const auto& k = spec.camera.intrinsics;
    std::printf("bench_synth: scene %s %dx%d, %d frames, supersample %d, %d OpenCV threads\n",
                spec.name.c_str(), k.width, k.height, frames, pool.supersample, cv::getNumThreads());
    std::printf("  render, calling thread only (baseline): %8.1f ms/frame wall, %8.1f ms CPU\n",
                t_single.wall_ms, t_single.cpu_ms);
    std::printf("  render, thread pool (default):          %8.1f ms/frame wall, %8.1f ms CPU  (x%.2f faster than baseline)\n",
                t_pool.wall_ms, t_pool.cpu_ms, t_single.wall_ms / t_pool.wall_ms);
    std::printf("  write one frame (4 PNG, calib, labels): %8.1f ms/frame wall, %8.1f ms CPU\n", write_wall, write_cpu);
    std::printf("  render + write KITTI layout:            %8.1f ms/frame  -> 100 frames in %.1f s\n",
                1000.0 * summary.seconds / frames, 100.0 * summary.seconds / frames);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_synth: %s\n", e.what());
    return 2;
  }
  return 0;
}
