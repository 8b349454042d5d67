// Offline detection quality: the reference table of the NERV method, computed
// in-process on a dataset folder, for fast tuning.
//
//   build/bin/bench_detection --data DIR [--labels DIR] [--max-distance M] [--frames N]
//       [--config FILE] [--set section.key=value ...] [--cache DIR] [--visible]
//       [--extrinsics FILE] [--overlay DIR] [--per-frame] [--stixels] [--quiet]
//       [--difficulty easy|moderate|hard] [--true-disparity | --oracle MODE]
//       [--gray-offset O]
//
// Per frame: disparity (the stereo_matcher's library and defaults, cached
// as 16-bit PNG under --cache, default /tmp/nerv_bench_cache) ->
// stixel::estimateStixels (with the previous frame's SNV pose as prior, as the
// stixel service does) -> snv::SnvExtrinsicEstimator::process ->
// validator::validate. Then:
//   - the table of tools/nerv run / nerv_eval_detections: objects, TP, FP, FN,
//     precision, recall, F1 for every hypothesis (stixel only) and for the kept
//     ones (stixel + SNV), same matcher (tools/lib/detection_eval.hpp);
//   - recall per class; per-object coverage over the frames (synthetic labels
//     with 3D positions: objects are followed from frame to frame);
//   - false positives and lost true positives by verdict and reason, and false
//     positives by where they lie (background, or which object: missed, found
//     by another box, or ignored as too far / hidden);
//   - hypotheses lying mostly (> 50 %) inside DIR/trap_mask and how many survive;
//   - depth (z and nearest_z) of the kept true positives against their labels'
//     nearest depth (tools/lib/distance_accuracy.hpp), per 10 m band;
//   - ground-model and SNV pose against DIR/extrinsics.txt (or --extrinsics);
//   - ms per frame of each stage.
// --visible counts only labels with occlusion < 2 and truncation < 0.5 (others
// are ignored: neither hit nor miss). --difficulty applies a KITTI benchmark
// difficulty as nerv_eval_detections does (tools/lib/detection_eval.hpp).
// --max-distance M ignores the labels
// farther than M and the hypotheses farther than M (z_m) that match no counted
// label (tools/lib/detection_eval.hpp); --count-far-detections counts those
// hypotheses as false positives, as before 2026-12-02's sixth session. --set overrides a config key, e.g.
// --set validator.max_error_fraction=0.5 (repeatable). --true-disparity feeds
// the ground truth (DIR/disp_occ_0) instead of the matcher's disparity: an
// oracle for what the matcher costs; --oracle MODE takes away one kind of the
// matcher's errors only (withOracle below). --per-frame lists every hypothesis and
// miss, and for each false positive the label it overlaps most. --overlay DIR
// writes DIR/<frame>.png (boxes over the left image) and DIR/<frame>_disparity.png
// (the disparity the stages saw, uint16 in 1/256 px as on the wire, 0 = invalid).
// --gray-offset O (0 <= O < 1) matches on floor(luma + O) of the color images
// instead of the decoder's gray (tools/lib/gray_requantize.hpp): inputs within
// one gray level of it; the spread of a figure over several offsets is its
// noise band (tools/nerv eval band).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "config.hpp"
#include "dataset.hpp"
#include "detection_eval.hpp"
#include "gray_requantize.hpp"
#include "distance_accuracy.hpp"
#include "kitti_labels.hpp"
#include "message_convert.hpp"
#include "miss_causes.hpp"
#include "pipeline_keys.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "validator.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::string data, labels, config, cache = "/tmp/nerv_bench_cache", extrinsics, overlay, difficulty;
  std::vector<std::pair<std::string, std::string>> sets;
  float max_distance_m = 1e9f;
  bool count_far_detections = false;  // unmatched detections beyond max_distance_m are false positives
  int frames = 0;
  bool visible = false, per_frame = false, quiet = false, dump_stixels = false;
  std::set<std::string> classes;  // --classes: count only these label types (others are ignored both ways)
  std::string oracle;  // "", truth, truth-at-valid, no-near-outliers, no-far-outliers, no-outliers
  double gray_offset = -1;  // --gray-offset: >= 0 requantizes the color images' luma (gray_requantize.hpp)
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr, "bench_detection: %s\n", why.c_str());
  std::fprintf(stderr,
               "usage: bench_detection --data DIR [--labels DIR] [--max-distance M] [--frames N]\n"
               "       [--config FILE] [--set section.key=value] [--cache DIR] [--visible] [--count-far-detections]\n"
               "       [--extrinsics FILE] [--overlay DIR] [--per-frame] [--stixels] [--quiet]\n"
               "       [--difficulty easy|moderate|hard] [--classes Car,Pedestrian,...]\n"
               "       [--true-disparity | --oracle MODE] [--gray-offset O]\n");
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage("flag " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--data") o.data = value();
    else if (a == "--labels") o.labels = value();
    else if (a == "--max-distance") o.max_distance_m = std::stof(value());
    else if (a == "--count-far-detections") o.count_far_detections = true;
    else if (a == "--frames") o.frames = std::stoi(value());
    else if (a == "--config") o.config = value();
    else if (a == "--cache") o.cache = value();
    else if (a == "--extrinsics") o.extrinsics = value();
    else if (a == "--overlay") o.overlay = value();
    else if (a == "--visible") o.visible = true;
    else if (a == "--difficulty") o.difficulty = value();
    else if (a == "--classes") {
      std::stringstream list(value());
      for (std::string c; std::getline(list, c, ',');)
        if (!c.empty()) o.classes.insert(c);
      if (o.classes.empty()) usage("--classes wants a comma-separated list of label types");
    }
    else if (a == "--per-frame") o.per_frame = true;
    else if (a == "--stixels") o.dump_stixels = true;
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--true-disparity") o.oracle = "truth";
    else if (a == "--gray-offset") {
      const std::string v = value();
      char* end = nullptr;
      o.gray_offset = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(o.gray_offset >= 0 && o.gray_offset < 1))
        usage("--gray-offset wants a number in [0, 1), got '" + v + "'");
    }
    else if (a == "--oracle") {
      o.oracle = value();
      if (o.oracle != "truth" && o.oracle != "truth-at-valid" && o.oracle != "no-near-outliers" &&
          o.oracle != "no-far-outliers" && o.oracle != "no-outliers" && o.oracle != "true-inliers")
        usage("--oracle wants truth, truth-at-valid, true-inliers, no-near-outliers, no-far-outliers or no-outliers, got " +
              o.oracle);
    }
    else if (a == "--set") {
      const std::string kv = value();
      const size_t eq = kv.find('=');
      if (eq == std::string::npos || kv.find('.') > eq) usage("--set wants section.key=value, got " + kv);
      o.sets.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else usage("unknown flag '" + a + "'");
  }
  if (o.data.empty()) usage("--data DIR is required");
  if (o.gray_offset >= 0 && o.oracle == "truth") usage("--gray-offset changes the matcher's input; --true-disparity uses none");
  if (o.labels.empty() && fs::is_directory(o.data + "/label_2")) o.labels = o.data + "/label_2";
  if (o.extrinsics.empty() && fs::exists(o.data + "/extrinsics.txt")) o.extrinsics = o.data + "/extrinsics.txt";
  return o;
}

