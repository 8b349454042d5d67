// nerv_render's library on logs written here (or, with NERV_RENDER_LOG set by
// tests/integration/test_render_report.sh, on a real pipeline log): images of
// the expected size, boxes of a DETECTIONS message drawn at their pixels in
// their verdict's colour, broken messages skipped and counted.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "color_map.hpp"
#include "frame_grid.hpp"
#include "frame_render.hpp"
#include "log_frames.hpp"
#include "message_convert.hpp"
#include "mjpeg_avi.hpp"
#include "overlay_draw.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 320, kH = 240;

fs::path tempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("nerv_render_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

stereo_calibration_t calibration() {
  StereoCamera cam;
  cam.width = kW, cam.height = kH, cam.fx = cam.fy = 300, cam.cx = kW / 2.0, cam.cy = kH / 2.0, cam.baseline_m = 0.5;
  return toCalibration(cam);
}

header_t header(int64_t seq) {
  header_t h;
  h.seq = seq;
  h.utime = 1000000 + seq * 100000;
  h.frame_id = "test/" + std::to_string(seq);
  return h;
}

template <class T>
void put(lcm::LogFile& log, const std::string& channel, const T& msg, int64_t utime, int truncate_to = -1) {
  std::vector<uint8_t> buf(msg.getEncodedSize());
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  if (truncate_to >= 0) buf.resize(truncate_to);
  lcm::LogEvent e;
  e.eventnum = 0;
  e.timestamp = utime;
  e.channel = channel;
  e.datalen = static_cast<int32_t>(buf.size());
  e.data = buf.data();
  log.writeEvent(&e);
}

detection_t box(int id, int x, int y, int w, int h, bool kept, const char* label, const char* reason) {
  detection_t d{};
  d.roi_id = id;
  d.x = x, d.y = y, d.w = w, d.h = h;
  d.distance_m = 12.5f;
  d.label = label;
  d.kept = kept;
  d.reason = reason;
  d.score = 0.8f;
  return d;
}

// A mid-grey textured road scene: ground plane at 1.5 m below a level camera
// plus a wall (constant disparity) where the kept box is.
void writeFrame(lcm::LogFile& log, int64_t seq, const std::string& prefix, bool with_stereo = true) {
  const header_t h = header(seq);
  cv::Mat gray(kH, kW, CV_8U);
  cv::randu(gray, 90, 140);
  stereo_frame_t frame{};
  frame.header = h;
  frame.calib = calibration();
  frame.left = encodeImage(gray, "gray8");
  frame.right = frame.left;
  if (with_stereo) put(log, prefix + "STEREO_FRAME", frame, h.utime);

  cv::Mat disp(kH, kW, CV_32F, cv::Scalar(0));
  for (int v = kH / 2 + 2; v < kH; ++v) disp.row(v).setTo((v - kH / 2.0) * 0.5 / 1.5);
  disp(cv::Rect(40, 60, 80, 70)).setTo(12.0f);
  disparity_t dmsg{};
  dmsg.header = h;
  dmsg.calib = frame.calib;
  encodeDisparity(disp, "u16le", dmsg);
  dmsg.algorithm = "test";
  dmsg.min_disparity = 0;
  dmsg.max_disparity = 64;
  dmsg.processing_ms = 5;
  put(log, prefix + "DISPARITY", dmsg, h.utime + 1000);

  stixels_t st{};
  st.header = h;
  st.ground.valid = true;
  st.ground.source = "v_disparity";
  st.ground.vd_slope = 0.5f / 1.5f;
  st.ground.vd_intercept = -kH / 2.0f * 0.5f / 1.5f;
  st.ground.horizon_row = kH / 2.0f;
  st.ground.height_m = 1.5f;
  stixel_t s{};
  s.u = 40, s.width = 80, s.top_row = 60, s.bottom_row = 129, s.disparity = 12, s.depth_m = 12.5f;
  st.stixels = {s};
  st.num_stixels = 1;
  roi_t r{};
  r.id = 1, r.x = 40, r.y = 60, r.w = 80, r.h = 70;
  st.rois = {r};
  st.num_rois = 1;
  put(log, prefix + "STIXELS", st, h.utime + 2000);

  surface_normals_t n{};
  n.header = h;
  n.interval_px = 4;
  n.ground_normal_y = -1;
  put(log, prefix + "SURFACE_NORMALS", n, h.utime + 3000);

  extrinsics_t e{};
  e.header = h;
  e.valid = true;
  e.status = "ok";
  e.height_m = 1.5f;
  put(log, prefix + "EXTRINSICS", e, h.utime + 3000);

  detections_t det{};
  det.header = h;
  det.detections = {box(1, 40, 60, 80, 70, true, "object", ""), box(2, 200, 80, 60, 50, false, "ground", "ground normals 78%")};
  det.num_detections = 2;
  det.num_kept = 1;
  put(log, prefix + "DETECTIONS", det, h.utime + 4000);
}

bool near(const cv::Vec3b& a, const cv::Scalar& b, int tol = 40) {
  return std::abs(a[0] - b[0]) <= tol && std::abs(a[1] - b[1]) <= tol && std::abs(a[2] - b[2]) <= tol;
}

// The detection panel is panel 0: at (0, kTitleBarPx) at scale 1.
cv::Vec3b at(const cv::Mat& grid, int x, int y) {
  const cv::Point o = viz::panelOrigin(0, {grid.cols / viz::kGridColumns, 0});
  return grid.at<cv::Vec3b>(o.y + y, o.x + x);
}

// Expects the box's edges in its verdict's colour at the middles of its left and right edges.
void expectBoxDrawn(const cv::Mat& grid, const detection_t& d) {
  const cv::Scalar c = d.kept ? viz::kKeptColor : viz::kRemovedColor;
  const int ym = d.y + d.h / 2;
  EXPECT_TRUE(near(at(grid, d.x, ym), c)) << "left edge of box " << d.roi_id << " at (" << d.x << "," << ym << ") is "
                                          << at(grid, d.x, ym);
  EXPECT_TRUE(near(at(grid, d.x + d.w - 1, ym), c)) << "right edge of box " << d.roi_id << " is " << at(grid, d.x + d.w - 1, ym);
}

}  // namespace

