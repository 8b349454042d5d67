// Test helper: publishes malformed STEREO_FRAME / DISPARITY messages (and ones of another
// layout, as a process of an older build sends), then one good frame, and checks over LCM that
// the stereo_matcher and stixel services counted each rejection in NERV_HEALTH and still produce
// output afterwards; and that an older build's NERV_HEALTH is read (a twin stixel/0 is named).
// Exit 0 when every expectation holds; prints what it saw either way.
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <thread>

#include "inject_bus.hpp"
#include "message_convert.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/health_t.hpp"
#include "nerv/health_v1_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"

using namespace nerv;

namespace {

struct Listener {
  std::map<std::string, std::map<std::string, int64_t>> counters;  // service -> counter -> value
  std::map<std::string, int64_t> outputs;                          // channel -> count
  void health(const lcm::ReceiveBuffer*, const std::string&, const health_t* h) {
    auto& mine = counters[h->service];  // present once the service has reported at all
    for (int i = 0; i < h->num_counters; ++i) mine[h->counter_names[i]] = h->counter_values[i];
  }
  void disparity(const lcm::ReceiveBuffer*, const std::string& ch, const disparity_t*) { ++outputs[ch]; }
  void stixels(const lcm::ReceiveBuffer*, const std::string& ch, const stixels_t*) { ++outputs[ch]; }
};

stereo_frame_t frame(int64_t seq) {
  StereoCamera cam;
  cam.width = 320;
  cam.height = 120;
  cam.fx = cam.fy = 200;
  cam.cx = 160;
  cam.cy = 60;
  cam.baseline_m = 0.5;
  cv::Mat img(cam.height, cam.width, CV_8UC1);
  cv::randu(img, 0, 255);
  stereo_frame_t f;
  f.header.seq = seq;
  f.header.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                       std::chrono::system_clock::now().time_since_epoch()).count();
  f.header.frame_id = "inject/" + std::to_string(seq);
  f.calib = toCalibration(cam);
  f.left = encodeImage(img, "gray8");
  f.right = encodeImage(img, "gray8");
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  const auto bus = test::openBus(argc, argv);
  if (!bus) return 2;
  lcm::LCM& lcm = *bus;
  Listener l;
  lcm.subscribe("NERV_HEALTH", &Listener::health, &l);
  lcm.subscribe("DISPARITY", &Listener::disparity, &l);
  lcm.subscribe("STIXELS", &Listener::stixels, &l);

  // The services must be listening before anything is sent.
  test::handleUntil(lcm, std::chrono::seconds(10),
                    [&] { return l.counters.count("stereo_matcher") && l.counters.count("stixel"); });

  // The services keep short queues (older frames are dropped under load), so
  // each message gets time to be handled before the next one.
  auto settle = [&] { test::handleFor(lcm, std::chrono::milliseconds(150)); };

  // 1. bytes that are no message at all
  const std::string garbage = "this is not an LCM message";
  lcm.publish("STEREO_FRAME", garbage.data(), garbage.size());
  settle();
  lcm.publish("DISPARITY", garbage.data(), garbage.size());
  settle();
  // 1b. the right type with a corrupt array length (decode fails: cmake/LcmDecoderBounds.cmake)
  {
    stereo_frame_t c = frame(99);
    c.left.encoding = "png";
    c.left.data = {0xAB, 0xCD, 0xEF};
    c.left.size = 3;
    std::vector<uint8_t> bytes(c.getEncodedSize());
    c.encode(bytes.data(), 0, bytes.size());
    const uint8_t marker[] = {0, 0, 0, 3, 0xAB, 0xCD, 0xEF};
    auto at = std::search(bytes.begin(), bytes.end(), std::begin(marker), std::end(marker));
    if (at == bytes.end()) {
      std::fprintf(stderr, "inject: cannot find the array length to corrupt\n");
      return 2;
    }
    std::fill(at, at + 4, 0xFF);  // size = -1
    lcm.publish("STEREO_FRAME", bytes.data(), bytes.size());
    settle();
  }
  // 1c. a message of another layout on a data channel (as from a process of an older build):
  // dropped and named as another build's layout
  {
    health_v1_t old{};
    old.service = "stixel";
    old.num_counters = 0;
    lcm.publish("DISPARITY", &old);
    settle();
  }
  // 1d. NERV_HEALTH in the first layout (a computer still on an older build) from a second
  // stixel/0: the running stixel service must read it and name the duplicate
  {
    health_v1_t twin{};
    twin.service = "stixel";
    twin.instance = "0";
    twin.host = "old-pc";
    twin.pid = 4242;
    twin.status = "ok";
    twin.num_counters = 0;
    lcm.publish("NERV_HEALTH", &twin);
    settle();
  }
  // 2. the image's byte count disagrees with its width, height and channels: 7 bytes more
  // (size must stay the data's length, which LCM encodes: a larger size alone read past it)
  stereo_frame_t f = frame(100);
  f.left.data.resize(f.left.data.size() + 7, 0);
  f.left.size += 7;
  lcm.publish("STEREO_FRAME", &f);
  settle();
  // 3. left and right of different sizes
  f = frame(101);
  cv::Mat small(60, 320, CV_8UC1, cv::Scalar(3));
  f.right = encodeImage(small, "gray8");
  lcm.publish("STEREO_FRAME", &f);
  settle();
  // 4. NaN calibration
  f = frame(102);
  f.calib.fx = NAN;
  lcm.publish("STEREO_FRAME", &f);
  settle();
  // 5. a disparity whose size does not match its calibration
  disparity_t d;
  d.header = frame(103).header;
  d.calib = frame(103).calib;
  encodeDisparity(cv::Mat(50, 50, CV_32F, cv::Scalar(5.f)), "u16le", d);
  encodeConfidence(cv::Mat(), d);
  lcm.publish("DISPARITY", &d);
  settle();
  // 6. a good frame: the services must still work
  f = frame(104);
  lcm.publish("STEREO_FRAME", &f);
  settle();

  auto expectations = [&] {
    auto c = [&](const char* svc, const char* name) { return l.counters[svc][name]; };
    return c("stereo_matcher", "decode_failed") >= 2 && c("stereo_matcher", "bad_size") >= 1 &&
           c("stereo_matcher", "size_mismatch") >= 1 && c("stereo_matcher", "bad_calibration") >= 1 &&
           c("stixel", "decode_failed") >= 2 && c("stixel", "size_mismatch") >= 1 &&
           c("stixel", "duplicate_instance") >= 1 &&
           l.outputs["DISPARITY"] >= 1 && l.outputs["STIXELS"] >= 1;
  };
  test::handleUntil(lcm, std::chrono::seconds(10), expectations, 100);

  for (const auto& [svc, counters] : l.counters)
    for (const auto& [name, value] : counters) std::printf("%s.%s = %lld\n", svc.c_str(), name.c_str(), (long long)value);
  for (const auto& [ch, n] : l.outputs) std::printf("output %s: %lld\n", ch.c_str(), (long long)n);
  if (!expectations()) {
    std::fprintf(stderr, "inject: not every rejection was counted, or no output after the bad input\n");
    return 1;
  }
  return 0;
}
