// nerv_export: what a recorded drive holds, in forms other tools read.
//
//   nerv_export LOG --json [--no-blobs]     one JSON object per event on stdout
//   nerv_export LOG --disparity-png DIR     each DISPARITY as KITTI 16-bit PNG (d*256, 0 invalid)
//   nerv_export LOG --summary FILE [--prefix P]
//                                           run summary as JSON (and as text on stdout); of a log
//                                           of several pipelines (a channel prefix per camera)
//                                           the one of prefix P, else the first in the log
//   nerv_export --live --json [--no-blobs] [--lcm-url URL] [--channels REGEX] [--count N] [--seconds S]
//                                           the same JSON lines from live traffic on the bus
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "frame_name.hpp"
#include "json_writer.hpp"
#include "log_decode.hpp"
#include "log_summary.hpp"
#include "message_convert.hpp"
#include "message_json.hpp"
#include "nerv/disparity_t.hpp"

using namespace nerv;

namespace {

// One JSON line per event (shared by log and live export).
void printEvent(const std::string& channel, int64_t utime, const void* data, int size, bool blobs,
                int64_t& unknown) {
  JsonWriter msg(blobs);
  const std::string type = writeMessageJson(data, size, msg);
  JsonWriter line(blobs);
  line.beginObject();
  line.field("channel", channel);
  line.field("utime", utime);
  line.field("type", type.empty() ? std::string("unknown") : type);
  line.key("message");
  if (type.empty()) {
    if (channel != "LCM_SELF_TEST") ++unknown;  // LCM's own start-up probe
    line.value(std::vector<uint8_t>(static_cast<const uint8_t*>(data),
                                    static_cast<const uint8_t*>(data) + size));
    line.endObject();
    std::cout << line.str() << '\n';
  } else {
    // The message object is spliced in as already-written JSON.
    std::cout << line.str() << msg.str() << "}\n";
  }
}

struct LivePrinter {
  bool blobs;
  int64_t count = 0, unknown = 0;
  void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    printEvent(channel, rbuf->recv_utime, rbuf->data, rbuf->data_size, blobs, unknown);
    std::cout.flush();
    ++count;
  }
};

volatile sig_atomic_t g_stop = 0;

int exportLive(int argc, char** argv) {
  std::string url, channels = ".*";
  bool blobs = true;
  long long max_count = -1;
  double seconds = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--live" || a == "--json") continue;
    if (a == "--no-blobs") blobs = false;
    else if (a == "--lcm-url") url = value();
    else if (a == "--channels") channels = value();
    else if (a == "--count") max_count = std::stoll(value());
    else if (a == "--seconds") seconds = std::stod(value());
    else throw std::runtime_error("unknown flag '" + a + "'");
  }
  lcm::LCM lcm(url);
  if (!lcm.good()) throw std::runtime_error("LCM cannot start on '" + url + "'");
  LivePrinter printer{blobs};
  lcm.subscribe(channels, &LivePrinter::onMessage, &printer);
  signal(SIGINT, [](int) { g_stop = 1; });
  signal(SIGTERM, [](int) { g_stop = 1; });
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!g_stop && (max_count < 0 || printer.count < max_count) &&
         (seconds < 0 || std::chrono::steady_clock::now() < end))
    lcm.handleTimeout(50);
  return 0;
}

int exportJson(const std::string& path, bool blobs) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("log " + path + " cannot be read");
  int64_t unknown = 0;
  while (const lcm::LogEvent* e = log.readNextEvent())
    printEvent(e->channel, e->timestamp, e->data, e->datalen, blobs, unknown);
  if (unknown) std::fprintf(stderr, "nerv_export: %lld events of unknown type\n", (long long)unknown);
  return 0;
}

int exportDisparity(const std::string& path, const std::string& dir) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("log " + path + " cannot be read");
  std::filesystem::create_directories(dir);
  int written = 0;
  cv::Mat disparity, fixed;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    disparity_t msg;
    if (!decodeEvent(*e, msg)) continue;
    if (std::string why = decodeDisparity(msg, disparity); !why.empty()) {
      std::fprintf(stderr, "nerv_export: seq %lld: %s\n", (long long)msg.header.seq, why.c_str());
      continue;
    }
    disparity.convertTo(fixed, CV_16U, 256.0);  // KITTI: d * 256, 0 = invalid
    std::string name = frameName(msg.header.frame_id);
    if (name.empty()) name = std::to_string(msg.header.seq);
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "%06lld_", (long long)msg.header.seq);
    cv::imwrite(dir + "/" + prefix + name + ".png", fixed);
    ++written;
  }
  std::printf("%d disparity maps written to %s\n", written, dir.c_str());
  return written > 0 ? 0 : 1;
}

int summary(const std::string& path, const std::string& out, const std::optional<std::string>& prefix) {
  std::string text;
  const std::string json = summarizeLog(path, &text, prefix);
  if (!out.empty() && out != "-") {
    FILE* f = std::fopen(out.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + out);
    std::fputs(json.c_str(), f);
    std::fputs("\n", f);
    std::fclose(f);
  }
  std::fputs(text.c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc >= 2 && std::string(argv[1]) == "--live") return exportLive(argc, argv);
    if (argc < 3) throw std::runtime_error("usage: nerv_export LOG --json [--no-blobs] | --disparity-png DIR | --summary FILE");
    const std::string log = argv[1], mode = argv[2];
    if (!std::filesystem::exists(log)) throw std::runtime_error("log " + log + " does not exist");
    if (mode == "--json") return exportJson(log, !(argc > 3 && std::string(argv[3]) == "--no-blobs"));
    if (mode == "--disparity-png" && argc > 3) return exportDisparity(log, argv[3]);
    if (mode == "--summary") {
      std::optional<std::string> prefix;
      if (argc == 6 && std::string(argv[4]) == "--prefix") prefix = argv[5];
      else if (argc > 4) throw std::runtime_error("usage: nerv_export LOG --summary FILE [--prefix P]");
      return summary(log, argc > 3 ? argv[3] : "", prefix);
    }
    throw std::runtime_error("unknown mode '" + mode + "'");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_export: %s\n", e.what());
    return 2;
  }
}