TEST(renderOverlay, DrawsBoxesOfTheLogAtTheirPixels) {
  const fs::path dir = tempDir("boxes");
  const std::string log_path = (dir / "test.lcmlog").string();
  {
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    writeFrame(log, 7, "FRONT_");  // a channel prefix: types are found by fingerprint
    writeFrame(log, 8, "FRONT_");
  }
  viz::RenderOptions o;
  o.out_dir = (dir / "out").string();
  const viz::RenderResult r = viz::renderLog(log_path, o);
  EXPECT_EQ(r.rendered, 2);
  EXPECT_EQ(r.log.broken, 0);
  for (const char* name : {"000007.png", "000008.png"}) {
    const cv::Mat grid = cv::imread((dir / "out" / name).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(grid.empty()) << name;
    EXPECT_EQ(grid.cols, viz::kGridColumns * kW);
    EXPECT_EQ(grid.rows, viz::kGridRows * (kH + viz::kTitleBarPx));
    expectBoxDrawn(grid, box(1, 40, 60, 80, 70, true, "object", ""));
    expectBoxDrawn(grid, box(2, 200, 80, 60, 50, false, "ground", ""));
    // Inside a box the camera image stays grey (no fill).
    const cv::Vec3b inside = at(grid, 80, 95);
    EXPECT_EQ(inside[0], inside[1]);
    EXPECT_EQ(inside[1], inside[2]);
  }
  fs::remove_all(dir);
}

TEST(renderOverlay, UnobservedStripsAreMarkedAlongTheLowerEdge) {
  cv::Mat panel(100, 200, CV_8UC3, cv::Scalar::all(0));
  stixels_t st{};
  st.column_width_px = 5;
  st.num_columns = 40;
  st.observed.assign(40, 1.0f);
  for (int k = 0; k < 10; ++k) st.observed[k] = 0.1f;  // columns 0-49 unseen
  st.observed[20] = 0.3f;                              // at the threshold: observed
  st.min_observed = 0.3f;
  viz::drawStixels(panel, st);
  auto magenta = [&](int u, int v) { return panel.at<cv::Vec3b>(v, u) == cv::Vec3b(255, 0, 255); };
  EXPECT_TRUE(magenta(0, 99));
  EXPECT_TRUE(magenta(49, 100 - viz::kUnobservedBandPx));
  EXPECT_FALSE(magenta(49, 100 - viz::kUnobservedBandPx - 1));  // a band, not the strip
  EXPECT_FALSE(magenta(50, 99));
  EXPECT_FALSE(magenta(102, 99));
}

TEST(renderOverlay, BrokenMessagesAreSkippedAndCounted) {
  const fs::path dir = tempDir("broken");
  const std::string log_path = (dir / "test.lcmlog").string();
  {
    lcm::LogFile log(log_path, "w");
    writeFrame(log, 1, "");
    detections_t det{};
    det.header = header(2);
    det.detections = {box(1, 1, 1, 5, 5, true, "object", "")};
    det.num_detections = 1;
    put(log, "DETECTIONS", det, 5000000, 20);   // right fingerprint, cut short
    put(log, "GARBAGE", det, 5000001, 5);       // shorter than a fingerprint
    writeFrame(log, 3, "");
  }
  viz::RenderOptions o;
  o.out_dir = (dir / "out").string();
  const viz::RenderResult r = viz::renderLog(log_path, o);
  EXPECT_EQ(r.rendered, 2);
  EXPECT_EQ(r.log.broken, 1);
  EXPECT_EQ(r.log.broken_per_channel.at("DETECTIONS"), 1);
  EXPECT_EQ(r.log.other_messages, 1);
  fs::remove_all(dir);
}

TEST(renderOverlay, LogWithoutStereoFramesRendersNothing) {
  const fs::path dir = tempDir("nostereo");
  const std::string log_path = (dir / "test.lcmlog").string();
  {
    lcm::LogFile log(log_path, "w");
    writeFrame(log, 1, "", false);
  }
  viz::RenderOptions o;
  o.out_dir = (dir / "out").string();
  const viz::RenderResult r = viz::renderLog(log_path, o);
  EXPECT_EQ(r.log.stereo_frames, 0);
  EXPECT_EQ(r.rendered, 0);
  EXPECT_EQ(r.skipped, 1);
  EXPECT_NE(r.first_problem.find("no STEREO_FRAME"), std::string::npos) << r.first_problem;
  fs::remove_all(dir);
}

TEST(renderOverlay, MissingLogThrows) {
  viz::RenderOptions o;
  o.out_dir = (fs::temp_directory_path() / "nerv_render_test_missing").string();
  EXPECT_THROW(viz::renderLog("/nonexistent/nerv.lcmlog", o), std::runtime_error);
}

TEST(renderOverlay, FrameRangeSelectsSeqs) {
  const fs::path dir = tempDir("range");
  const std::string log_path = (dir / "test.lcmlog").string();
  {
    lcm::LogFile log(log_path, "w");
    for (int s = 0; s < 5; ++s) writeFrame(log, s, "");
  }
  viz::RenderOptions o;
  o.out_dir = (dir / "out").string();
  o.seq_min = 1;
  o.seq_max = 3;
  EXPECT_EQ(viz::renderLog(log_path, o).rendered, 3);
  EXPECT_FALSE(fs::exists(dir / "out" / "000000.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "000003.png"));
  EXPECT_FALSE(fs::exists(dir / "out" / "000004.png"));
  fs::remove_all(dir);
}

TEST(renderOverlay, RemovalCodes) {
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "ground", "ground normals 78%")), "GND 78%");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "error", "error normals 61.5% facing")), "ERR 61.5%");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "unvalidated", "unvalidated: no normals")), "UNV none");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "unvalidated", "unvalidated: only 3 normals (< 5)")), "UNV few");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "error", "height 6.05 m above 4.50 m")), "ERR tall");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "error", "width 9.00 m above 6.00 m")), "ERR wide");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "unvalidated", "")), "UNV");
  EXPECT_EQ(viz::removalCode(box(1, 0, 0, 1, 1, false, "weird", "")), "WEI");
}