struct AllParams {
  stereo::Params stereo;
  stixel::Params stixel;
  float min_prior_confidence = 0.3f;
  snv::Params snv;
  validator::Params validator;
};

AllParams loadParams(const Options& o) {
  YAML::Node root = o.config.empty() ? YAML::Node(YAML::NodeType::Map) : loadConfigFile(o.config);
  for (const auto& [path, value] : o.sets) {
    const size_t dot = path.find('.');
    root[path.substr(0, dot)][path.substr(dot + 1)] = YAML::Load(value);
  }
  AllParams p;
  ConfigSection top(root, "");
  allowPipelineTopLevelKeys(top);
  {
    ConfigSection s = top.section("stereo_matcher");
    p.stereo = stereo::readParams(s);
    allowServiceOnlyKeys(s, "stereo_matcher");
    s.finish();
  }
  {
    ConfigSection s = top.section("stixel");
    p.stixel = stixel::readParams(s);
    s.get("min_prior_confidence", p.min_prior_confidence, 0.0, 1.0);
    allowServiceOnlyKeys(s, "stixel");
    s.finish();
  }
  {
    ConfigSection s = top.section("snv_extrinsic");
    p.snv = snv::readParams(s);
    allowServiceOnlyKeys(s, "snv_extrinsic");
    s.finish();
  }
  {
    ConfigSection s = top.section("validator");
    p.validator = validator::readParams(s);
    allowServiceOnlyKeys(s, "validator");
    s.finish();
  }
  top.finish();
  return p;
}

// The disparity the stixel and snv_extrinsic services receive: the DISPARITY
// message's fixed point (1/256 px, common/message_convert), as uint16.
cv::Mat wireFixed(const cv::Mat& d) {
  disparity_t msg;
  encodeDisparity(d, "u16le", msg);
  return cv::Mat(msg.height, msg.width, CV_16U, msg.data.data()).clone();
}

// Disparity of one frame as the pipeline's later stages see it (wireFixed), from
// the cache when the same pair and matcher settings were computed by this same
// build before (every
// stereo::Params field but `threads` is in the key, stereo::describeParams: until
// 2026-12-02 the road band, BM and WLS fields were not, so a --set of them read
// stale entries). The
// cache holds the wire's uint16 as PNG, so cached and fresh runs are identical
// (an earlier cache of 1/16 px steps rounded nerv_sgm's finer subpixel values:
// up to 0.01 F1 apart from a fresh run; its files have other names).
// This program's own file (size and time) is in the key too: the matcher's code
// is linked into it, so a change to the code that leaves Params alone (a new
// filter, a fix) gets fresh entries instead of reading the old code's maps
// (2026-12-05: the default cache held maps of an earlier build, and urban 12
// scored 217 true positives against 221 from a fresh cache). Runs of one build
// with --set of the later stages still share it.
std::string programStamp() {
  static const std::string stamp = [] {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return std::string("unknown");
    const auto size = fs::file_size(self, ec);
    const auto time = fs::last_write_time(self, ec).time_since_epoch().count();
    return ec ? std::string("unknown") : std::to_string(size) + "@" + std::to_string(time);
  }();
  return stamp;
}

