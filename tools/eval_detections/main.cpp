// nerv_eval_detections: the reference method's table from a recorded run.
//
//   nerv_eval_detections --log LOG --labels DIR [--max-distance M] [--classes Car,Pole]
//                        [--min-iou 0.5] [--visible] [--difficulty easy|moderate|hard]
//                        [--count-far-detections] [--extrinsics FILE] [--from-seq N] [--json]
//                        [--prefix P]
//
// A log of several pipelines (one per camera, each under its channel prefix) is scored for one:
// the pipeline of --prefix P, else the first in the log, saying so on stderr (the labels are
// one camera's).
// "stixel only" scores every hypothesis of DETECTIONS, "stixel + SNV" only the
// kept ones. Labels are DIR/<frame>.txt where <frame> ends the frame_id.
// --visible ignores largely hidden objects (occluded 2) and those half outside
// the image (truncated >= 0.5), as bench_detection --visible does.
// --difficulty applies one of the KITTI object benchmark's difficulties (devkit
// limits on label height, occlusion and truncation; unmatched detections lower
// than its minimum height count neither way; tools/lib/detection_eval.hpp).
// --max-distance M limits both sides: objects farther than M are ignored, and
// so are detections farther than M (their z_m) that match no counted object,
// as the KITTI devkit ignores detections below its minimum height;
// --count-far-detections counts those as false positives (the convention
// before 2026-12-02's sixth session).
// --from-seq N scores only the frames whose seq is N or more (those after a warm-up,
// or after the stereo_matcher's first row verdict).
// --extrinsics FILE (lines "frame pitch_deg roll_deg height_m") adds the pose
// error of EXTRINSICS against it. The depth of the kept true positives (z_m at
// the median stixel, nearest_z_m at the nearest part) is compared with the
// matched label's nearest depth per 10 m band, for labels neither truncated nor
// occluded (tools/lib/distance_accuracy.hpp). Missed objects are counted by
// cause (no box, a loose box at their depth, merged, a part, only boxes at
// another depth, removed by the validator; tools/lib/miss_causes.hpp).
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "frame_evaluation.hpp"
#include "json_writer.hpp"
#include "log_decode.hpp"
#include "miss_causes.hpp"
#include "frame_name.hpp"
#include "percentile.hpp"
#include "pipeline_prefix.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

using namespace nerv;

namespace {

struct Options {
  std::string log, labels, extrinsics;
  EvalParams params;
  bool json = false;
  int64_t from_seq = 0;
  std::optional<std::string> prefix;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--log") o.log = value();
    else if (a == "--labels") o.labels = value();
    else if (a == "--extrinsics") o.extrinsics = value();
    else if (a == "--max-distance") o.params.max_distance_m = std::stof(value());
    else if (a == "--min-iou") o.params.min_iou = std::stof(value());
    else if (a == "--json") o.json = true;
    else if (a == "--from-seq") o.from_seq = std::stoll(value());
    else if (a == "--prefix") o.prefix = value();
    else if (a == "--visible") o.params.visible_only = true;
    else if (a == "--difficulty") {
      if (const std::string why = setKittiDifficulty(value(), o.params); !why.empty()) throw std::runtime_error(why);
    }
    else if (a == "--count-far-detections") o.params.limit_detections = false;
    else if (a == "--classes") {
      std::stringstream list(value());
      for (std::string c; std::getline(list, c, ',');)
        if (!c.empty()) o.params.classes.insert(c);
    } else throw std::runtime_error("unknown flag '" + a + "'");
  }
  if (o.log.empty() || o.labels.empty()) throw std::runtime_error("--log LOG and --labels DIR are required");
  if (!std::filesystem::exists(o.log)) throw std::runtime_error("log " + o.log + " does not exist");
  if (!std::filesystem::is_directory(o.labels)) throw std::runtime_error("label folder " + o.labels + " does not exist");
  return o;
}

struct TruePose { float pitch = 0, roll = 0, height = 0; };

std::map<std::string, TruePose> readExtrinsics(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("extrinsics file " + path + " cannot be read");
  std::map<std::string, TruePose> poses;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string frame;
    TruePose p;
    if (s >> frame >> p.pitch >> p.roll >> p.height) poses[frame] = p;
  }
  return poses;
}

