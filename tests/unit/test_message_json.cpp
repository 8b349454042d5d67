#include <gtest/gtest.h>

#include "json_writer.hpp"
#include "message_json.hpp"
#include "nerv/extrinsics_t.hpp"

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