// The folder of this build's entries under the cache root, build-<hash of the
// stamp>. A build's maps are of no use to the next one, so the cache would grow
// by the sets' maps at every rebuild (100 MB for the nine synthetic sets); when
// a build's folder is made, all but the kKeptBuilds newest other build folders
// go. Files directly in the root are older caches' and are left alone.
std::string buildCacheDir(const std::string& root) {
  constexpr size_t kKeptBuilds = 2;
  const fs::path dir = fs::path(root) / ("build-" + std::to_string(std::hash<std::string>{}(programStamp())));
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return dir.string();
  std::vector<std::pair<fs::file_time_type, fs::path>> others;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (e.is_directory(ec) && e.path().filename().string().rfind("build-", 0) == 0)
      others.emplace_back(fs::last_write_time(e.path(), ec), e.path());
  std::sort(others.begin(), others.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = kKeptBuilds; i < others.size(); ++i) fs::remove_all(others[i].second, ec);
  fs::create_directories(dir, ec);
  return dir.string();
}

// The matcher's input: the decoder's gray, or with gray_offset >= 0 the color
// image's luma requantized at that offset.
cv::Mat matcherInput(const std::string& path, double gray_offset) {
  if (gray_offset < 0) return cv::imread(path, cv::IMREAD_GRAYSCALE);
  const cv::Mat color = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (color.empty()) return color;
  if (color.type() != CV_8UC3)
    throw std::runtime_error("--gray-offset needs 8-bit color images, " + path + " has " +
                             std::to_string(color.channels()) + " channel(s)");
  return requantizedGray(color, gray_offset);
}

// Raw views (a folder with raw_calib.yaml) are rectified as the stereo_matcher service
// rectifies them on ingest; the labels then refer to the rectified frame.
Rectifier& rectifier() {
  static Rectifier r;
  return r;
}

cv::Mat rectifiedLeft(const DatasetFrame& f, const cv::Mat& left) {
  return f.raw ? rectifier().rectifyLeft(*f.raw, left) : left;
}

cv::Mat disparityOf(const DatasetFrame& f, const stereo::Params& sp, stereo::StereoMatcher& m,
                    const std::string& cache_dir, double gray_offset, double& ms) {
  std::ostringstream key;
  key << fs::absolute(f.left_path).string() << '|' << fs::last_write_time(f.left_path).time_since_epoch().count()
      << '|' << stereo::describeParams(sp) << "|wire" << kDisparityScale << "|build " << programStamp();
  if (gray_offset >= 0) key << "|gray-offset " << gray_offset;
  const std::string path = cache_dir + "/" + std::to_string(std::hash<std::string>{}(key.str())) + ".png";
  ms = 0;
  cv::Mat fixed;
  if (fs::exists(path)) fixed = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (fixed.empty() || fixed.type() != CV_16U) {
    cv::Mat left = matcherInput(f.left_path, gray_offset);
    cv::Mat right = matcherInput(f.right_path, gray_offset);
    if (left.empty() || right.empty()) throw std::runtime_error("cannot read " + f.left_path);
    if (f.raw) {
      cv::Mat left_rect, right_rect;
      rectifier().rectify(*f.raw, left, right, left_rect, right_rect);
      left = left_rect;
      right = right_rect;
    }
    cv::Mat d;
    const auto t0 = std::chrono::steady_clock::now();
    m.compute(left, right, d);
    ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    fixed = wireFixed(d);
    fs::create_directories(cache_dir);
    cv::imwrite(path, fixed);
  }
  cv::Mat d;
  fixed.convertTo(d, CV_32F, 1.0 / kDisparityScale);
  return d;
}

// The ground-truth disparity (disp_occ_0, KITTI's uint16 in 1/256 px, 0 = no
// ground truth) through the wire's fixed point, in place of the matcher: an
// oracle that separates what the matcher costs from what the later stages cost.
cv::Mat trueDisparityOf(const DatasetFrame& f) {
  if (f.disp_gt_path.empty()) throw std::runtime_error("--true-disparity: frame " + f.name + " has no disp_occ_0");
  const std::string& path = f.disp_gt_path;
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty() || raw.type() != CV_16U) throw std::runtime_error("cannot read 16-bit " + path);
  cv::Mat d;
  raw.convertTo(d, CV_32F, 1.0 / 256);
  d.setTo(-1.f, raw == 0);
  cv::Mat out;
  wireFixed(d).convertTo(out, CV_32F, 1.0 / kDisparityScale);
  return out;
}

// The matcher's disparity with one kind of its errors taken away by the
// ground truth (both valid and more than 1 px apart is an outlier):
// "truth-at-valid" keeps the matcher's valid pixels but gives them the true
// value; "true-inliers" gives the true value to the pixels within 1 px of it
// (the matcher's subpixel noise) and leaves the outliers; "no-near-outliers" invalidates pixels read nearer than the truth
// (fattening, smear into textureless background), "no-far-outliers" those read
// farther (reflections, background bleeding into thin objects), "no-outliers"
// both. Which of the matcher's errors cost the later stages what.
cv::Mat withOracle(cv::Mat disp, const cv::Mat& truth, const std::string& mode) {
  for (int v = 0; v < disp.rows; ++v) {
    float* d = disp.ptr<float>(v);
    const float* g = truth.ptr<float>(v);
    for (int u = 0; u < disp.cols; ++u) {
      const bool both = d[u] > 0 && g[u] > 0;
      if (mode == "truth-at-valid") d[u] = d[u] > 0 ? std::max(g[u], 0.f) : 0.f;
      else if (mode == "true-inliers") { if (both && std::abs(d[u] - g[u]) <= 1.0f) d[u] = g[u]; }
      else if (both && d[u] - g[u] > 1.0f && mode != "no-far-outliers") d[u] = 0;
      else if (both && g[u] - d[u] > 1.0f && mode != "no-near-outliers") d[u] = 0;
    }
  }
  return disp;
}

