// nerv_render: what nerv saw, frame by frame, from a log alone.
//
//   nerv_render LOG --out DIR [--frames A:B] [--video] [--fps F] [--labels DIR]
//               [--scale S] [--needle-interval PX] [--prefix P]   (P: the camera pipeline of a log of several)
//
// Writes DIR/NNNNNN.png (NNNNNN = seq) per frame: a labelled grid of the left
// image with detections (and ground truth), the disparity with the ground
// model, stixels by depth, surface-normal needles by class, the v-disparity
// with its fitted line, and the frame's facts. --video adds DIR/render.avi (MJPG).
// Exit: 0 rendered, 1 nothing to render (no STEREO_FRAME, empty range), 2 bad
// flags or unreadable log.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "frame_render.hpp"

using namespace nerv;

namespace {

void usage() {
  std::fprintf(stderr,
               "usage: nerv_render LOG --out DIR [--frames A:B] [--video] [--fps F] [--labels DIR] [--scale S]\n"
               "                   [--needle-interval PX] [--prefix P]\n");
}

// "A:B", "A:" or ":B" (inclusive seq range).
void parseRange(const std::string& s, viz::RenderOptions& o) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos) throw std::runtime_error("--frames wants A:B, got '" + s + "'");
  if (colon > 0) o.seq_min = std::stoll(s.substr(0, colon));
  if (colon + 1 < s.size()) o.seq_max = std::stoll(s.substr(colon + 1));
  if (o.seq_min > o.seq_max) throw std::runtime_error("--frames " + s + " is an empty range");
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path;
  viz::RenderOptions o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
        return argv[++i];
      };
      if (a == "--out") o.out_dir = value();
      else if (a == "--frames") parseRange(value(), o);
      else if (a == "--video") o.video = true;
      else if (a == "--fps") o.video_fps = std::stod(value());
      else if (a == "--labels") o.labels_dir = value();
      else if (a == "--scale") o.scale = std::stod(value());
      else if (a == "--prefix") o.prefix = value();
      else if (a == "--needle-interval") o.needles.interval_px = std::stoi(value());
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] == '-') throw std::runtime_error("unknown flag '" + a + "'");
      else if (log_path.empty()) log_path = a;
      else throw std::runtime_error("one log only ('" + a + "')");
    }
    if (log_path.empty() || o.out_dir.empty()) throw std::runtime_error("LOG and --out DIR are required");
    if (!(o.scale > 0 && o.scale <= 4)) throw std::runtime_error("--scale must be in (0, 4]");
    if (!(o.video_fps > 0 && o.video_fps <= 240)) throw std::runtime_error("--fps must be in (0, 240]");
    if (o.needles.interval_px < 2 || o.needles.interval_px > 200)
      throw std::runtime_error("--needle-interval must be in [2, 200]");
    if (!o.labels_dir.empty() && !std::filesystem::is_directory(o.labels_dir))
      throw std::runtime_error("label folder " + o.labels_dir + " does not exist");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_render: %s\n", e.what());
    usage();
    return 2;
  }
  try {
    const viz::RenderResult r = viz::renderLog(log_path, o);
    if (!r.log.pipelines.empty()) std::fprintf(stderr, "nerv_render: %s\n", r.log.pipelines.c_str());
    if (r.log.stereo_frames == 0) {
      std::fprintf(stderr, "nerv_render: %s has no STEREO_FRAME messages (%lld events): nothing to render\n",
                   log_path.c_str(), static_cast<long long>(r.log.events));
      return 1;
    }
    std::printf("nerv_render: %d frames to %s in %.2f s (%.0f ms/frame)%s%s\n", r.rendered, o.out_dir.c_str(),
                r.seconds, r.rendered ? 1000 * r.seconds / r.rendered : 0.0, r.video_path.empty() ? "" : ", video ",
                r.video_path.c_str());
    if (r.log.broken || r.skipped || r.label_problems || r.log.duplicates)
      std::printf("nerv_render: skipped %lld broken messages, %lld duplicates, %d frames without a usable left image%s%s, "
                  "%d unreadable label files\n",
                  static_cast<long long>(r.log.broken), static_cast<long long>(r.log.duplicates), r.skipped,
                  r.first_problem.empty() ? "" : " (first: ", r.first_problem.empty() ? "" : (r.first_problem + ")").c_str(),
                  r.label_problems);
    if (r.rendered == 0) {
      std::fprintf(stderr, "nerv_render: no frame rendered%s\n", o.seq_min > INT64_MIN || o.seq_max < INT64_MAX ? " in --frames range" : "");
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_render: %s\n", e.what());
    return 2;
  }
}
