// Road-region disparity error of the matchers against the renderer's exact
// disparity, and the super-SNV pose each matcher's disparity gives (issue 6:
// why nerv_sgm degrades the normals). Not a timing benchmark: it prints error
// statistics per matcher over rendered frames of a synthetic preset.
//
//   bench_road_disparity [--scene urban] [--frames 8] [--stride 2]
//                        [--matcher nerv_sgm --matcher sgbm ...] [--p1 7 --p2 90]
//                        [--no-subpixel] [--max-depth 30] [--census W H]
//                        [--road-census W H] [--road-census-from SHARE]
//                        [--snv "{key: value, ...}"] [--cache DIR] [--pose-only]
//
// --snv: snv_extrinsic keys (as in the service config) for the estimator;
// --cache: keep each matcher's disparity per frame in DIR (raw float files, named
// by the matcher's settings, --blur, --median and the scene seed) and reuse it on
// the next run (variants of the snv keys on the same disparities);
// --pose-only: only the pose lines (with a cache, frames are then not rendered).
//
// Also printed (not with --pose-only): the "oracle" plane - the estimator's
// robust plane fit (fitDisparityPlane, Tukey plane_tukey_k, started from the
// exact plane) on the matcher's disparity at pixels the renderer says lie on the
// road surface itself (exact disparity within 0.02 px of the exact road plane:
// no sidewalk, kerb, object or trap), every 4th pixel, depth 2..30 m, rows >
// cy + 10: (a) all such pixels, (b) without the bottom 8 image rows, (c) only
// the estimator's ground samples (pixels with a road normal). Its pitch error is
// what the matcher's disparity alone costs a disparity-plane pitch, whatever
// the sample selection.
//
// Road pixels: object_id == -1 (ground), exact disparity > 0, no trap, depth
// below --max-depth (the super-SNV ground range), rows below cy + 10.
// Printed per matcher: density on the road, error e = d - d_true (median, mean,
// std, p95 |e|), pixel-locking (mean e per tenth of frac(d_true); a matcher that
// snaps to integers has e ~ -frac for frac < 0.5 and 1 - frac above), the
// histogram of frac(d), the mean error per depth band, and the pose errors.
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "camera_pose.hpp"
#include "config.hpp"
#include "ground_plane_fit.hpp"
#include "ground_samples.hpp"
#include "integral_normals.hpp"
#include "super_snv.hpp"
#include "renderer.hpp"
#include "scene_yaml.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "world_builder.hpp"

namespace {

struct Stats {
  std::vector<double> err;
  double lock_sum[10] = {}, lock_n[10] = {};
  double frac_hist[10] = {};
  double err_hist[21] = {};  // e in 0.1 px bins, -1.05..+1.05
  double band_sum[6] = {}, band_n[6] = {};  // depth bands 0-5,5-10,...,25-30 m
  double near_sum[6] = {}, near_n[6] = {}, open_sum[6] = {}, open_n[6] = {};  // within 16 px of an object in the row, or not
  long road = 0, valid = 0;
  std::vector<double> pitch_err, roll_err, height_err;
  std::vector<double> box_err, box_grad;
  double radius_hist[9] = {};
  std::vector<double> oracle_err[3];  // oracle plane pitch error: all, without bottom rows, ground samples
  std::vector<double> normal_pitch_err;  // per road grid pixel with a normal  // 17x17 mean error; its vertical difference over 16 rows
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - 1)];
}

cv::Mat testSgbm(const cv::Mat& l, const cv::Mat& r) {
  // the disparity test_snv_synthetic_pose uses (tests/unit/snv_test_scenes.hpp)
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 0, 0, 0, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, disp;
  sgbm->compute(l, r, raw);
  raw.convertTo(disp, CV_32F, 1.0 / 16.0);
  cv::threshold(disp, disp, 0.0, 0.0, cv::THRESH_TOZERO);
  return disp;
}

// Raw cache file: rows, cols (int32), then rows * cols floats.
bool loadDisparity(const std::string& path, cv::Mat& d) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  int32_t rc[2];
  bool ok = std::fread(rc, sizeof rc, 1, f) == 1;
  if (ok) {
    d.create(rc[0], rc[1], CV_32F);
    ok = std::fread(d.ptr<float>(), sizeof(float), d.total(), f) == d.total();
  }
  std::fclose(f);
  return ok;
}