struct TruePose {
  float pitch = 0, roll = 0, height = 0;
};

std::map<long, TruePose> readExtrinsics(const std::string& path) {
  std::map<long, TruePose> poses;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string frame;
    TruePose p;
    if (line.empty() || line[0] == '#' || !(s >> frame >> p.pitch >> p.roll >> p.height)) continue;
    try {
      poses[std::stol(frame)] = p;
    } catch (...) {
    }
  }
  return poses;
}

EvalBox boxOf(const Hypothesis& h) {
  EvalBox b = detectionBox(h.box.x, h.box.y, h.box.w, h.box.h);
  b.z = h.z_m;
  return b;
}

// Per-frame listing: true positive, false positive, or ignored (DontCare,
// an invisible or too far label).
const char* outcomeTag(const DetectionMatch& m) {
  return m.outcome == MatchOutcome::TruePositive ? "tp  " : m.outcome == MatchOutcome::FalsePositive ? "fp  " : "ign ";
}

// "error: height 0.12 m below 0.20 m" -> "error: height below"; numbers dropped.
std::string reasonKind(const Verdict& v) {
  std::string r = v.reason;
  if (r.rfind("unvalidated: ", 0) == 0) r = r.substr(13);
  std::string out;
  std::istringstream s(r);
  for (std::string w; s >> w && out.size() < 40;) {
    if (std::isdigit(static_cast<unsigned char>(w[0])) || w[0] == '(' || w[0] == '<') continue;
    if (w.back() == ',' || w.back() == ':') w.pop_back();
    out += (out.empty() ? "" : " ") + w;
    if (w == "normals" || w == "below" || w == "above" || w == "hypothesis") break;
  }
  return v.label + (out.empty() ? "" : ": " + out);
}

// Follows labelled objects across frames (synthetic labels carry 3D size and
// position): same type and size, nearest base position within a gate.
struct Track {
  std::string type;
  float h, w, l, x, z;
  int last_frame;
  int frames = 0, covered = 0, kept_covered = 0;
  float min_z = 1e9f, max_z = 0;
  std::string pattern{};  // one character per frame of the track: '#' covered, '.' not
};

