// Benchmark of the SNV stage: full-frame integral-image normal map, local SNV
// (ROIs + ground samples), super-SNV (histogram, mean shift, entropy, height),
// the road-plane fit for roll (reported apart), each next to a naive or previous
// implementation measured in the same run. The last lines state the issue 6
// targets: local SNV + super-SNV (with the mean shift) at interval 4 <= 1 ms,
// full map at interval 1 <= 3 ms.
// Input: SGBM disparity of ../shared/data/kitti_raw_0926_seq (gray, 128 levels,
// block 5, P1 8*25, P2 32*25, MODE_SGBM_3WAY, /16, negative -> 0) and its
// label_2 boxes as ROIs; a constructed road + boxes scene when the data is absent.
// Usage: bench_snv [repeats=5]
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <sstream>
#include <thread>
#include <string>
#include <vector>

#include "adaptive_mean_shift.hpp"
#include "calibration_io.hpp"
#include "camera_height.hpp"
#include "entropy.hpp"
#include "ground_plane_fit.hpp"
#include "ground_samples.hpp"
#include "integral_normals.hpp"
#include "local_fields.hpp"
#include "local_normals.hpp"
#include "lowest_surface.hpp"
#include "naive_normals.hpp"
#include "snv_extrinsic.hpp"
#include "super_snv.hpp"

using namespace nerv;
using namespace nerv::snv;
using Clock = std::chrono::steady_clock;

namespace {

struct Frame {
  cv::Mat disparity;
  std::vector<cv::Rect> rois;
};

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Median over repeats of the mean time per frame [ms].
double timePerFrame(const std::vector<Frame>& frames, int repeats,
                    const std::function<void(const Frame&)>& fn) {
  std::vector<double> runs;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    for (const Frame& f : frames) fn(f);
    runs.push_back(msSince(t0) / frames.size());
  }
  std::sort(runs.begin(), runs.end());
  return runs[runs.size() / 2];
}

std::vector<cv::Rect> readLabelBoxes(const std::string& path) {
  std::vector<cv::Rect> boxes;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string type;
    double trunc, occ, alpha, x0, y0, x1, y1;
    if (!(s >> type >> trunc >> occ >> alpha >> x0 >> y0 >> x1 >> y1) || type == "DontCare") continue;
    boxes.emplace_back(cv::Point(static_cast<int>(x0), static_cast<int>(y0)),
                       cv::Point(static_cast<int>(x1), static_cast<int>(y1)));
  }
  return boxes;
}

std::vector<Frame> loadKitti(const std::string& dir, StereoCamera& cam) {
  std::vector<Frame> frames;
  if (!std::filesystem::exists(dir + "/calib.yaml")) return frames;
  cam = loadPlainCalibration(dir + "/calib.yaml");
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 0, 0, 0, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  for (int i = 0;; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%010d", i);
    if (!std::filesystem::exists(dir + "/left/" + name + ".png")) break;  // end of the sequence
    const cv::Mat l = cv::imread(dir + "/left/" + name + ".png", cv::IMREAD_GRAYSCALE);
    const cv::Mat r = cv::imread(dir + "/right/" + name + ".png", cv::IMREAD_GRAYSCALE);
    if (l.empty() || r.empty()) break;
    cv::Mat raw;
    Frame f;
    sgbm->compute(l, r, raw);
    raw.convertTo(f.disparity, CV_32F, 1.0 / 16.0);
    cv::threshold(f.disparity, f.disparity, 0.0, 0.0, cv::THRESH_TOZERO);
    f.rois = readLabelBoxes(dir + "/label_2/" + name + ".txt");
    frames.push_back(f);
  }
  return frames;
}