// An AVI the writer made reads back: RIFF/AVI header, frame count, and every
// indexed chunk a JPEG of the frame size.
TEST(renderOverlay, MjpegAviReadsBack) {
  const fs::path dir = tempDir("avi");
  const std::string path = (dir / "v.avi").string();
  {
    viz::MjpegAviWriter w;
    ASSERT_TRUE(w.open(path, {64, 48}, 10));
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 80, 50, 200))));
    EXPECT_FALSE(w.write(cv::Mat(10, 10, CV_8UC3)));
    ASSERT_TRUE(w.close());
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> b((std::istreambuf_iterator<char>(in)), {});
  auto u32 = [&](size_t o) { return uint32_t(b[o]) | uint32_t(b[o + 1]) << 8 | uint32_t(b[o + 2]) << 16 | uint32_t(b[o + 3]) << 24; };
  auto tag = [&](size_t o) { return std::string(b.begin() + o, b.begin() + o + 4); };
  ASSERT_GT(b.size(), 300u);
  EXPECT_EQ(tag(0), "RIFF");
  EXPECT_EQ(u32(4), b.size() - 8);
  EXPECT_EQ(tag(8), "AVI ");
  EXPECT_EQ(tag(24), "avih");
  EXPECT_EQ(u32(48), 3u);      // total frames
  EXPECT_EQ(u32(64), 64u);     // width
  EXPECT_EQ(u32(68), 48u);     // height
  EXPECT_EQ(tag(112), "MJPG");
  // 'movi' follows the header lists; its LIST size leads to 'idx1'.
  const std::string head(b.begin(), b.begin() + 400);
  const size_t movi = head.find("movi");
  ASSERT_NE(movi, std::string::npos);
  ASSERT_EQ(tag(movi - 8), "LIST");
  const size_t idx1 = movi + u32(movi - 4);
  ASSERT_EQ(tag(idx1), "idx1");
  ASSERT_EQ(u32(idx1 + 4), 3u * 16);
  for (int i = 0; i < 3; ++i) {
    const size_t e = idx1 + 8 + i * 16;
    EXPECT_EQ(tag(e), "00dc");
    const size_t chunk = movi + u32(e + 8);
    EXPECT_EQ(tag(chunk), "00dc");
    ASSERT_EQ(u32(chunk + 4), u32(e + 12));
    const std::vector<uint8_t> jpeg(b.begin() + chunk + 8, b.begin() + chunk + 8 + u32(e + 12));
    const cv::Mat img = cv::imdecode(jpeg, cv::IMREAD_COLOR);
    ASSERT_EQ(img.size(), cv::Size(64, 48));
    EXPECT_NEAR(img.at<cv::Vec3b>(24, 32)[0], i * 80, 8);
  }
  fs::remove_all(dir);
}

