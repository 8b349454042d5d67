#include "run_report.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "distance_accuracy.hpp"
#include "frame_evaluation.hpp"
#include "frame_grid.hpp"
#include "frame_name.hpp"
#include "frame_render.hpp"
#include "html_report.hpp"
#include "kitti_labels.hpp"
#include "log_summary.hpp"
#include "message_convert.hpp"
#include "miss_causes.hpp"
#include "pitch_distribution.hpp"
#include "svg_plot.hpp"

namespace nerv::viz {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// What the report needs of one frame, without pixels.
struct Row {
  int64_t seq = 0;
  std::string frame_id;
  bool has_stereo = false;
  bool has_ext = false, ext_valid = false;
  double pitch = kNaN, roll = kNaN, height = kNaN, ipitch = kNaN, iroll = kNaN, iheight = kNaN;
  double confidence = kNaN, entropy = kNaN;
  double ground_pitch = kNaN, ground_height = kNaN;
  int hypotheses = -1, kept = -1;
  double observed = kNaN, unobserved = kNaN;  // free space measured, strips unobserved [%] (DETECTIONS)
  double latency_ms = kNaN;
  std::map<std::string, double> stage_ms;
  bool labelled = false;
  int objects = 0;
  EvalCounts eval_all, eval_kept;
  double truth_pitch = kNaN, truth_roll = kNaN, truth_height = kNaN;
};

struct TruePose {
  double pitch, roll, height;
};

std::map<long, TruePose> readTruePoses(const std::string& path) {
  std::map<long, TruePose> poses;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string frame;
    TruePose p{};
    if (!(s >> frame >> p.pitch >> p.roll >> p.height)) continue;
    try {
      poses[std::stol(frame)] = p;
    } catch (...) {
    }
  }
  return poses;
}

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

double percentile(std::vector<double> v, double p) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += x, ++n;
  return n ? s / n : kNaN;
}

template <class F>
SvgSeries series(const std::vector<Row>& rows, const std::string& name, const std::string& color, F value) {
  SvgSeries s;
  s.name = name;
  s.color = color;
  for (const auto& r : rows) {
    s.x.push_back(static_cast<double>(r.seq));
    s.y.push_back(value(r));
  }
  return s;
}

bool anyFinite(const SvgSeries& s) {
  return std::any_of(s.y.begin(), s.y.end(), [](double y) { return std::isfinite(y); });
}

std::vector<uint8_t> jpeg(const cv::Mat& img, double scale) {
  cv::Mat small;
  cv::resize(img, small, {}, scale, scale, cv::INTER_AREA);
  std::vector<uint8_t> bytes;
  cv::imencode(".jpg", small, bytes, {cv::IMWRITE_JPEG_QUALITY, 85});
  return bytes;
}

const char* kStages[] = {"stereo_matcher", "stixel", "snv_extrinsic", "validator"};
const char* kStageColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd"};

}  // namespace

