// nerv_source: plays a dataset folder as STEREO_FRAME messages.
//
//   nerv_source --data DIR [--rate HZ] [--in-flight K] [--encoding gray8|bgr8|png|jpeg]
//               [--frames N] [--wait-for svc[/instance],...] [--drain-timeout S] [--lcm-url URL]
//               [--prefix P] [--no-wait] [--check] [--repeat N]
//
// --rate 0 publishes as fast as the pipeline takes frames: at most K frames
// without DETECTIONS at any time. After the last frame it waits for every
// frame's DETECTIONS; exit 0 when all arrived, 3 when some did not. A folder with
// raw_calib.yaml holds raw views: they go out unrectified with the rig's calibration.
//
// The environment variable NERV_SOURCE_MAX_RATE (Hz) caps --rate for every source a
// script starts: `tools/nerv sanitize` plays the multiprocess tests at 1 Hz that way,
// as the sanitized stereo_matcher needs about 300 ms a frame (--rate 0 is left as is:
// it waits for the answers anyway).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <thread>

#include "dataset.hpp"
#include "lcm_node.hpp"
#include "message_convert.hpp"
#include "nerv/detections_t.hpp"
#include "build_version.hpp"
#include "nerv/health_t.hpp"

using namespace nerv;

namespace {

struct Options {
  std::string data, encoding = "gray8", lcm_url, prefix;
  double rate_hz = 10;
  int in_flight = 2;
  int max_frames = -1;
  int repeat = 1;
  double drain_timeout_s = 30, startup_timeout_s = 20;
  std::set<std::string> wait_for;
  bool wait_detections = true;
  bool check_only = false;
  bool version = false;  // --version: print the build and exit
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
      return argv[++i];
    };
    auto number = [&]() {
      const std::string v = value();
      try {
        size_t used = 0;
        const double d = std::stod(v, &used);
        if (used != v.size()) throw std::invalid_argument(v);
        return d;
      } catch (const std::exception&) {
        throw std::runtime_error("flag " + a + " needs a number, got '" + v + "'");
      }
    };
    if (a == "--data") o.data = value();
    else if (a == "--rate") o.rate_hz = number();
    else if (a == "--in-flight") o.in_flight = static_cast<int>(number());
    else if (a == "--encoding") o.encoding = value();
    else if (a == "--frames") o.max_frames = static_cast<int>(number());
    else if (a == "--repeat") o.repeat = static_cast<int>(number());
    else if (a == "--drain-timeout") o.drain_timeout_s = number();
    else if (a == "--startup-timeout") o.startup_timeout_s = number();
    else if (a == "--lcm-url") o.lcm_url = value();
    else if (a == "--prefix") o.prefix = value();
    else if (a == "--no-wait") o.wait_detections = false;
    else if (a == "--check") o.check_only = true;
    else if (a == "--version") o.version = true;
    else if (a == "--wait-for") {
      std::stringstream list(value());
      for (std::string s; std::getline(list, s, ',');)
        if (!s.empty()) o.wait_for.insert(s);
    } else throw std::runtime_error("unknown flag '" + a + "'");
  }
  if (o.version) return o;
  if (o.data.empty() && o.max_frames != 0) throw std::runtime_error("--data DIR is required");
  if (o.rate_hz < 0) throw std::runtime_error("--rate must be >= 0");
  if (const char* cap = std::getenv("NERV_SOURCE_MAX_RATE"); cap && *cap) {
    char* end = nullptr;
    const double max_hz = std::strtod(cap, &end);
    if (*end != '\0' || !(max_hz > 0) || !std::isfinite(max_hz))
      throw std::runtime_error(std::string("NERV_SOURCE_MAX_RATE must be a rate above 0 Hz, not '") + cap + "'");
    if (o.rate_hz > max_hz) {
      std::fprintf(stderr, "source: --rate %g capped at %g Hz by NERV_SOURCE_MAX_RATE\n", o.rate_hz, max_hz);
      o.rate_hz = max_hz;
    }
  }
  if (o.in_flight < 1) throw std::runtime_error("--in-flight must be >= 1");
  if (o.repeat < 1) throw std::runtime_error("--repeat must be >= 1");
  if (o.encoding != "gray8" && o.encoding != "bgr8" && o.encoding != "png" && o.encoding != "jpeg")
    throw std::runtime_error("--encoding must be gray8, bgr8, png or jpeg");
  return o;
}

stereo_frame_t makeFrame(const Dataset& ds, const DatasetFrame& f, const std::string& encoding) {
  const bool gray = encoding == "gray8" || encoding == "png" || encoding == "jpeg";
  const int mode = gray ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR;
  const cv::Mat left = cv::imread(f.left_path, mode), right = cv::imread(f.right_path, mode);
  if (left.empty()) throw std::runtime_error("image " + f.left_path + " cannot be read");
  if (right.empty()) throw std::runtime_error("image " + f.right_path + " cannot be read");
  stereo_frame_t msg{};
  msg.header.frame_id = std::filesystem::path(ds.root).filename().string() + "/" + f.name;
  // Raw views (raw_calib.yaml) go out as they are, with the rig's calibration: the
  // stereo_matcher rectifies them on ingest.
  msg.calib = f.raw ? toCalibration(*f.raw, f.camera) : toCalibration(f.camera);
  msg.left = encodeImage(left, encoding);
  msg.right = encodeImage(right, encoding);
  return msg;
}