// Fallback: level road 1.65 m below the camera with five upright boxes.
std::vector<Frame> constructedScene(StereoCamera& cam) {
  cam.width = 1242;
  cam.height = 375;
  cam.fx = cam.fy = 721.5377;
  cam.cx = 609.5593;
  cam.cy = 172.854;
  cam.baseline_m = 0.5327;
  Frame f;
  f.disparity.create(cam.height, cam.width, CV_32F);
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const double d = cam.baseline_m / 1.65 * (v - cam.cy);
      f.disparity.at<float>(v, u) = d > 1 ? static_cast<float>(d) : 0.0f;
    }
  for (int k = 0; k < 5; ++k) {
    const double z = 10.0 + 5.0 * k;
    const int bottom = static_cast<int>(cam.cy + cam.fy * 1.65 / z), top = static_cast<int>(cam.cy - cam.fy * 0.1 / z);
    const cv::Rect box(100 + 220 * k, top, static_cast<int>(cam.fx * 1.8 / z), bottom - top);
    f.disparity(box).setTo(static_cast<float>(cam.fx * cam.baseline_m / z));
    f.rois.push_back(box);
  }
  cv::Mat noise(f.disparity.size(), CV_32F);
  cv::randn(noise, 0.0, 0.1);
  cv::Mat mask = f.disparity > 0;
  cv::add(f.disparity, noise, f.disparity, mask);
  return std::vector<Frame>(3, f);
}