void saveDisparity(const std::string& path, const cv::Mat& d) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return;
  const int32_t rc[2] = {d.rows, d.cols};
  std::fwrite(rc, sizeof rc, 1, f);
  const cv::Mat c = d.isContinuous() ? d : d.clone();
  std::fwrite(c.ptr<float>(), sizeof(float), c.total(), f);
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace nerv;
  std::string scene = "urban";
  int frames = 8, stride = 2;
  double max_depth = 30.0;
  std::vector<std::string> matchers;
  int median = 0;  // experiment: median filter (3 or 5) on nerv_sgm's disparity
  int blur = 0;  // experiment: box-blur (blur x blur) both views before nerv_sgm
  std::string snv_yaml, cache;
  bool pose_only = false;
  std::string dump;  // directory: error images (128 + 100 e, 0 = invalid) of the first frame
  stereo::Params base;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--scene") scene = next();
    else if (a == "--frames") frames = std::atoi(next());
    else if (a == "--stride") stride = std::atoi(next());
    else if (a == "--matcher") matchers.push_back(next());
    else if (a == "--p1") base.sgm_p1 = std::atoi(next());
    else if (a == "--p2") base.sgm_p2 = std::atoi(next());
    else if (a == "--no-subpixel") base.subpixel = false;
    else if (a == "--uniqueness") base.uniqueness_ratio = std::atoi(next());
    else if (a == "--lr") base.lr_max_diff = std::atoi(next());
    else if (a == "--speckle") base.speckle_window_size = std::atoi(next());
    else if (a == "--dump") dump = next();
    else if (a == "--snv") snv_yaml = next();
    else if (a == "--cache") cache = next();
    else if (a == "--pose-only") pose_only = true;
    else if (a == "--blur") blur = std::atoi(next());
    else if (a == "--census") {
      base.census_width = std::atoi(next());
      base.census_height = std::atoi(next());
    } else if (a == "--road-census") {
      base.road_census_width = std::atoi(next());
      base.road_census_height = std::atoi(next());
    } else if (a == "--road-census-from") base.road_census_from = std::atof(next());
    else if (a == "--median") median = std::atoi(next());
    else if (a == "--max-depth") max_depth = std::atof(next());
    else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  if (matchers.empty()) matchers = {"nerv_sgm", "sgbm", "gt", "gt_mask_nerv"};

  const synth::SceneSpec spec =
      synth::loadScene(synth::resolveScenePath(scene, std::string(NERV_SOURCE_DIR) + "/config/scenes"));
  const synth::World world = synth::buildWorld(spec);
  const StereoCamera& cam = spec.camera.intrinsics;
  std::vector<Stats> stats(matchers.size());
  std::vector<std::unique_ptr<stereo::StereoMatcher>> impl(matchers.size());
  snv::Params snv_params;
  if (!snv_yaml.empty()) {
    ConfigSection section(YAML::Load(snv_yaml), "snv_extrinsic");
    snv_params = snv::readParams(section);
    section.finish();
  }
  std::vector<std::unique_ptr<snv::SnvExtrinsicEstimator>> est;  // not copyable: it keeps its buffers
  for (size_t m = 0; m < matchers.size(); ++m) est.push_back(std::make_unique<snv::SnvExtrinsicEstimator>(snv_params));
  for (size_t m = 0; m < matchers.size(); ++m)
    if (matchers[m] != "sgbm_test" && matchers[m] != "gt" && matchers[m] != "gt_mask_nerv") {
      stereo::Params p = base;
      p.algorithm = matchers[m];
      impl[m] = stereo::StereoMatcher::create(p);
    }
  // Cache files are keyed by everything that changes a matcher's output (its
  // settings, --blur, --median, the scene seed), so that a changed default or
  // option never reads a stale file.
  std::vector<std::string> cache_keys(matchers.size());
  for (size_t m = 0; m < matchers.size(); ++m) {
    stereo::Params p = base;
    p.algorithm = matchers[m];
    const std::string key = stereo::describeParams(p) + "|blur" + std::to_string(blur) + "|median" +
                            std::to_string(median) + "|seed" + std::to_string(spec.seed);
    cache_keys[m] = std::to_string(std::hash<std::string>{}(key));
  }
  std::unique_ptr<stereo::StereoMatcher> mask_matcher;
  const double fb = cam.fx * cam.baseline_m;
  for (int k = 0; k < frames; ++k) {
    const int f = k * stride;
    const synth::CameraPose pose = synth::cameraPose(spec.camera, world, f);
    auto cachePath = [&](size_t m) {
      return cache + "/" + scene + "_" + matchers[m] + "_" + std::to_string(f) + "_" + cache_keys[m] + ".bin";
    };
    bool all_cached = !cache.empty() && pose_only;
    for (size_t m = 0; m < matchers.size() && all_cached; ++m) {
      FILE* probe = std::fopen(cachePath(m).c_str(), "rb");
      all_cached = probe != nullptr;
      if (probe) std::fclose(probe);
    }
    synth::RenderedFrame rf;
    cv::Mat l, r;
    if (!all_cached) {
      rf = synth::renderFrame(world, spec.camera, pose, f, spec.seed);
      cv::cvtColor(rf.left, l, cv::COLOR_BGR2GRAY);
      cv::cvtColor(rf.right, r, cv::COLOR_BGR2GRAY);
    }
    for (size_t m = 0; m < matchers.size(); ++m) {
      cv::Mat d;
      const bool cached = !cache.empty() && loadDisparity(cachePath(m), d);
      if (cached) {
      } else if (impl[m]) {
        if (blur > 1 && matchers[m] == "nerv_sgm") {
          cv::Mat lb, rb;
          cv::blur(l, lb, cv::Size(blur, blur));
          cv::blur(r, rb, cv::Size(blur, blur));
          impl[m]->compute(lb, rb, d);
        } else {
          impl[m]->compute(l, r, d);
        }
        if (median > 1 && matchers[m] == "nerv_sgm") {
          cv::Mat dm;
          cv::medianBlur(d, dm, median);
          d = dm;
        }
      } else if (matchers[m] == "gt") {
        d = rf.disparity.clone();
      } else if (matchers[m] == "gt_mask_nerv") {
        // exact disparity with nerv_sgm's invalid pixels: holes vs noise
        if (!mask_matcher) {
          stereo::Params p = base;
          mask_matcher = stereo::StereoMatcher::create(p);
        }
        cv::Mat dn;
        mask_matcher->compute(l, r, dn);
        d = rf.disparity.clone();
        d.setTo(0.0f, dn <= 0.0f);
      } else {
        d = testSgbm(l, r);
      }
      if (!cache.empty() && !cached) saveDisparity(cachePath(m), d);
      Stats& s = stats[m];
      if (!pose_only) {  // error statistics (skipped with --pose-only)
        if (!dump.empty() && k == 0) {
          cv::Mat img(d.size(), CV_8U, cv::Scalar(0));
          for (int v = 0; v < d.rows; ++v)
            for (int u = 0; u < d.cols; ++u)
              if (d.at<float>(v, u) > 0 && rf.disparity.at<float>(v, u) > 0)
                img.at<uchar>(v, u) = cv::saturate_cast<uchar>(128 + 100 * (d.at<float>(v, u) - rf.disparity.at<float>(v, u)));
          cv::imwrite(dump + "/err_" + matchers[m] + ".png", img);
          if (m == 0) cv::imwrite(dump + "/left.png", l);
        }
        for (int v = static_cast<int>(cam.cy) + 10; v < cam.height; ++v)
          for (int u = 0; u < cam.width; ++u) {
            const float gt = rf.disparity.at<float>(v, u);
            if (gt <= 0 || rf.object_id.at<int>(v, u) != -1 || rf.trap_mask.at<uchar>(v, u)) continue;
            const double z = fb / gt;
            if (z > max_depth) continue;
            ++s.road;
            const float dv = d.at<float>(v, u);
            if (!(dv > 0)) continue;
            ++s.valid;
            const double e = dv - gt;
            s.err.push_back(e);
            if (std::abs(e) < 1.0) {
              const int fb_ = std::min(9, static_cast<int>((gt - std::floor(gt)) * 10));
              s.lock_sum[fb_] += e;
              s.lock_n[fb_] += 1;
              s.err_hist[std::clamp(static_cast<int>(std::floor((e + 1.05) * 10)), 0, 20)] += 1;
              s.frac_hist[std::min(9, static_cast<int>((dv - std::floor(dv)) * 10))] += 1;
              const int band = std::min(5, static_cast<int>(z / 5));
              s.band_sum[band] += e;
              s.band_n[band] += 1;
              bool near = false;
              for (int du = -16; du <= 16 && !near; ++du) {
                const int uu = u + du;
                if (uu >= 0 && uu < cam.width && rf.object_id.at<int>(v, uu) != -1) near = true;
              }
              (near ? s.near_sum : s.open_sum)[band] += e;
              (near ? s.near_n : s.open_n)[band] += 1;
            }
          }
        {
          // What the normals see: box means (17 x 17, the largest SNV window) of
          // the error over valid road pixels, and their difference across 16 rows.
          cv::Mat e(d.size(), CV_32F, 0.0f), w(d.size(), CV_32F, 0.0f);
          for (int v = 0; v < cam.height; ++v)
            for (int u = 0; u < cam.width; ++u) {
              const float gt = rf.disparity.at<float>(v, u), dv = d.at<float>(v, u);
              if (gt > 0 && dv > 0 && rf.object_id.at<int>(v, u) == -1 && std::abs(dv - gt) < 1.0f) {
                e.at<float>(v, u) = dv - gt;
                w.at<float>(v, u) = 1.0f;
              }
            }
          cv::Mat se, sw;
          cv::boxFilter(e, se, CV_32F, cv::Size(17, 17), cv::Point(-1, -1), false);
          cv::boxFilter(w, sw, CV_32F, cv::Size(17, 17), cv::Point(-1, -1), false);
          for (int v = static_cast<int>(cam.cy) + 18; v + 8 < cam.height; v += 4)
            for (int u = 8; u + 8 < cam.width; u += 4) {
              if (sw.at<float>(v - 8, u) < 150 || sw.at<float>(v + 8, u) < 150 || sw.at<float>(v, u) < 150) continue;
              const float gt = rf.disparity.at<float>(v, u);
              if (gt <= 0 || fb / gt > max_depth) continue;
              s.box_err.push_back(se.at<float>(v, u) / sw.at<float>(v, u));
              s.box_grad.push_back(se.at<float>(v + 8, u) / sw.at<float>(v + 8, u) -
                                   se.at<float>(v - 8, u) / sw.at<float>(v - 8, u));
            }
        }
        {
          snv::IntegralNormalField field;
          field.prepare(d, cam, snv::normalParams(snv_params));
          snv::NormalRow row;
          for (int v = static_cast<int>(cam.cy) + 12; v < cam.height; v += 4) {
            field.normalRow(v, 0, (cam.width - 1) / 4 + 1, 4, row);
            for (int i = 0; i * 4 < cam.width; ++i) {
              const int u = i * 4;
              const float gt = rf.disparity.at<float>(v, u);
              if (gt <= 0 || rf.object_id.at<int>(v, u) != -1 || fb / gt > max_depth || fb / gt < 2) continue;
              s.radius_hist[std::clamp(row.radius[i], 0, 8)] += 1;
              if (row.radius[i] >= 1 && std::isfinite(row.ny[i]))
                s.normal_pitch_err.push_back(std::atan2(-row.nz[i], -row.ny[i]) * 180.0 / CV_PI - pose.pitch_deg);
            }
          }
        }
        {
          // Oracle plane on the exact road surface (see the header).
          const cv::Vec3f n_true = snv::normalFromPitchRoll(static_cast<float>(pose.pitch_deg),
                                                            static_cast<float>(pose.roll_deg));
          const snv::DisparityPlane exact = snv::planeFromNormal(n_true, static_cast<float>(pose.height_m), cam);
          auto onSurface = [&](int u, int v) {
            const float gt = rf.disparity.at<float>(v, u);
            return gt > 0 && fb / gt <= max_depth && fb / gt >= 2 && !rf.trap_mask.at<uchar>(v, u) &&
                   std::abs(gt - exact.disparity(cam, u, v)) < 0.02;
          };
          std::vector<snv::PlanePoint> pts[3];
          for (int v = static_cast<int>(cam.cy) + 12; v < cam.height; v += 4)
            for (int u = 0; u < cam.width; u += 4) {
              const float dv = d.at<float>(v, u);
              if (!(dv > 0) || !onSurface(u, v)) continue;
              pts[0].push_back({static_cast<float>(u), static_cast<float>(v), dv});
              if (v < cam.height - 8) pts[1].push_back({static_cast<float>(u), static_cast<float>(v), dv});
            }
          snv::IntegralNormalField sample_field;
          sample_field.prepare(d, cam, snv::normalParams(snv_params));
          const snv::GroundSampleParams gp = snv::groundParams(snv_params);
          for (const snv::GroundSample& g :
               snv::selectGroundSamples(sample_field, d, cam, GroundModel{}, gp,
                                        snv::groundRows(cam, GroundModel{}, gp), snv_params.interval_px))
            if (onSurface(g.u, g.v)) pts[2].push_back({static_cast<float>(g.u), static_cast<float>(g.v), g.d});
          snv::PlaneFitParams fit;
          fit.tukey_k = snv_params.plane_tukey_k;
          std::printf("%-10s frame %3d oracle plane pitch err:", matchers[m].c_str(), f);
          for (int k = 0; k < 3; ++k) {
            const snv::DisparityPlane pl = snv::fitDisparityPlane(pts[k], cam, fit, &exact);
            const double e = pl.valid ? snv::normalPitchDeg(snv::planeNormal(pl, cam)) - pose.pitch_deg : NAN;
            s.oracle_err[k].push_back(e);
            std::printf(" %s %+.3f (%zu)", k == 0 ? "all" : k == 1 ? "no-bottom-8" : "samples", e, pts[k].size());
          }
          std::printf("\n");
        }
      }
      const snv::SnvResult res = est[m]->process(d, cam, {}, GroundModel{});
      s.pitch_err.push_back(res.pose.instant_pitch_deg - pose.pitch_deg);
      s.roll_err.push_back(res.pose.instant_roll_deg - pose.roll_deg);
      s.height_err.push_back(res.pose.instant_height_m - pose.height_m);
      std::printf("%-10s frame %3d true pitch %+.3f: err pitch %+.3f roll %+.3f h %+.4f (%s, %d samples)\n",
                  matchers[m].c_str(), f, pose.pitch_deg, s.pitch_err.back(), s.roll_err.back(),
                  s.height_err.back(), res.pose.status.c_str(), res.ground_samples);
    }
  }
  std::printf("\nscene %s, %d frames (stride %d), road within %.0f m\n", scene.c_str(), frames, stride,
              max_depth);
  for (size_t m = 0; m < matchers.size(); ++m) {
    Stats& s = stats[m];
    std::vector<double> abs_err(s.err.size()), inl;
    for (size_t i = 0; i < s.err.size(); ++i) abs_err[i] = std::abs(s.err[i]);
    for (double e : s.err)
      if (std::abs(e) < 1.0) inl.push_back(e);
    double mean = 0, sq = 0;
    for (double e : inl) mean += e;
    mean /= std::max<size_t>(1, inl.size());
    for (double e : inl) sq += (e - mean) * (e - mean);
    const double sd = std::sqrt(sq / std::max<size_t>(1, inl.size()));
    std::vector<double> ap, ar, ah;
    for (double e : s.pitch_err) ap.push_back(std::abs(e));
    for (double e : s.roll_err) ar.push_back(std::abs(e));
    for (double e : s.height_err) ah.push_back(std::abs(e));
    std::printf("%-10s road density %.1f %%, |e|>1 px %.2f %%, median e %+.3f, |e|<1: mean %+.3f std %.3f, "
                "p95 |e| %.3f px\n",
                matchers[m].c_str(), 100.0 * s.valid / std::max(1L, s.road),
                100.0 * (s.err.size() - inl.size()) / std::max<size_t>(1, s.err.size()),
                percentile(s.err, 0.5), mean, sd, percentile(abs_err, 0.95));
    std::printf("%-10s   mean e by frac(d_true) 0.0..0.9:", matchers[m].c_str());
    for (int b = 0; b < 10; ++b) std::printf(" %+.3f", s.lock_sum[b] / std::max(1.0, s.lock_n[b]));
    std::printf("\n%-10s   histogram of frac(d) [%%]:      ", matchers[m].c_str());
    double n = 0;
    for (double h : s.frac_hist) n += h;
    for (int b = 0; b < 10; ++b) std::printf(" %5.1f", 100.0 * s.frac_hist[b] / std::max(1.0, n));
    std::printf("\n%-10s   histogram of e, 0.1 px bins -1..+1 [%%]:", matchers[m].c_str());
    for (int b = 0; b < 21; ++b) std::printf(" %.1f", 100.0 * s.err_hist[b] / std::max(1.0, n));
    std::printf("\n%-10s   mean e per 5 m depth band:      ", matchers[m].c_str());
    for (int b = 0; b < 6; ++b) std::printf(" %+.3f", s.band_sum[b] / std::max(1.0, s.band_n[b]));
    std::printf("\n%-10s   near objects (16 px):", matchers[m].c_str());
    for (int b = 0; b < 6; ++b) std::printf(" %+.3f (%.0f)", s.near_sum[b] / std::max(1.0, s.near_n[b]), s.near_n[b]);
    std::printf("\n%-10s   open road:", matchers[m].c_str());
    for (int b = 0; b < 6; ++b) std::printf(" %+.3f (%.0f)", s.open_sum[b] / std::max(1.0, s.open_n[b]), s.open_n[b]);
    auto meanStd = [](const std::vector<double>& x, double& mu, double& sd) {
      mu = 0;
      for (double v : x) mu += v;
      mu /= std::max<size_t>(1, x.size());
      sd = 0;
      for (double v : x) sd += (v - mu) * (v - mu);
      sd = std::sqrt(sd / std::max<size_t>(1, x.size()));
    };
    double bm, bs, gm, gs;
    meanStd(s.box_err, bm, bs);
    meanStd(s.box_grad, gm, gs);
    std::printf("\n%-10s   17x17 box mean of e: mean %+.4f std %.4f; its difference over 16 rows: mean %+.4f std %.4f px",
                matchers[m].c_str(), bm, bs, gm, gs);
    std::printf("\n%-10s   SNV radius on road grid pixels r=0..8 [%%]:", matchers[m].c_str());
    double rn = 0;
    for (double h : s.radius_hist) rn += h;
    for (int b = 0; b < 9; ++b) std::printf(" %.1f", 100.0 * s.radius_hist[b] / std::max(1.0, rn));
    {
      std::vector<double> pe = s.normal_pitch_err, ape;
      for (double x : pe) ape.push_back(std::abs(x));
      std::printf("\n%-10s   per-normal pitch error: n %zu median %+.3f, p25 %+.3f p75 %+.3f, median |e| %.3f deg",
                  matchers[m].c_str(), pe.size(), percentile(pe, 0.5), percentile(pe, 0.25),
                  percentile(pe, 0.75), percentile(ape, 0.5));
    }
    if (!s.oracle_err[0].empty()) {
      std::printf("\n%-10s   oracle plane |pitch err| p95 (mean):", matchers[m].c_str());
      for (int k = 0; k < 3; ++k) {
        std::vector<double> a;
        double mean = 0;
        for (double e : s.oracle_err[k]) {
          a.push_back(std::abs(e));
          mean += e / s.oracle_err[k].size();
        }
        std::printf(" %s %.3f (%+.3f)", k == 0 ? "all" : k == 1 ? "no-bottom-8" : "samples", percentile(a, 0.95), mean);
      }
    }
    std::printf("\n%-10s   pose |err| p95: pitch %.3f deg, roll %.3f deg, height %.4f m\n",
                matchers[m].c_str(), percentile(ap, 0.95), percentile(ar, 0.95), percentile(ah, 0.95));
  }
  return 0;
}
