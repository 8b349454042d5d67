// nerv_export: what a recorded drive holds, in forms other tools read.
//
//   nerv_export LOG --json [--no-blobs]     one JSON object per event on stdout
//   nerv_export LOG --disparity-png DIR     each DISPARITY as KITTI 16-bit PNG (d*256, 0 invalid)
//   nerv_export LOG --summary FILE          run summary as JSON (and as text on stdout)
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "json_writer.hpp"
#include "log_summary.hpp"
#include "message_convert.hpp"
#include "message_json.hpp"
#include "nerv/disparity_t.hpp"

using namespace nerv;

namespace {

int exportJson(const std::string& path, bool blobs) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("log " + path + " cannot be read");
  int64_t unknown = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    JsonWriter msg(blobs);
    const std::string type = writeMessageJson(e->data, e->datalen, msg);
    JsonWriter line(blobs);
    line.beginObject();
    line.field("channel", e->channel);
    line.field("utime", e->timestamp);
    line.field("type", type.empty() ? std::string("unknown") : type);
    line.key("message");
    if (type.empty()) {
      if (e->channel != "LCM_SELF_TEST") ++unknown;  // LCM's own start-up probe
      line.value(std::vector<uint8_t>(static_cast<const uint8_t*>(e->data),
                                      static_cast<const uint8_t*>(e->data) + e->datalen));
      line.endObject();
      std::cout << line.str() << '\n';
    } else {
      // The message object is spliced in as already-written JSON.
      std::string s = line.str();
      std::cout << s << msg.str() << "}\n";
    }
  }
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
    if (e->datalen < 8 || msg.decode(e->data, 0, e->datalen) < 0) continue;
    if (std::string why = decodeDisparity(msg, disparity); !why.empty()) {
      std::fprintf(stderr, "nerv_export: seq %lld: %s\n", (long long)msg.header.seq, why.c_str());
      continue;
    }
    disparity.convertTo(fixed, CV_16U, 256.0);  // KITTI: d * 256, 0 = invalid
    std::string name = msg.header.frame_id;
    name = name.substr(name.find_last_of('/') + 1);
    if (name.empty()) name = std::to_string(msg.header.seq);
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "%06lld_", (long long)msg.header.seq);
    cv::imwrite(dir + "/" + prefix + name + ".png", fixed);
    ++written;
  }
  std::printf("%d disparity maps written to %s\n", written, dir.c_str());
  return written > 0 ? 0 : 1;
}

int summary(const std::string& path, const std::string& out) {
  std::string text;
  const std::string json = summarizeLog(path, &text);
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
    if (argc < 3) throw std::runtime_error("usage: nerv_export LOG --json [--no-blobs] | --disparity-png DIR | --summary FILE");
    const std::string log = argv[1], mode = argv[2];
    if (!std::filesystem::exists(log)) throw std::runtime_error("log " + log + " does not exist");
    if (mode == "--json") return exportJson(log, !(argc > 3 && std::string(argv[3]) == "--no-blobs"));
    if (mode == "--disparity-png" && argc > 3) return exportDisparity(log, argv[3]);
    if (mode == "--summary") return summary(log, argc > 3 ? argv[3] : "");
    throw std::runtime_error("unknown mode '" + mode + "'");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_export: %s\n", e.what());
    return 2;
  }
}