int play(const Options& o) {
  // --frames 0 without data: only wait for the services' health (used by replay).
  const Dataset ds = o.data.empty() ? Dataset{} : openDataset(o.data);
  if (o.check_only) return 0;  // --check: the dataset opens, nothing else to do
  const size_t distinct = o.max_frames >= 0 ? std::min<size_t>(o.max_frames, ds.frames.size())
                                            : ds.frames.size();
  const size_t count = distinct * o.repeat;  // --repeat plays the sequence again with new seqs
  // Frames are read before the clock starts so disk speed does not shape the stream.
  std::vector<stereo_frame_t> frames;
  for (size_t i = 0; i < distinct; ++i) frames.push_back(makeFrame(ds, ds.frames[i], o.encoding));

  NodeOptions opts;
  opts.service = "source";
  opts.lcm_url = o.lcm_url;
  opts.channel_prefix = o.prefix;
  Node node(opts);
  std::set<std::string> seen_services;
  std::set<int64_t> detected;
  // --wait-for names a service (any instance will do) or one instance ("stereo_matcher/shard1"):
  // with shards, every shard must be up, or the first frames of a late one are lost.
  // Any layout: a service of an older build on another computer counts as up too.
  node.onHealthReport([&](const health_t& h) {
    seen_services.insert(h.service);
    seen_services.insert(h.service + "/" + h.instance);
  });
  node.subscribe<detections_t>("DETECTIONS", [&](const detections_t& d) {
    if (d.header.seq >= 0 && d.header.seq < static_cast<int64_t>(count)) detected.insert(d.header.seq);
  }, 50);

  using clock = std::chrono::steady_clock;
  auto deadline = clock::now() + std::chrono::duration<double>(o.startup_timeout_s);
  auto missing = [&] {
    std::string m;
    for (const auto& s : o.wait_for)
      if (!seen_services.count(s)) m += (m.empty() ? "" : ",") + s;
    return m;
  };
  while (!missing().empty() && !Node::stopRequested()) {
    if (clock::now() > deadline) {
      std::fprintf(stderr, "source: no health from %s within %.0f s\n", missing().c_str(),
                   o.startup_timeout_s);
      return 3;
    }
    node.poll(50);
  }

  const auto start = clock::now();
  const auto period = std::chrono::duration<double>(o.rate_hz > 0 ? 1.0 / o.rate_hz : 0.0);
  for (size_t i = 0; i < count && !Node::stopRequested(); ++i) {
    if (o.rate_hz > 0) {
      const auto due = start + std::chrono::duration_cast<clock::duration>(period * double(i));
      while (clock::now() < due) {
        const auto left_ms = std::chrono::duration_cast<std::chrono::milliseconds>(due - clock::now()).count();
        node.poll(static_cast<int>(std::max<long long>(0, std::min<long long>(left_ms, 20))));
      }
    } else if (o.wait_detections) {
      // Keep at most in_flight frames without an answer; a frame that never
      // comes back is given up after drain_timeout so the stream goes on.
      const auto wait_until = clock::now() + std::chrono::duration<double>(o.drain_timeout_s);
      while (static_cast<int64_t>(i) - static_cast<int64_t>(detected.size()) >= o.in_flight &&
             clock::now() < wait_until && !Node::stopRequested())
        node.poll(5);
    }
    stereo_frame_t& msg = frames[i % distinct];
    msg.header.seq = static_cast<int64_t>(i);
    msg.header.utime = nowUtime();
    node.publish("STEREO_FRAME", msg);
    node.countOut(msg.header.utime, 0);
    std::fprintf(stderr, "\rsource: sent %zu/%zu, detected %zu ", i + 1, count, detected.size());
    node.poll(0);
  }
  if (o.wait_detections) {
    deadline = clock::now() + std::chrono::duration<double>(o.drain_timeout_s);
    while (detected.size() < count && clock::now() < deadline && !Node::stopRequested()) {
      node.poll(20);
      std::fprintf(stderr, "\rsource: sent %zu/%zu, detected %zu ", count, count, detected.size());
    }
  }
  node.reportHealth();
  const double seconds = std::chrono::duration<double>(clock::now() - start).count();
  std::fprintf(stderr, "\rsource: sent %zu frames in %.2f s, %zu with DETECTIONS\n", count,
               seconds, detected.size());
  if (o.wait_detections && detected.size() < count) {
    std::string lost;
    for (size_t i = 0; i < count; ++i)
      if (!detected.count(static_cast<int64_t>(i))) lost += (lost.empty() ? "" : ",") + std::to_string(i);
    std::fprintf(stderr, "source: no DETECTIONS for frames %s within %.0f s\n", lost.c_str(),
                 o.drain_timeout_s);
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    if (o.version) return std::printf("nerv_source: nerv %s\n", buildVersion()), 0;
    return play(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_source: %s\n", e.what());
    return 2;
  }
}
