// nerv_eval_detections on a hand-made log: the table, the JSON and the depth
// errors come out as computed by hand (the tool behind `tools/nerv eval detections`).
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nerv/detections_t.hpp"

namespace fs = std::filesystem;
using namespace nerv;

namespace {

// build/tests/test_eval_detections_cli -> build/bin/nerv_eval_detections
fs::path cliPath() {
  return fs::canonical("/proc/self/exe").parent_path().parent_path() / "bin" / "nerv_eval_detections";
}

detection_t detection(int x, int y, int w, int h, bool kept, float z, float nearest) {
  detection_t d{};
  d.x = x, d.y = y, d.w = w, d.h = h;
  d.z_m = d.distance_m = z;
  d.nearest_z_m = nearest;
  d.label = kept ? "object" : "error";
  d.score = 0.9f;
  d.kept = kept;
  d.reason = kept ? "" : "error-like normals";
  return d;
}

// Runs of spaces as one, so the checks do not depend on column widths.
std::string squeeze(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != ' ' || out.empty() || out.back() != ' ') out += c;
  return out;
}

std::string run(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
  }
  return out;
}

}  // namespace

TEST(toolsEvalDetectionsCli, TableJsonAndDepthErrorsOfAHandMadeLog) {
  const fs::path cli = cliPath();
  if (!fs::exists(cli)) GTEST_SKIP() << cli << " not built";
  const fs::path tmp = fs::temp_directory_path() / ("nerv_test_eval_cli_" + std::to_string(getpid()));
  fs::create_directories(tmp / "labels");
  // One car seen from behind: centre at z 20 m, 4 m long -> nearest depth 18 m;
  // a DontCare region on the right.
  std::ofstream(tmp / "labels" / "000001.txt")
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "DontCare -1 -1 -10 600.00 100.00 700.00 200.00 -1 -1 -1 -1000 -1000 -1000 -10\n";
  {
    lcm::LogFile log((tmp / "run.lcmlog").string(), "w");
    ASSERT_TRUE(log.good());
    detections_t msg{};
    msg.header.seq = 1;
    msg.header.frame_id = "synthetic/000001";
    msg.detections = {detection(100, 100, 100, 80, true, 18.5f, 18.1f),   // kept, on the car
                      detection(300, 100, 50, 50, true, 30, 30),           // kept, on nothing
                      detection(400, 100, 50, 50, false, 30, 30),          // removed, on nothing
                      detection(610, 110, 40, 40, true, 25, 25)};          // kept, in DontCare
    msg.num_detections = static_cast<int32_t>(msg.detections.size());
    std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    lcm::LogEvent e{};
    e.eventnum = 0;
    e.timestamp = 1;
    e.channel = "DETECTIONS";
    e.datalen = static_cast<int32_t>(buf.size());
    e.data = buf.data();
    log.writeEvent(&e);
  }
  const std::string base = cli.string() + " --log " + (tmp / "run.lcmlog").string() + " --labels " +
                           (tmp / "labels").string();
  const std::string text = squeeze(run(base + " 2>&1"));
  // stixel only: 1 object, TP 1, FP 2 (the DontCare box counts neither way); + SNV: TP 1, FP 1
  EXPECT_NE(text.find("stixel only 1 1 2 0 0.333 1.000 0.500"), std::string::npos) << text;
  EXPECT_NE(text.find("stixel + SNV 1 1 1 0 0.500 1.000 0.667"), std::string::npos) << text;
  EXPECT_NE(text.find("10-20 m n 1 bias +0.50 m"), std::string::npos) << text;  // z_m 18.5 vs 18
  EXPECT_NE(text.find("10-20 m n 1 bias +0.10 m"), std::string::npos) << text;  // nearest_z_m 18.1 vs 18
  const std::string json = run(base + " --json");
  EXPECT_NE(json.find("\"stixel_snv\":{\"objects\":1,\"tp\":1,\"fp\":1,\"fn\":0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"depth_error_nearest_z\":[{\"from_m\":10,\"to_m\":20,\"count\":1"), std::string::npos)
      << json;
  // A missing label folder is a one-line error and exit status 2.
  EXPECT_NE(run(cli.string() + " --log " + (tmp / "run.lcmlog").string() + " --labels /nonexistent 2>&1; echo rc=$?")
                .find("label folder /nonexistent does not exist\nrc=2"),
            std::string::npos);
  fs::remove_all(tmp);
}