ReportResult writeRunReport(const std::string& log_path, const ReportOptions& options) {
  if (!std::filesystem::exists(log_path)) throw std::runtime_error("log " + log_path + " does not exist");
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (!std::filesystem::is_directory(options.out_dir))
    throw std::runtime_error("cannot make output folder " + options.out_dir);
  ReportResult result;

  std::string extrinsics_file = options.extrinsics_file;
  if (extrinsics_file.empty() && !options.labels_dir.empty()) {
    const auto guess = std::filesystem::path(options.labels_dir).lexically_normal().parent_path() / "extrinsics.txt";
    if (std::filesystem::exists(guess)) extrinsics_file = guess.string();
  }
  const auto true_poses = extrinsics_file.empty() ? std::map<long, TruePose>() : readTruePoses(extrinsics_file);

  // Pass 1: every frame without pixels.
  std::vector<Row> rows;
  int label_problems = 0;
  DepthErrors depth;  // kept true positives vs the labels' nearest depth
  MissTally misses;   // why labelled objects were missed (miss_causes.hpp)
  {
    LogFrameOptions read;
    read.keep_images = false;
    read.max_pending = 64;
    read.prefix = options.prefix;
    LogFrameReader reader(log_path, read);
    LogFrame f;
    while (reader.next(f)) {
      Row r;
      r.seq = f.seq;
      r.frame_id = f.frame_id;
      r.has_stereo = f.stereo.has_value();
      if (f.extrinsics) {
        const auto& e = *f.extrinsics;
        r.has_ext = true;
        r.ext_valid = e.valid;
        r.pitch = e.pitch_deg, r.roll = e.roll_deg, r.height = e.height_m;
        r.ipitch = e.instant_pitch_deg, r.iroll = e.instant_roll_deg, r.iheight = e.instant_height_m;
        r.confidence = e.confidence, r.entropy = e.entropy;
        r.stage_ms["snv_extrinsic"] = e.processing_ms;
      }
      if (f.stixels) {
        if (f.stixels->ground.valid) {
          r.ground_pitch = f.stixels->ground.pitch_deg;
          r.ground_height = f.stixels->ground.height_m;
        }
        r.stage_ms["stixel"] = f.stixels->processing_ms;
      }
      if (f.disparity) r.stage_ms["stereo_matcher"] = f.disparity->processing_ms;
      if (f.detections) {
        r.hypotheses = f.detections->num_detections;
        r.kept = f.detections->num_kept;
        if (f.detections->num_columns > 0) {
          r.observed = 100.0 * f.detections->observed_share;
          r.unobserved = 100.0 * f.detections->num_unobserved / f.detections->num_columns;
        }
        r.stage_ms["validator"] = f.detections->processing_ms;
        if (f.detections_log_utime >= 0) r.latency_ms = (f.detections_log_utime - f.detections->header.utime) / 1000.0;
      }
      const std::string name = frameName(f.frame_id);
      try {
        if (auto it = true_poses.find(std::stol(name)); it != true_poses.end()) {
          r.truth_pitch = it->second.pitch;
          r.truth_roll = it->second.roll;
          r.truth_height = it->second.height;
        }
      } catch (...) {
      }
      if (f.detections) {
        if (const std::string path = labelFileFor(options.labels_dir, f.frame_id); !path.empty()) {
          try {
            const auto labels = readKittiLabels(path);
            const FrameEvaluation e = evaluateDetections(*f.detections, labels, options.eval, depth, misses);
            r.eval_all = e.all;
            r.eval_kept = e.kept;
            r.objects = r.eval_all.objects;
            r.labelled = true;
          } catch (const std::exception&) {
            ++label_problems;
          }
        }
      }
      rows.push_back(std::move(r));
    }
    result.log = reader.stats();
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.seq < b.seq; });
  result.frames = static_cast<int>(rows.size());

  // Frames to look at closely: the histogram frame and the worst ones.
  int64_t hist_seq = options.histogram_seq;
  if (hist_seq < 0) {
    std::vector<int64_t> valid;
    for (const auto& r : rows)
      if (r.ext_valid && r.has_stereo) valid.push_back(r.seq);
    if (valid.empty())
      for (const auto& r : rows)
        if (r.has_stereo) valid.push_back(r.seq);
    if (!valid.empty()) hist_seq = valid[valid.size() / 2];
  }
  std::vector<const Row*> worst;
  for (const auto& r : rows)
    if (r.labelled && r.has_stereo && r.eval_kept.fp + r.eval_kept.fn > 0) worst.push_back(&r);
  std::sort(worst.begin(), worst.end(), [](const Row* a, const Row* b) {
    return a->eval_kept.fp + a->eval_kept.fn > b->eval_kept.fp + b->eval_kept.fn;
  });
  if (static_cast<int>(worst.size()) > options.worst_frames) worst.resize(std::max(0, options.worst_frames));

  // Pass 2: pixels of those frames only.
  std::map<int64_t, cv::Mat> grids;
  PitchDistribution pitch_dist;
  const extrinsics_t* hist_ext = nullptr;
  extrinsics_t hist_ext_copy;
  std::string hist_problem;
  {
    LogFrameOptions read;
    read.prefix = options.prefix;
    if (hist_seq >= 0) read.seqs.insert(hist_seq);
    for (const Row* r : worst) read.seqs.insert(r->seq);
    if (!read.seqs.empty()) {
      LogFrameReader reader(log_path, read);
      LogFrame f;
      while (reader.next(f)) {
        std::vector<KittiLabel> labels;
        GridOptions go;
        if (const std::string path = labelFileFor(options.labels_dir, f.frame_id); !path.empty()) {
          try {
            labels = readKittiLabels(path);
            go.labels = &labels;
          } catch (const std::exception&) {
          }
        }
        std::string problem;
        cv::Mat grid = renderFrameGrid(f, go, &problem);
        if (!grid.empty()) grids[f.seq] = grid;
        if (f.seq == hist_seq) {
          if (f.extrinsics) {
            hist_ext_copy = *f.extrinsics;
            hist_ext = &hist_ext_copy;
          }
          cv::Mat disparity;
          if (!f.disparity) hist_problem = "no DISPARITY for this frame";
          else if (!f.stixels) hist_problem = "no STIXELS (ground model) for this frame";
          else if (std::string why = decodeDisparity(*f.disparity, disparity); !why.empty())
            hist_problem = "DISPARITY: " + why;
          else if (const StereoCamera cam = toCamera(f.disparity->calib); !cam.problem().empty())
            hist_problem = "DISPARITY calibration: " + cam.problem();
          else {
            pitch_dist = computePitchDistribution(disparity, cam, f.stixels->ground);
            if (pitch_dist.pitch_deg.empty()) hist_problem = "no ground samples (invalid ground model or no road in view)";
          }
        }
      }
    }
  }

  // The page.
  HtmlReport page("nerv run report: " + std::filesystem::path(log_path).filename().string());
  page.paragraph("Log " + log_path + (options.labels_dir.empty() ? "" : ", labels " + options.labels_dir) +
                 (extrinsics_file.empty() ? "" : ", true pose " + extrinsics_file) +
                 ". Everything below is computed from the log alone (and the labels).");

  page.heading("Run summary");
  {
    int with_stereo = 0, with_det = 0, valid_pose = 0;
    std::vector<double> lat, hyp, kept, observed, unobserved;
    for (const auto& r : rows) {
      with_stereo += r.has_stereo;
      with_det += r.hypotheses >= 0;
      valid_pose += r.ext_valid;
      lat.push_back(r.latency_ms);
      if (r.hypotheses >= 0) hyp.push_back(r.hypotheses), kept.push_back(r.kept);
      if (std::isfinite(r.observed)) observed.push_back(r.observed), unobserved.push_back(r.unobserved);
    }
    page.table({"figure", "value"},
               {{"frames in the log (STEREO_FRAME)", std::to_string(with_stereo)},
                {"frames with DETECTIONS", std::to_string(with_det)},
                {"frames with a valid pose (EXTRINSICS)", std::to_string(valid_pose)},
                {"latency capture to DETECTIONS p50 [ms]", fmt("%.1f", percentile(lat, 0.5))},
                {"latency capture to DETECTIONS p95 [ms]", fmt("%.1f", percentile(lat, 0.95))},
                {"hypotheses per frame (mean)", fmt("%.1f", mean(hyp))},
                {"kept detections per frame (mean)", fmt("%.1f", mean(kept))},
                {"free space measured, median / lowest frame [%]",
                 observed.empty() ? std::string("not reported")
                                  : fmt("%.0f", percentile(observed, 0.5)) + " / " +
                                        fmt("%.0f", *std::min_element(observed.begin(), observed.end()))},
                {"strips unobserved (unknown, not free), median / highest frame [%]",
                 unobserved.empty() ? std::string("not reported")
                                    : fmt("%.0f", percentile(unobserved, 0.5)) + " / " +
                                          fmt("%.0f", *std::max_element(unobserved.begin(), unobserved.end()))},
                {"broken messages skipped", std::to_string(result.log.broken)},
                {"duplicate messages skipped", std::to_string(result.log.duplicates)}});
    std::string text;
    try {
      summarizeLog(log_path, &text, options.prefix);
      page.paragraph("The run summary of tools/lib/log_summary (as `nerv export --summary`), with the last health "
                     "report of every service (frames dropped, errors):");
      page.pre(text);
    } catch (const std::exception& e) {
      page.paragraph(std::string("log summary failed: ") + e.what());
    }
  }

  auto plot = [&](SvgPlot& p, int height = 260) {
    page.raw(p.render(1000, height));
    ++result.plots;
  };

  page.heading("Camera pose over time (EXTRINSICS)");
  page.paragraph("Filtered (thick) and instant (thin) super-SNV estimates, the stixel stage's v-disparity ground model "
                 "(dashed) and, where known, the true pose. Gaps: frames without a valid estimate.");
  {
    auto valid_or_nan = [](const Row& r, double v) { return r.ext_valid ? v : kNaN; };
    struct Quantity {
      const char* title;
      const char* unit;
      double Row::*filtered;
      double Row::*instant;
      double Row::*ground;
      double Row::*truth;
    };
    const Quantity qs[] = {{"pitch", "pitch [deg], positive = looking down", &Row::pitch, &Row::ipitch, &Row::ground_pitch, &Row::truth_pitch},
                           {"roll", "roll [deg]", &Row::roll, &Row::iroll, nullptr, &Row::truth_roll},
                           {"height", "camera height [m]", &Row::height, &Row::iheight, &Row::ground_height, &Row::truth_height}};
    for (const auto& q : qs) {
      SvgPlot p(std::string("Camera ") + q.title + " per frame", "frame seq", q.unit);
      auto f = series(rows, "filtered", "#1f77b4", [&](const Row& r) { return valid_or_nan(r, r.*q.filtered); });
      f.width_px = 2.5;
      p.add(f);
      auto i = series(rows, "instant", "#6baed6", [&](const Row& r) { return valid_or_nan(r, r.*q.instant); });
      i.width_px = 1;
      i.points = true;
      p.add(i);
      if (q.ground) {
        auto g = series(rows, "v-disparity model", "#ff7f0e", [&](const Row& r) { return r.*q.ground; });
        g.dashed = true;
        if (anyFinite(g)) p.add(g);
      }
      auto t = series(rows, "true", "#2ca02c", [&](const Row& r) { return r.*q.truth; });
      if (anyFinite(t)) p.add(t);
      plot(p);
    }
    SvgPlot c("Pose confidence per frame (from the histogram entropy)", "frame seq", "confidence [0..1]");
    c.setYRange(0, 1);
    auto cs = series(rows, "confidence", "#9467bd", [](const Row& r) { return r.confidence; });
    cs.points = true;
    c.add(cs);
    auto vs = series(rows, "valid (1) / not (0)", "#bbbbbb", [](const Row& r) { return r.has_ext ? (r.ext_valid ? 1.0 : 0.0) : kNaN; });
    vs.dashed = true;
    c.add(vs);
    plot(c, 220);
  }

  page.heading("Detections per frame (DETECTIONS)");
  {
    SvgPlot p("Hypotheses and kept detections per frame", "frame seq", "boxes per frame");
    auto h = series(rows, "hypotheses (stixel)", "#d62728", [](const Row& r) { return r.hypotheses >= 0 ? double(r.hypotheses) : kNaN; });
    h.points = true;
    p.add(h);
    auto k = series(rows, "kept (stixel + SNV)", "#2ca02c", [](const Row& r) { return r.kept >= 0 ? double(r.kept) : kNaN; });
    k.points = true;
    k.width_px = 2.5;
    p.add(k);
    auto o = series(rows, "labelled objects", "#7f7f7f", [](const Row& r) { return r.labelled ? double(r.objects) : kNaN; });
    o.dashed = true;
    if (anyFinite(o)) p.add(o);
    plot(p);
  }

  page.heading("Free or unseen (STIXELS.observed)");
  {
    SvgPlot p("Free space measured per frame", "frame seq", "%");
    auto o = series(rows, "free-space pixels with a disparity", "#1f77b4", [](const Row& r) { return r.observed; });
    o.points = true;
    p.add(o);
    auto u = series(rows, "strips unobserved (unknown, not free)", "#e377c2", [](const Row& r) { return r.unobserved; });
    u.points = true;
    p.add(u);
    if (anyFinite(o)) plot(p);
    else page.paragraph("No frame reported its free space (DETECTIONS.num_columns 0).");
  }

  page.heading("Pitch histogram of one frame");
  if (hist_seq < 0) {
    page.paragraph("No frame with a stereo pair in the log: no histogram.");
  } else {
    page.paragraph(
        "Frame seq " + std::to_string(hist_seq) +
        ". EXTRINSICS carries the histogram's mode, mean and mean-shift estimate but not the histogram, so the bars "
        "are recomputed here from the frame's DISPARITY and the STIXELS ground model: ground samples every 4 px "
        "(below the horizon, within max(1 px, 5 %) of the ground disparity, 2-30 m, normal within 20 deg of vertical), "
        "plain cross-product normals (not the service's integral-image normals), pitch = atan2(-n_z, -n_y) at 0.1 deg "
        "bins. The vertical lines are the service's own three estimates.");
    if (!pitch_dist.pitch_deg.empty()) {
      SvgPlot p("Ground-normal pitch distribution, frame " + std::to_string(hist_seq), "pitch [deg]",
                "normals per 0.1 deg bin");
      SvgBars b;
      b.name = cv::format("recomputed (%zu normals)", pitch_dist.pitch_deg.size());
      b.x0 = pitch_dist.origin_deg;
      b.bin = pitch_dist.bin_deg;
      b.counts = pitch_dist.counts;
      p.add(b);
      std::vector<double> pv(pitch_dist.pitch_deg.begin(), pitch_dist.pitch_deg.end());
      double lo = percentile(pv, 0.02), hi = percentile(pv, 0.98);
      if (hist_ext)
        for (double v : {hist_ext->pitch_mode_deg, hist_ext->pitch_mean_deg, hist_ext->pitch_mean_shift_deg})
          if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
      p.setXRange(lo - 0.5, hi + 0.5);
      if (hist_ext) {
        p.add(SvgMarker{"mode (EXTRINSICS)", hist_ext->pitch_mode_deg, "#d62728", false});
        p.add(SvgMarker{"mean (EXTRINSICS)", hist_ext->pitch_mean_deg, "#ff7f0e", true});
        p.add(SvgMarker{"mean shift (EXTRINSICS)", hist_ext->pitch_mean_shift_deg, "#2ca02c", false});
      }
      p.add(SvgMarker{"recomputed mode", pitch_dist.mode_deg, "#555555", true});
      plot(p, 300);
      if (hist_ext)
        page.paragraph(cv::format("EXTRINSICS of this frame: %s, entropy %.2f bits, confidence %.2f, %d normals, %d inliers "
                                  "in the mean-shift window.",
                                  hist_ext->status.c_str(), hist_ext->entropy, hist_ext->confidence, hist_ext->num_normals,
                                  hist_ext->inliers));
      else
        page.paragraph("No EXTRINSICS for this frame: only the recomputed distribution is shown.");
    } else {
      page.paragraph("No histogram: " + hist_problem + ".");
    }
  }

  page.heading("Per-stage timing");
  {
    SvgPlot p("Processing time per stage and frame", "frame seq", "time [ms]");
    for (int s = 0; s < 4; ++s) {
      auto ser = series(rows, kStages[s], kStageColors[s], [&](const Row& r) {
        auto it = r.stage_ms.find(kStages[s]);
        return it == r.stage_ms.end() ? kNaN : it->second;
      });
      if (anyFinite(ser)) p.add(ser);
    }
    auto lat = series(rows, "latency capture to DETECTIONS", "#d62728", [](const Row& r) { return r.latency_ms; });
    lat.dashed = true;
    if (anyFinite(lat)) p.add(lat);
    plot(p);
    std::vector<std::vector<std::string>> table;
    for (const char* stage : kStages) {
      std::vector<double> v;
      for (const auto& r : rows)
        if (auto it = r.stage_ms.find(stage); it != r.stage_ms.end()) v.push_back(it->second);
      table.push_back({stage, std::to_string(v.size()), fmt("%.2f", mean(v)), fmt("%.2f", percentile(v, 0.5)),
                       fmt("%.2f", percentile(v, 0.95)), fmt("%.2f", v.empty() ? kNaN : *std::max_element(v.begin(), v.end()))});
    }
    page.table({"stage", "frames", "mean [ms]", "p50 [ms]", "p95 [ms]", "max [ms]"}, table);
  }

  if (!options.labels_dir.empty()) {
    page.heading("Precision and recall against the labels");
    EvalCounts all, kept;
    int frames = 0;
    for (const auto& r : rows)
      if (r.labelled) all.add(r.eval_all), kept.add(r.eval_kept), ++frames;
    page.paragraph(cv::format("%d labelled frames, PASCAL matching at IoU > %.2f (tools/lib/detection_eval; DontCare "
                              "regions and ignored objects count neither way)%s.",
                              frames, options.eval.min_iou,
                              options.eval.max_distance_m < 1e8f
                                  ? cv::format(farDetectionsIgnored(options.eval)
                                                   ? ", objects and unmatched detections beyond %.0f m ignored"
                                                   : ", objects beyond %.0f m ignored", options.eval.max_distance_m).c_str()
                                  : ""));
    auto line = [](const char* name, const EvalCounts& c) {
      return std::vector<std::string>{name, std::to_string(c.objects), std::to_string(c.tp), std::to_string(c.fp),
                                      std::to_string(c.fn), fmt("%.3f", c.precision()), fmt("%.3f", c.recall()),
                                      fmt("%.3f", c.f1())};
    };
    page.table({"method", "objects", "TP", "FP", "FN", "precision", "recall", "F1"},
               {line("stixel only (all hypotheses)", all), line("stixel + SNV (kept)", kept)});
    if (label_problems) page.paragraph(std::to_string(label_problems) + " label files could not be read and were left out.");
    if (depth.count()) {
      page.heading("Distance of the kept detections");
      page.paragraph("Depth of each kept true positive against its label's nearest depth (the nearest corner of the "
                     "labelled 3D box, or the labelled depth when the label has no size), for objects neither "
                     "truncated nor occluded (tools/lib/distance_accuracy): z_m is the depth of the median stixel, "
                     "nearest_z_m of the object's nearest part; the last two columns: the share of "
                     "nearest_z_m within one and two of the detections' own nearest_z_sigma_m of the truth (a "
                     "calibrated uncertainty gives about 68 % and 95 %).");
      std::vector<std::vector<std::string>> rows_d;
      for (const auto& [name, acc] : {std::pair<const char*, const DistanceAccuracy*>{"z_m", &depth.z},
                                      {"nearest_z_m", &depth.nearest}})
        for (const DistanceErrorBand& b : acc->bands(defaultDistanceBands()))
          rows_d.push_back({name,
                            std::isfinite(b.to_m) ? cv::format("%.0f-%.0f m", b.from_m, b.to_m) : cv::format("%.0f m and more", b.from_m),
                            std::to_string(b.count), fmt("%+.2f", b.bias_m), fmt("%.2f", b.median_abs_m),
                            fmt("%.2f", b.p95_abs_m), fmt("%.1f %%", 100.0 * b.median_rel),
                            b.count_with_sigma ? fmt("%.0f %%", 100.0 * b.within_1sigma) : std::string("-"),
                            b.count_with_sigma ? fmt("%.0f %%", 100.0 * b.within_2sigma) : std::string("-")});
      page.table({"depth", "range", "boxes", "bias [m]", "median |error| [m]", "p95 |error| [m]", "median |error|",
                  "within 1 sigma", "within 2 sigma"},
                 rows_d);
    }
    page.heading("Why objects were missed");
    if (misses.stixelOnly().empty() && misses.stixelSnv().empty()) {
      page.paragraph("No labelled object was missed.");
    } else {
      page.paragraph("Each missed object by the boxes near it, judged by the depth of each box's nearest part against "
                     "the object's nearest depth (within 1.5 m or 15 %; tools/lib/miss_causes): no box overlaps it, "
                     "only boxes at another depth, a box at its depth covering only a part of it or merged with a "
                     "neighbour (IoU < 0.3), a loose box at its depth, or the validator removed the box that found it.");
      std::map<MissCause, std::pair<int, int>> counts;  // cause -> (stixel only, stixel + SNV)
      std::map<MissCause, std::map<std::string, int>> classes;  // cause -> class -> count (stixel + SNV)
      for (const auto& [cause, by_class] : misses.stixelOnly())
        for (const auto& [type, n] : by_class) counts[cause].first += n;
      for (const auto& [cause, by_class] : misses.stixelSnv())
        for (const auto& [type, n] : by_class) counts[cause].second += n, classes[cause][type] += n;
      std::vector<std::vector<std::string>> rows_m;
      for (const auto& [cause, n] : counts) {
        std::string by;
        for (const auto& [type, k] : classes[cause]) by += (by.empty() ? "" : ", ") + type + " " + std::to_string(k);
        rows_m.push_back({missCauseName(cause, misses.params()), std::to_string(n.first), std::to_string(n.second), by});
      }
      page.table({"cause", "stixel only", "stixel + SNV", "by class (stixel + SNV)"}, rows_m);
    }
    page.heading("Frames with the most errors");
    if (worst.empty()) page.paragraph("No labelled frame with a false positive or a miss.");
    for (const Row* r : worst) {
      auto it = grids.find(r->seq);
      const std::string caption = cv::format("seq %lld %s: kept %d TP, %d FP, %d FN (of %d objects); all hypotheses %d TP, %d FP",
                                             static_cast<long long>(r->seq), r->frame_id.c_str(), r->eval_kept.tp,
                                             r->eval_kept.fp, r->eval_kept.fn, r->eval_kept.objects, r->eval_all.tp, r->eval_all.fp);
      if (it == grids.end()) {
        page.paragraph(caption + " (could not be rendered)");
        continue;
      }
      page.image(jpeg(it->second, 0.5), "image/jpeg", "frame " + std::to_string(r->seq), caption);
      ++result.images;
    }
  }

  page.heading("A rendered frame");
  if (auto it = grids.find(hist_seq); it != grids.end()) {
    page.image(jpeg(it->second, 0.5), "image/jpeg", "frame " + std::to_string(hist_seq),
               "seq " + std::to_string(hist_seq) + " (the histogram frame), as nerv_render draws it");
    ++result.images;
  } else {
    result.note = result.log.stereo_frames == 0 ? "the log has no STEREO_FRAME messages: no frame images in the report"
                                                : "the histogram frame could not be rendered";
    page.paragraph("No rendered frame: " + result.note + ".");
  }

  page.heading("Reading the log");
  {
    std::vector<std::vector<std::string>> t = {
        {"events", std::to_string(result.log.events)},
        {"frame messages decoded", std::to_string(result.log.frame_messages)},
        {"other messages (health, other types)", std::to_string(result.log.other_messages)},
        {"broken messages skipped", std::to_string(result.log.broken)},
        {"duplicates skipped", std::to_string(result.log.duplicates)}};
    for (const auto& [ch, n] : result.log.broken_per_channel) t.push_back({"broken on " + ch, std::to_string(n)});
    page.table({"", "count"}, t);
  }

  result.html_path = options.out_dir + "/report.html";
  std::ofstream out(result.html_path, std::ios::binary);
  out << page.str();
  if (!out) throw std::runtime_error("cannot write " + result.html_path);
  return result;
}

}  // namespace nerv::viz