struct Stat {
  double sum = 0, max = 0;
  int n = 0;
  void add(double v) {
    sum += v;
    max = std::max(max, std::abs(v));
    ++n;
  }
  double mean() const { return n ? sum / n : 0; }
};

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const AllParams P = loadParams(o);
    Dataset ds = openDataset(o.data);
    if (o.frames > 0 && static_cast<int>(ds.frames.size()) > o.frames) ds.frames.resize(o.frames);
    const std::map<long, TruePose> truth = o.extrinsics.empty() ? std::map<long, TruePose>{} : readExtrinsics(o.extrinsics);
    const bool have_traps = fs::is_directory(o.data + "/trap_mask");
    if (!o.overlay.empty()) fs::create_directories(o.overlay);

    const std::string cache_dir = buildCacheDir(o.cache);  // made with the root when missing
    auto matcher = stereo::StereoMatcher::create(P.stereo);
    snv::SnvExtrinsicEstimator snv_est(P.snv);
    stixel::GroundPrior prior;

    EvalParams ep;
    ep.max_distance_m = o.max_distance_m;
    ep.visible_only = o.visible;
    if (!o.difficulty.empty())
      if (const std::string why = setKittiDifficulty(o.difficulty, ep); !why.empty()) throw std::runtime_error(why);
    ep.limit_detections = !o.count_far_detections;
    ep.classes = o.classes;
    EvalCounts all, kept;
    DepthErrors depth_kept;  // kept true positives: the label's nearest depth vs the hypothesis' depths
    std::map<std::string, int> cls_objects, cls_tp_all, cls_tp_kept;
    std::map<std::string, int> fp_removed, fp_kept, tp_lost, tp_kept, fp_where;
    MissTally misses;  // why objects were missed (miss_causes.hpp)
    std::map<std::string, int> verdicts;
    int trap_hyps = 0, trap_removed = 0, frames_done = 0, frames_no_ground = 0;
    std::vector<double> ms_matcher, ms_stixel, ms_snv, ms_val, observed_share, unobserved_strips;
    size_t strips = 0;  // free-space strips across the image (observed_free_space.hpp)
    Stat ground_h, ground_p, snv_h, snv_p, snv_ih, snv_ip;
    std::vector<Track> tracks;
    int num_hyps = 0;

    for (size_t fi = 0; fi < ds.frames.size(); ++fi) {
      const DatasetFrame& f = ds.frames[fi];
      double t_matcher = 0;
      const cv::Mat disp = o.oracle == "truth" ? trueDisparityOf(f)
                           : o.oracle.empty() ? disparityOf(f, P.stereo, *matcher, cache_dir, o.gray_offset, t_matcher)
                                              : withOracle(disparityOf(f, P.stereo, *matcher, cache_dir, o.gray_offset, t_matcher),
                                                           trueDisparityOf(f), o.oracle);
      if (t_matcher > 0) ms_matcher.push_back(t_matcher);

      auto t0 = std::chrono::steady_clock::now();
      const stixel::StixelResult st = stixel::estimateStixels(disp, f.camera, P.stixel, prior);
      auto t1 = std::chrono::steady_clock::now();
      const snv::SnvResult sn = snv_est.process(disp, f.camera, st.hypotheses, st.ground);
      auto t2 = std::chrono::steady_clock::now();
      const std::vector<Verdict> vs = validator::validate(st.hypotheses, sn.rois, P.validator);
      auto t3 = std::chrono::steady_clock::now();
      ms_stixel.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      observed_share.push_back(st.observed.observed_share);
      unobserved_strips.push_back(st.observed.num_unobserved);
      strips = st.observed.observed.size();
      ms_snv.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
      ms_val.push_back(std::chrono::duration<double, std::milli>(t3 - t2).count());
      // The stixel service takes the latest EXTRINSICS as its prior.
      if (sn.pose.valid && sn.pose.confidence >= P.min_prior_confidence)
        prior = {true, sn.pose.pitch_deg, sn.pose.roll_deg, sn.pose.height_m};
      ++frames_done;
      num_hyps += static_cast<int>(st.hypotheses.size());
      if (!st.ground.valid) ++frames_no_ground;
      for (const Verdict& v : vs) ++verdicts[v.label + (v.kept ? " (kept)" : " (removed)")];

      long frame_no = -1;
      try {
        frame_no = std::stol(f.name);
      } catch (...) {
      }
      if (auto it = truth.find(frame_no); it != truth.end()) {
        if (st.ground.valid) {
          ground_h.add(st.ground.height_m - it->second.height);
          ground_p.add(st.ground.pitch_deg - it->second.pitch);
        }
        if (sn.pose.valid) {
          snv_h.add(sn.pose.height_m - it->second.height);
          snv_p.add(sn.pose.pitch_deg - it->second.pitch);
          snv_ih.add(sn.pose.instant_height_m - it->second.height);
          snv_ip.add(sn.pose.instant_pitch_deg - it->second.pitch);
        }
      } else if (truth.empty() && st.ground.valid && !o.quiet && o.per_frame) {
        std::printf("frame %s ground height %.3f m pitch %.2f deg, snv %.3f m %.2f deg\n", f.name.c_str(),
                    st.ground.height_m, st.ground.pitch_deg, sn.pose.height_m, sn.pose.pitch_deg);
      }

      // Trap hypotheses: most of the box inside the trap mask.
      std::vector<bool> in_trap(st.hypotheses.size(), false);
      if (have_traps) {
        const cv::Mat mask = cv::imread(o.data + "/trap_mask/" + f.name + ".png", cv::IMREAD_GRAYSCALE);
        if (!mask.empty()) {
          for (size_t i = 0; i < st.hypotheses.size(); ++i) {
            const Box& b = st.hypotheses[i].box;
            const cv::Rect r = cv::Rect(b.x, b.y, b.w, b.h) & cv::Rect(0, 0, mask.cols, mask.rows);
            if (r.area() <= 0) continue;
            in_trap[i] = cv::countNonZero(mask(r)) > 0.5 * r.area();
            if (in_trap[i]) {
              ++trap_hyps;
              trap_removed += vs[i].kept ? 0 : 1;
            }
          }
        }
      }

      if (o.labels.empty()) continue;
      const std::string label_path = o.labels + "/" + f.name + ".txt";
      if (!fs::exists(label_path)) continue;
      const std::vector<KittiLabel> labels = readKittiLabels(label_path);
      // Hidden objects (--visible: ep.visible_only) count neither way.
      auto hidden = [&](const KittiLabel& l) {
        return l.type != "DontCare" && ((ep.visible_only && isHidden(l)) || isBeyondDifficulty(l, ep));
      };

      std::vector<EvalBox> hyps, val;
      std::vector<size_t> val_index;
      for (size_t i = 0; i < st.hypotheses.size(); ++i) {
        EvalBox b = boxOf(st.hypotheses[i]);
        hyps.push_back(b);
        if (vs[i].kept) {
          b.score = vs[i].score;
          val.push_back(b);
          val_index.push_back(i);
        }
      }
      const auto out_all = matchDetections(hyps, labels, ep);
      const auto out_kept = matchDetections(val, labels, ep);
      const EvalCounts c_all = countMatches(out_all, labels, ep), c_kept = countMatches(out_kept, labels, ep);
      all.add(c_all);
      kept.add(c_kept);

      for (size_t i = 0; i < labels.size(); ++i) {
        const auto& l = labels[i];
        if (!isCounted(l, ep)) continue;
        ++cls_objects[l.type];
      }
      std::vector<bool> kept_tp_label(labels.size(), false);
      for (size_t k = 0; k < val.size(); ++k)
        if (out_kept[k].outcome == MatchOutcome::TruePositive) {
          const int li = out_kept[k].label;
          ++cls_tp_kept[labels[li].type], kept_tp_label[li] = true;
          const Hypothesis& h = st.hypotheses[val_index[k]];
          depth_kept.add(labels[li], h.z_m, h.nearest_z_m, h.nearest_z_sigma_m);
        }
      for (size_t i = 0; i < hyps.size(); ++i) {
        if (out_all[i].outcome == MatchOutcome::TruePositive) {
          ++cls_tp_all[labels[out_all[i].label].type];
          ++(vs[i].kept ? tp_kept : tp_lost)[reasonKind(vs[i])];
        } else if (out_all[i].outcome == MatchOutcome::FalsePositive) {
          (vs[i].kept ? fp_kept : fp_removed)[reasonKind(vs[i])]++;
          // Where the false positive lies: on a labelled object (split, merge,
          // loose box) or on background / a trap.
          float best = 0, cover = 0;
          int best_label = -1;
          for (size_t li = 0; li < labels.size(); ++li) {
            const auto& l = labels[li];
            if (l.type == "DontCare") continue;
            const float o = iou(hyps[i], labelBox(l));
            if (o > best) best = o, best_label = int(li);
            cover = std::max(cover, intersection(hyps[i], labelBox(l)) / std::max(1.f, area(hyps[i])));
          }
          std::string where = in_trap[i] ? "trap" : best > 0.2f ? "object, IoU 0.2-0.5" : cover > 0.5f
                                                     ? "part of an object" : best > 0.0f ? "touches an object"
                                                                                          : "background";
          // Which object the box lies on (the label of highest IoU): one no box
          // found, one another box found (a second box), or one the count
          // ignores (beyond the distance, hidden, another class).
          if (!in_trap[i] && (best > 0.2f || cover > 0.5f) && best_label >= 0) {
            const KittiLabel& l = labels[best_label];
            const bool found = std::any_of(out_all.begin(), out_all.end(),
                                           [&](const DetectionMatch& m) { return m.label == best_label; });
            where += hidden(l) ? " (hidden object, ignored)"
                     : l.z > ep.max_distance_m ? " (object beyond the distance, ignored)"
                     : !ep.classes.empty() && !ep.classes.count(l.type) ? " (other class, ignored)"
                     : found ? " (second box on a found object)" : " (missed object)";
          }
          ++fp_where[where + (vs[i].kept ? " / kept" : " / removed")];
        }
      }

      // Why each counted object was missed, from the boxes near it (by their nearest part's depth).
      std::vector<float> hyp_near(hyps.size());
      for (size_t k = 0; k < hyps.size(); ++k) hyp_near[k] = st.hypotheses[k].nearest_z_m;
      const std::vector<std::string> cause_of = misses.addFrame(labels, ep, hyps, hyp_near, out_all, out_kept);

      // Per-object coverage (labels with a 3D position only).
      for (size_t i = 0; i < labels.size(); ++i) {
        const auto& l = labels[i];
        if (l.type == "DontCare" || l.x < -999 || l.z <= 0 || l.z > ep.max_distance_m || hidden(l)) continue;
        if (!ep.classes.empty() && !ep.classes.count(l.type)) continue;
        int ti = -1;
        float bestd = 1e9f;
        for (size_t t = 0; t < tracks.size(); ++t) {
          const Track& tr = tracks[t];
          if (tr.type != l.type || tr.last_frame != static_cast<int>(fi) - 1) continue;
          if (std::abs(tr.h - l.h) > 0.02f || std::abs(tr.w - l.w) > 0.02f || std::abs(tr.l - l.l) > 0.02f) continue;
          const float dx = std::abs(tr.x - l.x), dz = std::abs(tr.z - l.z);
          if (dx < 1.5f && dz < 6.0f && dx + dz < bestd) bestd = dx + dz, ti = static_cast<int>(t);
        }
        if (ti < 0) {
          tracks.push_back({l.type, l.h, l.w, l.l, l.x, l.z, static_cast<int>(fi)});
          ti = static_cast<int>(tracks.size()) - 1;
        }
        Track& tr = tracks[ti];
        tr.x = l.x, tr.z = l.z, tr.last_frame = static_cast<int>(fi);
        ++tr.frames;
        tr.min_z = std::min(tr.min_z, l.z);
        tr.max_z = std::max(tr.max_z, l.z);
        bool cov = false;
        for (const auto& h : hyps) cov = cov || iou(h, labelBox(l)) > ep.min_iou;
        tr.covered += cov ? 1 : 0;
        tr.pattern += cov ? '#' : '.';
        tr.kept_covered += kept_tp_label[i] ? 1 : 0;
      }

      if (o.dump_stixels) {
        std::printf("frame %s stixels (u width top bottom disparity depth):\n", f.name.c_str());
        for (const Stixel& s : st.stixels)
          std::printf("  st %4d %2d %3d %3d %6.2f %6.2f\n", s.u, s.width, s.top_row, s.bottom_row, s.disparity, s.depth_m);
      }
      if (o.per_frame) {
        std::printf("frame %s: %zu hyps, all TP %d FP %d FN %d | kept TP %d FP %d FN %d\n", f.name.c_str(),
                    hyps.size(), c_all.tp, c_all.fp, c_all.fn, c_kept.tp, c_kept.fp, c_kept.fn);
        // Misses: each counted label no hypothesis matched, with the closest box.
        std::vector<bool> hit(labels.size(), false);
        for (size_t i = 0; i < hyps.size(); ++i)
          if (out_all[i].outcome == MatchOutcome::TruePositive) hit[out_all[i].label] = true;
        for (size_t i = 0; i < labels.size(); ++i) {
          const auto& l = labels[i];
          if (hit[i] || !isCounted(l, ep)) continue;
          int best = -1;
          float bi = 0;
          for (size_t k = 0; k < hyps.size(); ++k)
            if (iou(hyps[k], labelBox(l)) > bi) bi = iou(hyps[k], labelBox(l)), best = int(k);
          std::printf("  miss %-10s occ %d z %5.1f box %4.0f,%3.0f-%4.0f,%3.0f", l.type.c_str(), l.occluded, l.z,
                      l.x1, l.y1, l.x2, l.y2);
          if (best >= 0)
            std::printf("  best hyp %d IoU %.2f box %4.0f,%3.0f-%4.0f,%3.0f z %.1f %s", best, bi, hyps[best].x1,
                        hyps[best].y1, hyps[best].x2, hyps[best].y2, st.hypotheses[best].z_m, vs[best].label.c_str());
          if (!cause_of[i].empty()) std::printf(" | %s", cause_of[i].c_str());
          std::printf("\n");
        }
        for (size_t k = 0; k < hyps.size(); ++k) {
          const NormalStats& ns = sn.rois[k];
          std::printf("  %s hyp %d box %4.0f,%3.0f-%4.0f,%3.0f z %.1f h %.2f w %.2f | n %d dens %.2f g %.2f o %.2f e %.2f "
                      "elev %.0f tilt %.0f | %s%s\n", outcomeTag(out_all[k]), int(k), hyps[k].x1,
                      hyps[k].y1, hyps[k].x2, hyps[k].y2, st.hypotheses[k].z_m, st.hypotheses[k].height_m,
                      st.hypotheses[k].width_m, ns.num_normals, ns.density, ns.ground_fraction, ns.object_fraction,
                      ns.error_fraction, ns.pitch_deg, ns.tilt_from_ground_deg, vs[k].label.c_str(),
                      vs[k].kept ? "" : (" (removed: " + vs[k].reason + ")").c_str());
          if (out_all[k].outcome == MatchOutcome::FalsePositive) {  // a badly fitting box on an object, or nothing there
            int bl = -1;
            float bli = 0;
            for (size_t i = 0; i < labels.size(); ++i)
              if (labels[i].type != "DontCare" && iou(hyps[k], labelBox(labels[i])) > bli)
                bli = iou(hyps[k], labelBox(labels[i])), bl = int(i);
            if (bl >= 0)
              std::printf("       best label %s IoU %.2f box %4.0f,%3.0f-%4.0f,%3.0f z %.1f%s\n", labels[bl].type.c_str(), bli,
                          labels[bl].x1, labels[bl].y1, labels[bl].x2, labels[bl].y2, labels[bl].z,
                          hit[bl] ? " (matched by another)" : "");
            else std::printf("       best label none\n");
          }
        }
      }

      if (!o.overlay.empty()) {
        cv::Mat img = rectifiedLeft(f, cv::imread(f.left_path, cv::IMREAD_COLOR));
        for (const auto& l : labels) {
          const cv::Scalar col = l.type == "DontCare" ? cv::Scalar(128, 128, 128) : cv::Scalar(255, 0, 0);
          cv::rectangle(img, cv::Point(int(l.x1), int(l.y1)), cv::Point(int(l.x2), int(l.y2)), col, 1);
        }
        // Stixels: a thin bar each at its foot-to-top rows, hue by depth (red near, blue 40 m+).
        for (const Stixel& s : st.stixels) {
          const double t = std::min(1.0, s.depth_m / 40.0);
          const cv::Scalar col(255 * t, 64, 255 * (1 - t));
          cv::line(img, cv::Point(s.u + s.width / 2, s.top_row), cv::Point(s.u + s.width / 2, s.bottom_row), col, 1);
        }
        for (size_t i = 0; i < hyps.size(); ++i) {
          const Box& b = st.hypotheses[i].box;
          const cv::Scalar col = out_all[i].outcome == MatchOutcome::TruePositive ? cv::Scalar(0, 255, 0)
                                 : out_all[i].outcome == MatchOutcome::FalsePositive ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 255, 255);
          cv::rectangle(img, cv::Rect(b.x, b.y, b.w, b.h), col, vs[i].kept ? 2 : 1);
          cv::putText(img, std::to_string(i) + (vs[i].kept ? "" : "x") + vs[i].label.substr(0, 1),
                      cv::Point(b.x, b.y - 2), cv::FONT_HERSHEY_PLAIN, 0.8, col, 1);
        }
        cv::imwrite(o.overlay + "/" + f.name + ".png", img);
        // The disparity the stages saw, as the wire carries it (uint16, 1/256 px, 0 = invalid).
        cv::imwrite(o.overlay + "/" + f.name + "_disparity.png", wireFixed(disp));
      }
    }

    auto median = [](std::vector<double> v) {
      if (v.empty()) return 0.0;
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    auto mean = [](const std::vector<double>& v) {
      double s = 0;
      for (double x : v) s += x;
      return v.empty() ? 0.0 : s / v.size();
    };

    std::printf("data %s: %d frames, %d hypotheses, %d frames without ground\n", o.data.c_str(), frames_done,
                num_hyps, frames_no_ground);
    // An oracle's table must not pass for the matcher's.
    if (o.oracle == "truth") std::printf("disparity: the rendered disparity (--true-disparity), not the matcher's\n");
    else if (!o.oracle.empty()) std::printf("disparity: the matcher's with the oracle '%s' applied\n", o.oracle.c_str());
    if (!o.labels.empty()) {
      std::printf("IoU > %.2f%s%s%s\n", ep.min_iou,
                  o.max_distance_m < 1e8 ? (", labels within " + std::to_string(int(o.max_distance_m)) + " m" +
                                             (o.count_far_detections ? " (all hypotheses counted)"
                                                                     : " (unmatched hypotheses beyond it ignored)")).c_str()
                                        : "",
                  o.visible ? ", occlusion < 2 and truncation < 0.5 only" : "", difficultyText(ep).c_str());
      if (!ep.classes.empty()) {
        std::printf("classes counted:");
        for (const std::string& c : ep.classes) std::printf(" %s", c.c_str());
        std::printf(" (boxes on other labelled objects count neither way)\n");
      }
      std::printf("%-14s %8s %6s %6s %6s %10s %8s %6s\n", "", "objects", "TP", "FP", "FN", "precision", "recall", "F1");
      for (const auto& [name, c] : {std::pair<const char*, EvalCounts>{"stixel only", all}, {"stixel + SNV", kept}})
        std::printf("%-14s %8d %6d %6d %6d %10.3f %8.3f %6.3f\n", name, c.objects, c.tp, c.fp, c.fn, c.precision(),
                    c.recall(), c.f1());
      const int removed_fp = all.fp - kept.fp;
      std::printf("SNV: precision %+.1f points, recall %+.1f points, %d of %d FPs removed (%.0f %%), %d TPs lost\n",
                  100 * (kept.precision() - all.precision()), 100 * (kept.recall() - all.recall()), removed_fp,
                  all.fp, all.fp ? 100.0 * removed_fp / all.fp : 0.0, all.tp - kept.tp);
      std::printf("recall per class (stixel only / + SNV):");
      for (const auto& [t, n] : cls_objects)
        std::printf("  %s %d/%d, %d/%d", t.c_str(), cls_tp_all[t], n, cls_tp_kept[t], n);
      std::printf("\n");
      auto dump = [](const char* title, const std::map<std::string, int>& m) {
        if (m.empty()) return;
        std::printf("%s\n", title);
        for (const auto& [k, n] : m) std::printf("  %5d  %s\n", n, k.c_str());
      };
      dump("false positives of stixel only, removed by SNV (verdict: reason):", fp_removed);
      dump("false positives kept by SNV (verdict):", fp_kept);
      dump("true positives lost by SNV (verdict: reason):", tp_lost);
      dump("true positives kept by SNV (verdict):", tp_kept);
      dump("false positives by location (stixel only):", fp_where);
      std::printf("%s", misses.format().c_str());
      if (depth_kept.count()) std::printf("%s", depth_kept.format().c_str());
    }
    std::printf("verdicts:");
    for (const auto& [k, n] : verdicts) std::printf("  %s %d", k.c_str(), n);
    std::printf("\n");
    if (have_traps)
      std::printf("trap hypotheses (> 50 %% of the box in trap_mask): %d, removed %d, kept %d\n", trap_hyps,
                  trap_removed, trap_hyps - trap_removed);
    if (!tracks.empty()) {
      int n = 0, ok = 0;
      std::vector<const Track*> bad;
      for (const Track& t : tracks) {
        if (t.frames == 0) continue;
        ++n;
        if (t.covered >= 0.95 * t.frames) ++ok;
        else bad.push_back(&t);
      }
      std::printf("per-object coverage (hypothesis IoU > 0.5) of %d objects%s: %d covered in >= 95 %% of their frames\n",
                  n, o.visible ? " (occlusion < 2, truncation < 0.5)" : "", ok);
      for (const Track* t : bad)
        std::printf("  %-10s %2d/%2d frames covered (kept TP %2d), z %.1f..%.1f m, x %.1f  %s\n", t->type.c_str(),
                    t->covered, t->frames, t->kept_covered, t->min_z, t->max_z, t->x, t->pattern.c_str());
    }
    if (!observed_share.empty()) {
      // Free or unseen (observed_free_space.hpp): what the STIXELS / DETECTIONS fields say.
      const auto [lo, hi] = std::minmax_element(unobserved_strips.begin(), unobserved_strips.end());
      std::printf("observed free space: share median %.3f (min %.3f), unobserved strips median %.0f (%.0f..%.0f) of %zu\n",
                  median(observed_share), *std::min_element(observed_share.begin(), observed_share.end()),
                  median(unobserved_strips), *lo, *hi, strips);
    }
    if (ground_h.n || snv_h.n)
      std::printf("pose vs extrinsics (mean / max |error|): ground model height %+.3f / %.3f m, pitch %+.3f / %.3f deg "
                  "(%d frames); SNV filtered height %+.3f / %.3f m, pitch %+.3f / %.3f deg; instant height %+.3f / "
                  "%.3f m, pitch %+.3f / %.3f deg (%d frames)\n",
                  ground_h.mean(), ground_h.max, ground_p.mean(), ground_p.max, ground_h.n, snv_h.mean(), snv_h.max,
                  snv_p.mean(), snv_p.max, snv_ih.mean(), snv_ih.max, snv_ip.mean(), snv_ip.max, snv_h.n);
    std::printf("ms per frame (median / mean): %s %.2f / %.2f (%zu computed, rest cached), stixel %.2f / %.2f, "
                "snv %.2f / %.2f, validator %.3f / %.3f\n",
                P.stereo.algorithm.c_str(), median(ms_matcher), mean(ms_matcher), ms_matcher.size(), median(ms_stixel), mean(ms_stixel),
                median(ms_snv), mean(ms_snv), median(ms_val), mean(ms_val));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_detection: %s\n", e.what());
    return 2;
  }
}
