#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>

#include "json_writer.hpp"
#include "message_json.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/health_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

using namespace nerv;

TEST(toolsJsonWriter, EscapesAndBase64) {
  JsonWriter j;
  j.beginObject();
  j.field("s", std::string("a\"b\\c\n"));
  j.field("n", std::nan(""));
  j.field("b", std::vector<uint8_t>{'M', 'a', 'n', 'M', 'a'});
  j.endObject();
  EXPECT_EQ(j.str(), R"({"s":"a\"b\\c\n","n":null,"b":"TWFuTWE="})");
}

TEST(toolsMessageJson, DecodesByFingerprintWithFieldNames) {
  extrinsics_t e{};
  e.header.seq = 42;
  e.header.utime = 123456789;
  e.header.frame_id = "f/1";
  e.valid = true;
  e.status = "ok";
  e.pitch_deg = 1.5f;
  std::vector<uint8_t> buf(e.getEncodedSize());
  ASSERT_GT(e.encode(buf.data(), 0, buf.size()), 0);
  JsonWriter j;
  EXPECT_EQ(writeMessageJson(buf.data(), buf.size(), j), "nerv.extrinsics_t");
  const std::string s = j.str();
  EXPECT_NE(s.find(R"("header":{"seq":42,"utime":123456789,"frame_id":"f/1"})"), std::string::npos) << s;
  EXPECT_NE(s.find(R"("pitch_deg":1.5)"), std::string::npos) << s;
  JsonWriter k;
  EXPECT_EQ(writeMessageJson(buf.data(), 4, k), "");
}

// Every field of every message definition reaches the JSON export: a field
// added to an .lcm file but not to tools/lib/message_json.cpp fails here, so
// `nerv export --json` never silently drops data.
namespace {

// Field names of lcmtypes/<type>.lcm and, recursively, of the nerv types it uses.
void lcmFieldNames(const std::string& type, std::set<std::string>& names) {
  std::ifstream in(std::string(NERV_SOURCE_DIR) + "/lcmtypes/" + type + ".lcm");
  ASSERT_TRUE(in) << "lcmtypes/" << type << ".lcm";
  const std::regex field(R"(^\s*(\w+)\s+(\w+)\s*(\[[^\]]*\])?\s*;)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, field) || m[1] == "const" || m[1] == "package") continue;
    names.insert(m[2]);
    const std::string used = m[1];
    if (std::ifstream(std::string(NERV_SOURCE_DIR) + "/lcmtypes/" + used + ".lcm")) lcmFieldNames(used, names);
  }
}

template <class T>
void expectEveryField(const T& msg, const std::string& type) {
  std::vector<uint8_t> buf(msg.getEncodedSize());
  ASSERT_GT(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), 0);
  JsonWriter j;
  ASSERT_EQ(writeMessageJson(buf.data(), static_cast<int>(buf.size()), j), "nerv." + type);
  std::set<std::string> names;
  lcmFieldNames(type, names);
  ASSERT_GT(names.size(), 3u) << type;
  for (const std::string& n : names)
    EXPECT_NE(j.str().find("\"" + n + "\":"), std::string::npos) << type << " field '" << n << "' is not exported";
}

}  // namespace

TEST(toolsMessageJson, ExportsEveryFieldOfEveryMessage) {
  stereo_frame_t frame{};
  expectEveryField(frame, "stereo_frame_t");
  disparity_t disparity{};
  expectEveryField(disparity, "disparity_t");
  stixels_t stixels{};  // one element per array, so the element types are written too
  stixels.stixels.resize(1);
  stixels.num_stixels = 1;
  stixels.rois.resize(1);
  stixels.num_rois = 1;
  stixels.observed.resize(1);
  stixels.num_columns = 1;
  expectEveryField(stixels, "stixels_t");
  surface_normals_t normals{};
  normals.rois.resize(1);
  normals.num_rois = 1;
  expectEveryField(normals, "surface_normals_t");
  extrinsics_t extrinsics{};
  expectEveryField(extrinsics, "extrinsics_t");
  detections_t detections{};
  detections.detections.resize(1);
  detections.num_detections = 1;
  expectEveryField(detections, "detections_t");
  health_t health{};
  health.counter_names = {"bad_size"};
  health.counter_values = {1};
  health.num_counters = 1;
  health.gauge_names = {"row_offset_px"};
  health.gauge_values = {0.1};
  health.num_gauges = 1;
  expectEveryField(health, "health_t");
}