std::string firstLine(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

// The three load averages of /proc/loadavg (the machine is shared: say how busy it was).
std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  StereoCamera cam;
  const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  std::vector<Frame> frames = loadKitti(dir, cam);
  const bool real = !frames.empty();
  if (!real) frames = constructedScene(cam);
  size_t num_rois = 0;
  for (const Frame& f : frames) num_rois += f.rois.size();

  std::printf("bench_snv: %s, %zu frames %dx%d, %.1f ROIs/frame, %d repeats (median)\n",
              real ? "kitti_raw_0926_seq SGBM disparity" : "constructed scene (no shared data)",
              frames.size(), cam.width, cam.height, double(num_rois) / frames.size(), repeats);
  std::printf("machine: %u hardware threads, CPU %s, OpenCV %s, OpenCV threads %d, load average at start %s\n\n",
              std::thread::hardware_concurrency(), firstLine("/proc/cpuinfo", "model name").c_str(),
              CV_VERSION, cv::getNumThreads(), loadAverage().c_str());

  const Params params;
  IntegralNormalParams np;
  np.depth_change_px = params.depth_change_px;
  np.depth_change_rel = params.depth_change_rel;
  np.window_base_px = params.window_base_px;
  np.window_px_per_m = params.window_px_per_m;
  np.max_radius_px = params.max_radius_px;
  np.smooth_disparity = params.smooth_disparity;
  GroundSampleParams gp;
  gp.max_depth_m = params.ground_max_depth_m;
  gp.min_depth_m = params.ground_min_depth_m;
  const GroundModel no_model;
  const cv::Range ground_rows = groundRows(cam, no_model, gp);

  // Ground normals of every frame at each interval, for the super-SNV timing.
  std::printf("%-3s | %-50s | %-40s | %-28s | %-6s | %-15s | %s\n", "", "full-frame SNV map [ms/frame]",
              "local SNV (ROIs + ground) [ms/frame]", "super-SNV [ms/frame]", "plane", "target [ms]", "process() [ms]");
  std::printf("%-3s | %8s %8s %8s %6s %8s %6s | %8s %8s %10s %6s %5s | %7s %8s %6s %5s | %6s | %15s | %7s\n", "int",
              "fast", "1 thread", "previous", "ratio", "naive", "ratio", "local", "naive", "box-naive", "ratio",
              "nrm", "super", "previous", "ratio", "nrm", "fit", "local+super", "total");
  double target_ms = 0, plane_ms = 0, surface_ms = 0, full1_ms = 0;
  for (int k = 1; k <= 6; ++k) {
    cv::setNumThreads(-1);
    const double full = timePerFrame(frames, repeats, [&](const Frame& f) { computeNormalMap(f.disparity, cam, np, k); });
    if (k == 1) full1_ms = full;
    cv::setNumThreads(1);
    const double full1 = timePerFrame(frames, repeats, [&](const Frame& f) { computeNormalMap(f.disparity, cam, np, k); });
    const double ref = timePerFrame(frames, std::min(repeats, 3), [&](const Frame& f) { computeNormalMapReference(f.disparity, cam, np, k); });
    cv::setNumThreads(-1);
    const double naive = timePerFrame(frames, repeats, [&](const Frame& f) { computeNaiveNormalMap(f.disparity, cam, 1, k); });

    // Local SNV: the integral field over the needed band, ground samples and ROI normals.
    size_t normals_per_frame = 0;
    std::vector<std::vector<GroundSample>> ground(frames.size());
    LocalFields fields;  // kept across frames, as SnvExtrinsicEstimator does
    const double local = timePerFrame(frames, repeats, [&](const Frame& f) {
      fields.prepare(f.disparity, cam, np, ground_rows, f.rois);
      const size_t i = &f - frames.data();
      ground[i] = selectGroundSamples(fields.ground(), f.disparity, cam, no_model, gp, ground_rows, k);
      std::vector<LocalNormal> out;
      for (size_t r = 0; r < f.rois.size(); ++r) localNormalsInRect(fields.roi(r), f.rois[r], k, out);
      normals_per_frame = ground[i].size() + out.size();
    });
    // Naive local: the same sample pixels, each box mean summed pixel by pixel.
    const int naive_repeats = 1;
    const double box_naive = timePerFrame(frames, naive_repeats, [&](const Frame& f) {
      cv::Vec3f n;
      for (const GroundSample& s : ground[&f - frames.data()]) bruteForceSmoothedNormal(f.disparity, cam, np, s.u, s.v, 3, n);
      for (const cv::Rect& r : f.rois)
        for (int v = (std::max(r.y, 0) + k - 1) / k * k; v < std::min(r.y + r.height, cam.height); v += k)
          for (int u = (std::max(r.x, 0) + k - 1) / k * k; u < std::min(r.x + r.width, cam.width); u += k)
            bruteForceSmoothedNormal(f.disparity, cam, np, u, v, 3, n);
    });
    // Unsmoothed naive cross product on the same pixels.
    const double local_naive = timePerFrame(frames, repeats, [&](const Frame& f) {
      const NormalMap m = computeNaiveNormalMap(f.disparity, cam, 1, k);
      (void)m;
    });

    // Super-SNV as in SnvExtrinsicEstimator::process(): pitch/roll, sort, histogram
    // mode, mean, adaptive mean shift, window entropy, median height.
    size_t ground_normals = 0;
    for (const auto& g : ground) ground_normals += g.size();
    std::vector<float> pitch_ms(frames.size()), roll_ms(frames.size()), height_ms(frames.size());
    const double super = timePerFrame(frames, repeats, [&](const Frame& f) {
      const size_t fi = &f - frames.data();
      const auto& g = ground[fi];
      if (g.empty()) return;
      std::vector<cv::Vec3f> nrm(g.size());
      for (size_t i = 0; i < g.size(); ++i) nrm[i] = g[i].n;
      std::vector<float> pitch(g.size()), roll(g.size());
      normalAnglesDeg(nrm.data(), static_cast<int>(nrm.size()), pitch.data(), roll.data());
      sortAngles(pitch);
      sortAngles(roll);
      const float pm = sortedModeDeg(pitch, 0.1f), rm = sortedModeDeg(roll, 0.1f);
      volatile double mean = std::accumulate(pitch.begin(), pitch.end(), 0.0) / pitch.size();
      (void)mean;
      const MeanShiftResult ps = adaptiveMeanShift(pitch, pm, 0.5f, 0.01f);
      const MeanShiftResult rs = adaptiveMeanShift(roll, rm, 0.5f, 0.01f);
      windowEntropyBits(pitch, ps.estimate, 0.5f, 0.1f);
      std::vector<cv::Vec3f> pts(g.size());
      for (size_t i = 0; i < g.size(); ++i) pts[i] = g[i].p;
      pitch_ms[fi] = ps.estimate;
      roll_ms[fi] = rs.estimate;
      height_ms[fi] = medianCameraHeight(pts, normalFromPitchRoll(ps.estimate, rs.estimate));
    });
    // Roll from the road plane, as process() does after the super-SNV (plane_fit:
    // true): IRLS plane, roll, height again, entropy of the relative residuals.
    // Part of the per-frame pose cost, reported apart from the target figure.
    const double plane = timePerFrame(frames, repeats, [&](const Frame& f) {
      const size_t fi = &f - frames.data();
      const auto& g = ground[fi];
      if (g.empty()) return;
      std::vector<PlanePoint> pp(g.size());
      std::vector<cv::Vec3f> pts(g.size());
      for (size_t i = 0; i < g.size(); ++i) {
        pp[i] = {static_cast<float>(g[i].u), static_cast<float>(g[i].v), g[i].d};
        pts[i] = g[i].p;
      }
      const DisparityPlane start = planeFromNormal(normalFromPitchRoll(pitch_ms[fi], roll_ms[fi]), height_ms[fi], cam);
      PlaneFitParams fit;
      fit.tukey_k = params.plane_tukey_k;
      const DisparityPlane pl = fitDisparityPlane(pp, cam, fit, &start);
      if (!pl.valid) return;
      const cv::Vec3f n = normalFromPitchRoll(pitch_ms[fi], normalRollDeg(planeNormal(pl, cam)));
      medianCameraHeight(pts, n);
      std::vector<float> res(g.size());
      for (size_t i = 0; i < g.size(); ++i)
        res[i] = static_cast<float>(g[i].d - pl.disparity(cam, g[i].u, g[i].v)) / g[i].d;
      sampleEntropyBits(res, params.residual_entropy_bin);
    });
    // Lowest-surface selection before the planes (plane_lowest_surface: true): its
    // passes, each a selection and a plane fit on the kept samples (process()
    // starts the roll plane from the last one, so the "plane" column above then
    // converges at once). Part of the per-frame pose cost, reported apart from
    // the target figure.
    const double surface = timePerFrame(frames, repeats, [&](const Frame& f) {
      const size_t fi = &f - frames.data();
      const auto& g = ground[fi];
      if (g.empty()) return;
      std::vector<PlanePoint> pp(g.size()), sub;
      for (size_t i = 0; i < g.size(); ++i) pp[i] = {static_cast<float>(g[i].u), static_cast<float>(g[i].v), g[i].d};
      DisparityPlane ref = planeFromNormal(normalFromPitchRoll(pitch_ms[fi], roll_ms[fi]), height_ms[fi], cam);
      LowestSurfaceParams lp;
      lp.band_rows = params.lowest_surface_band_px;
      lp.min_peak_fraction = params.lowest_surface_min_fraction;
      lp.tolerance = params.lowest_surface_tolerance;
      PlaneFitParams fit;
      fit.tukey_k = params.plane_tukey_k;
      std::vector<unsigned char> keep;
      for (int pass = 0; pass < params.lowest_surface_passes; ++pass) {
        selectLowestSurface(pp, ref, cam, lp, keep);
        sub.clear();
        for (size_t i = 0; i < pp.size(); ++i)
          if (keep[i]) sub.push_back(pp[i]);
        const DisparityPlane next = fitDisparityPlane(sub, cam, fit, &ref);
        if (!next.valid) break;
        ref = next;
      }
    });
    // Previous implementation: std::atan2 per angle, histogram, std::sort.
    const double super_prev = timePerFrame(frames, repeats, [&](const Frame& f) {
      const auto& g = ground[&f - frames.data()];
      if (g.empty()) return;
      std::vector<float> pitch, roll;
      std::vector<cv::Vec3f> pts;
      for (const GroundSample& s : g) {
        pitch.push_back(normalPitchDeg(s.n));
        roll.push_back(normalRollDeg(s.n));
        pts.push_back(s.p);
      }
      const float pm = buildAngleHistogram(pitch, 0.1f).modeDeg(), rm = buildAngleHistogram(roll, 0.1f).modeDeg();
      std::sort(pitch.begin(), pitch.end());
      std::sort(roll.begin(), roll.end());
      const MeanShiftResult ps = adaptiveMeanShift(pitch, pm, 0.5f, 0.01f);
      const MeanShiftResult rs = adaptiveMeanShift(roll, rm, 0.5f, 0.01f);
      windowEntropyBits(pitch, ps.estimate, 0.5f, 0.1f);
      medianCameraHeight(pts, normalFromPitchRoll(ps.estimate, rs.estimate));
    });

    Params pk = params;
    pk.interval_px = k;
    SnvExtrinsicEstimator est(pk);
    const double total = timePerFrame(frames, repeats, [&](const Frame& f) {
      std::vector<Hypothesis> hyps;
      for (const cv::Rect& r : f.rois) {
        Hypothesis h;
        h.id = static_cast<int>(hyps.size());
        h.box = {r.x, r.y, r.width, r.height};
        hyps.push_back(h);
      }
      est.process(f.disparity, cam, hyps, no_model);
    });
    (void)local_naive;
    std::printf("%-3d | %8.2f %8.2f %8.2f %6.1f %8.2f %6.2f | %8.2f %8.2f %10.2f %6.1f %5zu | %7.3f %8.3f %6.1f %5zu | %6.3f | %15.3f | %7.2f\n", k,
                full, full1, ref, ref / full, naive, naive / full, local, local_naive, box_naive, box_naive / local,
                normals_per_frame, super, super_prev, super_prev / super, ground_normals / frames.size(), plane,
                local + super, total);
    if (k == 4) {
      target_ms = local + super;
      plane_ms = plane;
      surface_ms = surface;
    }
  }
  std::printf("\nfull-frame: fast = computeNormalMap (vectorised rows, all OpenCV threads), 1 thread = same with "
              "cv::setNumThreads(1), previous = computeNormalMapReference (the scalar per-pixel path this "
              "replaced, 1 thread), naive = raw-neighbour cross product per pixel (r = 1, no smoothing); "
              "ratios = previous / fast, naive / fast.\nlocal = band integral field + ground samples + ROI normals; "
              "naive = the unsmoothed full naive map; box-naive = the same sample pixels with r = 3 box "
              "means summed pixel by pixel (1 repeat), ratio = box-naive / local; nrm = normals per frame.\n"
              "super = pitch+roll (polynomial atan), bucket sort (sortAngles), mode from the sorted run, mean, adaptive mean shift, "
              "entropy, median height; previous = std::atan2, histogram, std::sort, same rest; "
              "nrm = ground normals per frame.\n"
              "plane fit = road plane for roll (IRLS), second height, residual entropy: part of process() "
              "(plane_fit: true), not of the target figure.\n"
              "local+super = the issue 6 target figure; total = SnvExtrinsicEstimator::process() with the "
              "label_2 boxes as ROIs (adds the plane fit and the ROI statistics).\n\n");
  std::printf("TARGET local SNV + super-SNV (incl. mean shift) at interval 4: %.3f ms/frame (target <= 1 ms: %s)\n",
              target_ms, target_ms <= 1.0 ? "met" : "NOT met");
  std::printf("       road-plane fit for roll (per-frame pose cost, outside the target): %.3f ms/frame\n", plane_ms);
  std::printf("       lowest-surface selection, %d passes (per-frame pose cost, outside the target): %.3f ms/frame\n",
              params.lowest_surface_passes, surface_ms);
  std::printf("TARGET full-frame SNV map at interval 1: %.2f ms/frame (target <= 3 ms: %s)\n", full1_ms,
              full1_ms <= 3.0 ? "met" : "NOT met");
  std::printf("load average at end: %s\n", loadAverage().c_str());
  return 0;
}
