// nerv_diff: where two recorded runs differ, per channel and frame.
//
//   nerv_diff LOG_A LOG_B [--channels STIXELS,EXTRINSICS,...] [--max-lines N]
//
// Messages are matched by channel (its prefix included: a log of several cameras holds a pipeline
// per prefix, whose seqs overlap) and header.seq and compared field by field
// (as JSON) with timing fields (processing_ms) set aside. Health, frames and
// other channels without a frame header are skipped by default. Exit 0 when
// the compared channels are identical, 1 when they differ, 2 on error.
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "json_writer.hpp"
#include "log_decode.hpp"
#include "message_json.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

using namespace nerv;

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// channel -> seq -> JSON of the message without timing fields
using Run = std::map<std::string, std::map<int64_t, std::string>>;

template <class T>
bool canonical(const lcm::LogEvent& e, int64_t& seq, std::string& json) {
  T msg;
  if (!decodeEvent(e, msg)) return false;
  msg.processing_ms = 0;  // timing differs between runs by nature
  std::vector<uint8_t> buf(msg.getEncodedSize());
  msg.encode(buf.data(), 0, buf.size());
  JsonWriter j(true);
  writeMessageJson(buf.data(), static_cast<int>(buf.size()), j);
  seq = msg.header.seq;
  json = j.str();
  return true;
}

Run readRun(const std::string& path, const std::set<std::string>& channels) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("log " + path + " does not exist");
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("log " + path + " cannot be read");
  Run run;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (std::none_of(channels.begin(), channels.end(), [&](const std::string& c) { return endsWith(e->channel, c); }))
      continue;
    int64_t seq = 0;
    std::string json;
    const bool ok = canonical<detections_t>(*e, seq, json) || canonical<stixels_t>(*e, seq, json) ||
                    canonical<extrinsics_t>(*e, seq, json) || canonical<surface_normals_t>(*e, seq, json) ||
                    canonical<disparity_t>(*e, seq, json);
    if (ok) run[e->channel][seq] = json;
  }
  return run;
}

// The JSON key path around the first differing character, for a readable report.
std::string firstDifference(const std::string& a, const std::string& b) {
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  const size_t key_end = a.rfind("\":", i);
  const size_t key_start = key_end == std::string::npos ? std::string::npos : a.rfind('"', key_end - 1);
  std::string key = key_start == std::string::npos ? "?" : a.substr(key_start + 1, key_end - key_start - 1);
  auto value = [&](const std::string& s) {
    const size_t from = key_end == std::string::npos ? i : key_end + 2;
    return s.substr(from, std::min<size_t>(40, s.find_first_of(",}", from) - from));
  };
  return key + ": " + value(a) + " vs " + value(b);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 3) throw std::runtime_error("usage: nerv_diff LOG_A LOG_B [--channels A,B] [--max-lines N]");
    std::set<std::string> channels = {"DISPARITY", "STIXELS", "SURFACE_NORMALS", "EXTRINSICS", "DETECTIONS"};
    int max_lines = 20;
    for (int i = 3; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--channels" && i + 1 < argc) {
        channels.clear();
        std::stringstream list(argv[++i]);
        for (std::string c; std::getline(list, c, ',');) channels.insert(c);
      } else if (a == "--max-lines" && i + 1 < argc) {
        max_lines = std::stoi(argv[++i]);
      } else {
        throw std::runtime_error("unknown flag '" + a + "'");
      }
    }
    const Run a = readRun(argv[1], channels), b = readRun(argv[2], channels);
    bool differ = false;
    int lines = 0;
    // Each channel of either log (FRONT_STIXELS and REAR_STIXELS apart), and a compared channel
    // neither holds as a line of zeros.
    std::set<std::string> names;
    for (const Run* r : {&a, &b})
      for (const auto& [ch, m] : *r) names.insert(ch);
    for (const auto& c : channels)
      if (std::none_of(names.begin(), names.end(), [&](const std::string& n) { return endsWith(n, c); })) names.insert(c);
    for (const auto& ch : names) {
      const auto& ma = a.count(ch) ? a.at(ch) : std::map<int64_t, std::string>{};
      const auto& mb = b.count(ch) ? b.at(ch) : std::map<int64_t, std::string>{};
      int same = 0, changed = 0, only_a = 0, only_b = 0;
      for (const auto& [seq, ja] : ma) {
        auto it = mb.find(seq);
        if (it == mb.end()) {
          ++only_a;
          if (lines++ < max_lines) std::printf("  %s seq %lld: only in A\n", ch.c_str(), (long long)seq);
        } else if (it->second == ja) {
          ++same;
        } else {
          ++changed;
          if (lines++ < max_lines)
            std::printf("  %s seq %lld: %s\n", ch.c_str(), (long long)seq, firstDifference(ja, it->second).c_str());
        }
      }
      for (const auto& [seq, jb] : mb)
        if (!ma.count(seq)) {
          ++only_b;
          if (lines++ < max_lines) std::printf("  %s seq %lld: only in B\n", ch.c_str(), (long long)seq);
        }
      std::printf("%-16s %5d identical %5d differ %5d only in A %5d only in B\n", ch.c_str(), same, changed, only_a, only_b);
      differ = differ || changed || only_a || only_b;
    }
    std::printf(differ ? "runs differ\n" : "runs are identical (timing fields aside)\n");
    return differ ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_diff: %s\n", e.what());
    return 2;
  }
}