// With NERV_RENDER_LOG and NERV_RENDER_DIR (PNGs nerv_render made from that
// log), every kept box that no other box comes near is drawn in green at the
// middle of its left and right edges.
TEST(renderOverlay, PipelineLogBoxesAtTheirPixels) {
  const char* log_path = std::getenv("NERV_RENDER_LOG");
  const char* png_dir = std::getenv("NERV_RENDER_DIR");
  if (!log_path || !png_dir) GTEST_SKIP() << "set by tests/integration/test_render_report.sh";
  LogFrameOptions read;
  read.keep_images = false;
  LogFrameReader reader(log_path, read);
  LogFrame f;
  int frames = 0, boxes = 0;
  while (reader.next(f)) {
    if (!f.detections || !f.stereo) continue;
    const cv::Mat grid = cv::imread(std::string(png_dir) + cv::format("/%06lld.png", static_cast<long long>(f.seq)));
    ASSERT_FALSE(grid.empty()) << "no image for seq " << f.seq;
    EXPECT_EQ(grid.cols, viz::kGridColumns * f.stereo->left.width);
    EXPECT_EQ(grid.rows, viz::kGridRows * (f.stereo->left.height + viz::kTitleBarPx));
    ++frames;
    const auto& dets = f.detections->detections;
    for (size_t i = 0; i < dets.size(); ++i) {
      const auto& d = dets[i];
      if (!d.kept || d.w < 8 || d.h < 30 || d.x < 0 || d.y < 0 || d.x + d.w > f.stereo->left.width ||
          d.y + d.h > f.stereo->left.height)
        continue;
      // Others' boxes and labels (up to 20 px above a box) must stay clear of both edge middles.
      const cv::Rect probe_l(d.x - 2, d.y + d.h / 2 - 2, 5, 5), probe_r(d.x + d.w - 3, d.y + d.h / 2 - 2, 5, 5);
      bool clear = true;
      for (size_t j = 0; j < dets.size() && clear; ++j) {
        if (j == i) continue;
        const cv::Rect other(dets[j].x - 120, dets[j].y - 20, dets[j].w + 240, dets[j].h + 24);
        clear = (other & probe_l).area() == 0 && (other & probe_r).area() == 0;
      }
      if (!clear) continue;
      expectBoxDrawn(grid, d);
      ++boxes;
    }
  }
  EXPECT_GT(frames, 0);
  EXPECT_GT(boxes, 0) << "no isolated kept box to check in the log";
  std::printf("checked %d isolated kept boxes in %d frames\n", boxes, frames);
}