// Frame names may be "000003" in one place and "3" in another.
const TruePose* findPose(const std::map<std::string, TruePose>& poses, const std::string& name) {
  if (auto it = poses.find(name); it != poses.end()) return &it->second;
  try {
    const long n = std::stol(name);
    for (const auto& [k, v] : poses)
      if (std::stol(k) == n) return &v;
  } catch (...) {
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    lcm::LogFile log(o.log, "r");
    if (!log.good()) throw std::runtime_error("log " + o.log + " cannot be read");
    std::map<std::string, TruePose> poses;
    if (!o.extrinsics.empty()) poses = readExtrinsics(o.extrinsics);

    EvalCounts all, kept;
    DepthErrors depth;  // kept true positives vs the label's nearest depth
    MissTally misses;   // why objects were missed
    int frames = 0, unlabelled = 0;
    std::map<std::string, std::vector<double>> stage_ms;
    std::vector<double> pitch_err, roll_err, height_err;
    std::map<int64_t, bool> seen;
    PipelineSelection pipeline(o.prefix);
    while (const lcm::LogEvent* e = log.readNextEvent()) {
      if (!pipeline.take(e->channel)) continue;  // another camera's pipeline: its seqs are its own
      detections_t det;
      disparity_t disp;
      stixels_t stix;
      surface_normals_t normals;
      extrinsics_t ext;
      if (decodeEvent(*e, det)) {
        if (seen[det.header.seq] || det.header.seq < o.from_seq) continue;  // a replayed or duplicated frame counts once
        seen[det.header.seq] = true;
        stage_ms["validator"].push_back(det.processing_ms);
        const std::string label_path = o.labels + "/" + frameName(det.header.frame_id) + ".txt";
        if (!std::filesystem::exists(label_path)) {
          ++unlabelled;
          continue;
        }
        const auto labels = readKittiLabels(label_path);
        const FrameEvaluation e = evaluateDetections(det, labels, o.params, depth, misses);
        all.add(e.all);
        kept.add(e.kept);
        ++frames;
      } else if (decodeEvent(*e, disp)) {
        stage_ms["stereo_matcher"].push_back(disp.processing_ms);
      } else if (decodeEvent(*e, stix)) {
        stage_ms["stixel"].push_back(stix.processing_ms);
      } else if (decodeEvent(*e, normals)) {
        stage_ms["snv_extrinsic"].push_back(normals.processing_ms);
      } else if (decodeEvent(*e, ext) && !poses.empty()) {
        if (const TruePose* p = findPose(poses, frameName(ext.header.frame_id)); p && ext.valid) {
          pitch_err.push_back(std::fabs(ext.pitch_deg - p->pitch));
          roll_err.push_back(std::fabs(ext.roll_deg - p->roll));
          height_err.push_back(std::fabs(ext.height_m - p->height));
        }
      }
    }
    if (const std::string note = pipeline.note(); !note.empty())
      std::fprintf(stderr, "nerv_eval_detections: %s\n", note.c_str());
    if (frames == 0) throw std::runtime_error("no DETECTIONS with labels in " + o.log);
    auto mean = [](const std::vector<double>& v) {
      double s = 0;
      for (double x : v) s += x;
      return v.empty() ? 0.0 : s / v.size();
    };

    if (o.json) {
      JsonWriter j;
      j.beginObject();
      j.field("frames", frames);
      j.field("prefix", pipeline.selected());
      j.field("frames_without_labels", unlabelled);
      j.field("visible_only", o.params.visible_only);
      j.field("difficulty", o.params.difficulty);
      j.field("far_detections_ignored", farDetectionsIgnored(o.params));
      for (const auto& [name, c] : {std::pair<const char*, EvalCounts>{"stixel_only", all}, {"stixel_snv", kept}}) {
        j.key(name);
        j.beginObject();
        j.field("objects", c.objects);
        j.field("tp", c.tp);
        j.field("fp", c.fp);
        j.field("fn", c.fn);
        j.field("precision", c.precision());
        j.field("recall", c.recall());
        j.field("f1", c.f1());
        j.endObject();
      }
      for (const auto& [name, acc] : {std::pair<const char*, const DistanceAccuracy*>{"depth_error_z", &depth.z},
                                      {"depth_error_nearest_z", &depth.nearest}}) {
        j.key(name);
        j.beginArray();
        for (const DistanceErrorBand& b : acc->bands(defaultDistanceBands())) {
          j.beginObject();
          j.field("from_m", b.from_m);
          if (std::isfinite(b.to_m)) j.field("to_m", b.to_m);
          j.field("count", b.count);
          j.field("bias_m", b.bias_m);
          j.field("median_abs_m", b.median_abs_m);
          j.field("p95_abs_m", b.p95_abs_m);
          j.field("median_rel", b.median_rel);
          if (b.count_with_sigma > 0) {  // against the detections' own nearest_z_sigma_m
            j.field("count_with_sigma", b.count_with_sigma);
            j.field("within_1sigma", b.within_1sigma);
            j.field("within_2sigma", b.within_2sigma);
            j.field("p68_abs_over_sigma", b.p68_abs_over_sigma);
          }
          j.endObject();
        }
        j.endArray();
      }
      for (const auto& [name, table] : {std::pair<const char*, const MissTally::Table*>{"misses_stixel_only", &misses.stixelOnly()},
                                        {"misses_stixel_snv", &misses.stixelSnv()}}) {
        j.key(name);
        j.beginObject();
        for (const auto& [cause, by_class] : *table) {
          j.key(missCauseKey(cause));
          j.beginObject();
          for (const auto& [type, n] : by_class) j.field(type, n);
          j.endObject();
        }
        j.endObject();
      }
      j.key("stage_ms");
      j.beginObject();
      for (const auto& [s, v] : stage_ms) j.field(s, mean(v));
      j.endObject();
      if (!poses.empty()) {
        j.key("pose_error");
        j.beginObject();
        j.field("frames", static_cast<int>(pitch_err.size()));
        j.field("pitch_deg_p95", percentile(pitch_err, 0.95));
        j.field("roll_deg_p95", percentile(roll_err, 0.95));
        j.field("height_m_p95", percentile(height_err, 0.95));
        j.field("height_m_mean", mean(height_err));
        j.endObject();
      }
      j.endObject();
      std::printf("%s\n", j.str().c_str());
      return 0;
    }
    std::printf("frames evaluated: %d (%d without labels), IoU > %.2f%s%s%s\n", frames, unlabelled,
                o.params.min_iou,
                farDetectionsIgnored(o.params)     ? ", distance-limited (objects and unmatched detections)"
                : o.params.max_distance_m < 1e8    ? ", distance-limited (objects only)"
                                                   : "",
                o.params.visible_only ? ", occlusion < 2 and truncation < 0.5 only" : "",
                difficultyText(o.params).c_str());
    std::printf("%-14s %8s %6s %6s %6s %10s %8s %6s\n", "", "objects", "TP", "FP", "FN", "precision", "recall", "F1");
    for (const auto& [name, c] : {std::pair<const char*, EvalCounts>{"stixel only", all}, {"stixel + SNV", kept}})
      std::printf("%-14s %8d %6d %6d %6d %10.3f %8.3f %6.3f\n", name, c.objects, c.tp, c.fp, c.fn,
                  c.precision(), c.recall(), c.f1());
    std::printf("%s", misses.format().c_str());
    if (depth.count()) std::printf("%s", depth.format().c_str());
    std::printf("mean ms per frame:");
    for (const auto& [s, v] : stage_ms) std::printf(" %s %.2f", s.c_str(), mean(v));
    std::printf("\n");
    if (!poses.empty())
      std::printf("pose error (95th percentile over %zu frames): pitch %.3f deg, roll %.3f deg, height %.3f m\n",
                  pitch_err.size(), percentile(pitch_err, 0.95), percentile(roll_err, 0.95),
                  percentile(height_err, 0.95));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_eval_detections: %s\n", e.what());
    return 2;
  }
}
