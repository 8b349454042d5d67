// nerv_report: one self-contained HTML page about a recorded run.
//
//   nerv_report LOG --out DIR [--labels DIR] [--extrinsics FILE] [--frame SEQ]
//               [--worst N] [--max-distance M] [--min-iou X] [--visible] [--difficulty easy|moderate|hard] [--count-far-detections] [--prefix P]
//
// Writes DIR/report.html: run summary, pose over time, detections per frame, a
// frame's pitch histogram with the mode / mean / mean-shift of EXTRINSICS,
// per-stage timing and, with labels, precision/recall and the worst frames.
// Images are inlined (base64), plots are inline SVG: the page works offline.
// Exit: 0 written, 2 bad flags or unreadable log.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "run_report.hpp"

using namespace nerv;

namespace {

void usage() {
  std::fprintf(stderr,
               "usage: nerv_report LOG --out DIR [--labels DIR] [--extrinsics FILE] [--frame SEQ] [--worst N]\n"
               "                   [--max-distance M] [--min-iou X] [--visible] [--difficulty easy|moderate|hard] [--count-far-detections]\n"
               "                   [--prefix P]\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path;
  viz::ReportOptions o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
        return argv[++i];
      };
      if (a == "--out") o.out_dir = value();
      else if (a == "--labels") o.labels_dir = value();
      else if (a == "--extrinsics") o.extrinsics_file = value();
      else if (a == "--frame") o.histogram_seq = std::stoll(value());
      else if (a == "--worst") o.worst_frames = std::stoi(value());
      else if (a == "--max-distance") o.eval.max_distance_m = std::stof(value());
      else if (a == "--min-iou") o.eval.min_iou = std::stof(value());
      else if (a == "--visible") o.eval.visible_only = true;
      else if (a == "--difficulty") {
        if (const std::string why = setKittiDifficulty(value(), o.eval); !why.empty()) throw std::runtime_error(why);
      }
      else if (a == "--count-far-detections") o.eval.limit_detections = false;
      else if (a == "--prefix") o.prefix = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] == '-') throw std::runtime_error("unknown flag '" + a + "'");
      else if (log_path.empty()) log_path = a;
      else throw std::runtime_error("one log only ('" + a + "')");
    }
    if (log_path.empty() || o.out_dir.empty()) throw std::runtime_error("LOG and --out DIR are required");
    if (!o.labels_dir.empty() && !std::filesystem::is_directory(o.labels_dir))
      throw std::runtime_error("label folder " + o.labels_dir + " does not exist");
    if (!o.extrinsics_file.empty() && !std::filesystem::exists(o.extrinsics_file))
      throw std::runtime_error("extrinsics file " + o.extrinsics_file + " does not exist");
    if (o.worst_frames < 0 || o.worst_frames > 50) throw std::runtime_error("--worst must be in [0, 50]");
    if (!(o.eval.min_iou > 0 && o.eval.min_iou < 1)) throw std::runtime_error("--min-iou must be in (0, 1)");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_report: %s\n", e.what());
    usage();
    return 2;
  }
  try {
    const viz::ReportResult r = viz::writeRunReport(log_path, o);
    if (!r.note.empty()) std::fprintf(stderr, "nerv_report: %s\n", r.note.c_str());
    if (!r.log.pipelines.empty()) std::fprintf(stderr, "nerv_report: %s\n", r.log.pipelines.c_str());
    std::printf("nerv_report: %s (%d frames, %d plots, %d images; %lld broken messages skipped)\n", r.html_path.c_str(),
                r.frames, r.plots, r.images, static_cast<long long>(r.log.broken));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_report: %s\n", e.what());
    return 2;
  }
}
