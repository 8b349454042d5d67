// nerv_eval_detections on a hand-made log: the table, the JSON and the depth
// errors and the misses by cause come out as computed by hand (the tool behind
// `tools/nerv eval detections`).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.hpp"
#include "lcm_test_log.hpp"
#include "nerv/detections_t.hpp"

namespace fs = std::filesystem;
using namespace nerv;

namespace {

fs::path cliPath() { return test::cliPath("nerv_eval_detections"); }

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

std::string squeeze(const std::string& s) { return test::squeezeSpaces(s); }
std::string run(const std::string& cmd) { return test::runCli(cmd); }

// DETECTIONS of frame "synthetic/<seq, 6 digits>".
detections_t frame(int seq, std::vector<detection_t> detections) {
  detections_t f{};
  f.header.seq = seq;
  char name[32];
  std::snprintf(name, sizeof name, "synthetic/%06d", seq);
  f.header.frame_id = name;
  f.detections = std::move(detections);
  return f;
}

void writeLog(const fs::path& path, std::vector<detections_t> frames) {
  for (detections_t& f : frames) f.num_detections = static_cast<int32_t>(f.detections.size());
  ASSERT_TRUE(test::writeLcmLog(path.string(), "DETECTIONS", frames));
}

// A temporary folder with labels/ and run.lcmlog, and the command line reading them.
class toolsEvalDetectionsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(cli)) GTEST_SKIP() << cli << " not built";
    fs::create_directories(tmp / "labels");
  }
  void TearDown() override { fs::remove_all(tmp); }
  std::string base() const {
    return cli.string() + " --log " + (tmp / "run.lcmlog").string() + " --labels " + (tmp / "labels").string();
  }
  const fs::path cli = cliPath();
  const fs::path tmp = fs::temp_directory_path() / ("nerv_test_eval_cli_" + std::to_string(getpid()));
};

}  // namespace

TEST_F(toolsEvalDetectionsCli, MissesByCauseOfAHandMadeLog) {
  // A pedestrian (columns 300..319, rows 100..159, 15 m, no 3D size) whose only box
  // at its depth misses its head: rows 130..159, IoU 0.5 exactly (not above): loose.
  // A car (rows 100..179, 20 m) found only by a box the validator removed.
  // A pole (columns 500..509, rows 80..179, 25 m) with only the facade behind it boxed.
  std::ofstream(tmp / "labels" / "000002.txt")
      << "Pedestrian 0.00 0 0 300.00 100.00 319.00 159.00 -1 -1 -1 -1000 -1000 15.00 0\n"
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "Pole 0.00 0 0 500.00 80.00 509.00 179.00 -1 -1 -1 -1000 -1000 25.00 0\n";
  writeLog(tmp / "run.lcmlog", {frame(2, {detection(300, 130, 20, 30, true, 15.2f, 15.0f),     // the pedestrian's lower half
                                          detection(100, 100, 100, 80, false, 18.5f, 18.1f),  // the car, removed
                                          detection(480, 40, 60, 150, true, 48, 47)})});      // the facade behind the pole
  const std::string text = squeeze(run(base() + " 2>&1"));
  const size_t all = text.find("misses by cause (stixel only):"), kept = text.find("misses by cause (stixel + SNV):");
  ASSERT_NE(all, std::string::npos) << text;
  ASSERT_NE(kept, std::string::npos) << text;
  const std::string all_part = text.substr(all, kept - all), kept_part = text.substr(kept);
  EXPECT_NE(all_part.find(" 1 loose box at its depth (IoU >= 0.3): Pedestrian 1"), std::string::npos) << text;
  EXPECT_NE(all_part.find(" 1 only boxes at another depth: Pole 1"), std::string::npos) << text;
  EXPECT_EQ(all_part.find("Car"), std::string::npos) << text;  // the stixels found the car
  EXPECT_NE(kept_part.find(" 1 found by the stixels, removed by the validator: Car 1"), std::string::npos) << text;
  EXPECT_NE(kept_part.find(" 1 loose box at its depth (IoU >= 0.3): Pedestrian 1"), std::string::npos) << text;
  const std::string json = run(base() + " --json");
  EXPECT_NE(json.find("\"misses_stixel_only\":{\"other_depth\":{\"Pole\":1},\"loose_box\":{\"Pedestrian\":1}}"),
            std::string::npos) << json;
  EXPECT_NE(json.find("\"misses_stixel_snv\":{\"other_depth\":{\"Pole\":1},\"loose_box\":{\"Pedestrian\":1},"
                      "\"removed_by_validator\":{\"Car\":1}}"),
            std::string::npos) << json;
}

TEST_F(toolsEvalDetectionsCli, TableJsonAndDepthErrorsOfAHandMadeLog) {
  // One car seen from behind: centre at z 20 m, 4 m long -> nearest depth 18 m;
  // a DontCare region on the right.
  std::ofstream(tmp / "labels" / "000001.txt")
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "DontCare -1 -1 -10 600.00 100.00 700.00 200.00 -1 -1 -1 -1000 -1000 -1000 -10\n";
  writeLog(tmp / "run.lcmlog", {frame(1, {detection(100, 100, 100, 80, true, 18.5f, 18.1f),  // kept, on the car
                                          detection(300, 100, 50, 50, true, 30, 30),        // kept, on nothing
                                          detection(400, 100, 50, 50, false, 30, 30),       // removed, on nothing
                                          detection(610, 110, 40, 40, true, 25, 25)})});    // kept, in DontCare
  const std::string text = squeeze(run(base() + " 2>&1"));
  // stixel only: 1 object, TP 1, FP 2 (the DontCare box counts neither way); + SNV: TP 1, FP 1
  EXPECT_NE(text.find("stixel only 1 1 2 0 0.333 1.000 0.500"), std::string::npos) << text;
  EXPECT_NE(text.find("stixel + SNV 1 1 1 0 0.500 1.000 0.667"), std::string::npos) << text;
  EXPECT_NE(text.find("10-20 m n 1 bias +0.50 m"), std::string::npos) << text;  // z_m 18.5 vs 18
  EXPECT_NE(text.find("10-20 m n 1 bias +0.10 m"), std::string::npos) << text;  // nearest_z_m 18.1 vs 18
  const std::string json = run(base() + " --json");
  EXPECT_NE(json.find("\"stixel_snv\":{\"objects\":1,\"tp\":1,\"fp\":1,\"fn\":0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"depth_error_nearest_z\":[{\"from_m\":10,\"to_m\":20,\"count\":1"), std::string::npos)
      << json;
  // A missing label folder is a one-line error and exit status 2.
  EXPECT_NE(run(cli.string() + " --log " + (tmp / "run.lcmlog").string() + " --labels /nonexistent 2>&1; echo rc=$?")
                .find("label folder /nonexistent does not exist\nrc=2"),
            std::string::npos);
}

TEST_F(toolsEvalDetectionsCli, VisibleIgnoresHiddenObjectsAndTheBoxesOnThem) {
  // A visible car found, a largely hidden one (occluded 2) found, and a hidden one missed.
  std::ofstream(tmp / "labels" / "000003.txt")
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "Car 0.00 2 -1.57 300.00 100.00 399.00 179.00 1.50 1.80 4.00 2.00 1.65 20.00 -1.5708\n"
      << "Car 0.00 2 -1.57 500.00 100.00 599.00 179.00 1.50 1.80 4.00 4.00 1.65 20.00 -1.5708\n";
  writeLog(tmp / "run.lcmlog", {frame(3, {detection(100, 100, 100, 80, true, 18.5f, 18.1f),
                                          detection(300, 100, 100, 80, true, 18.5f, 18.1f)})});
  // All three count without --visible: TP 2, FN 1.
  EXPECT_NE(squeeze(run(base() + " 2>&1")).find("stixel + SNV 3 2 0 1 1.000 0.667 0.800"), std::string::npos);
  // With it only the visible car counts, and the box on the hidden one is neither TP nor FP.
  const std::string text = squeeze(run(base() + " --visible 2>&1"));
  EXPECT_NE(text.find("occlusion < 2 and truncation < 0.5 only"), std::string::npos) << text;
  EXPECT_NE(text.find("stixel + SNV 1 1 0 0 1.000 1.000 1.000"), std::string::npos) << text;
  EXPECT_NE(run(base() + " --visible --json").find("\"visible_only\":true"), std::string::npos);
}

TEST_F(toolsEvalDetectionsCli, DistanceLimitIgnoresUnmatchedDetectionsBeyondIt) {
  // A car at 20 m found, a car at 50 m (beyond --max-distance 40) with a loose box
  // at 48 m on it, and a kept box at 60 m on nothing.
  std::ofstream(tmp / "labels" / "000004.txt")
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "Car 0.00 0 -1.57 300.00 100.00 339.00 129.00 1.50 1.80 4.00 2.00 1.65 50.00 -1.5708\n";
  writeLog(tmp / "run.lcmlog", {frame(4, {detection(100, 100, 100, 80, true, 18.5f, 18.1f),
                                          detection(320, 100, 40, 30, true, 48.0f, 47.5f),
                                          detection(700, 100, 30, 30, true, 60.0f, 59.0f)})});
  // Both far boxes count neither way by default ...
  const std::string text = squeeze(run(base() + " --max-distance 40 2>&1"));
  EXPECT_NE(text.find("distance-limited (objects and unmatched detections)"), std::string::npos) << text;
  EXPECT_NE(text.find("stixel + SNV 1 1 0 0 1.000 1.000 1.000"), std::string::npos) << text;
  EXPECT_NE(run(base() + " --max-distance 40 --json").find("\"far_detections_ignored\":true"), std::string::npos);
  // ... and are false positives with --count-far-detections.
  const std::string old = squeeze(run(base() + " --max-distance 40 --count-far-detections 2>&1"));
  EXPECT_NE(old.find("distance-limited (objects only)"), std::string::npos) << old;
  EXPECT_NE(old.find("stixel + SNV 1 1 2 0 0.333 1.000 0.500"), std::string::npos) << old;
}

TEST_F(toolsEvalDetectionsCli, DifficultyIgnoresLowAndHiddenObjectsAndLowBoxes) {
  // A car 79 px tall found, a pole 20 px tall found, a partly hidden car (occluded 1) missed,
  // and a 15 px box on nothing.
  std::ofstream(tmp / "labels" / "000005.txt")
      << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 20.00 -1.5708\n"
      << "Pole 0.00 0 0 500.00 160.00 503.00 180.00 -1 -1 -1 -1000 -1000 38.00 0\n"
      << "Car 0.00 1 -1.57 300.00 100.00 399.00 179.00 1.50 1.80 4.00 2.00 1.65 20.00 -1.5708\n";
  writeLog(tmp / "run.lcmlog", {frame(5, {detection(100, 100, 100, 80, true, 18.5f, 18.1f),
                                          detection(500, 160, 4, 21, true, 38.0f, 38.0f),
                                          detection(700, 100, 10, 15, true, 30.0f, 30.0f)})});
  // Without a difficulty: 3 objects, TP 2, FP 1, FN 1.
  EXPECT_NE(squeeze(run(base() + " 2>&1")).find("stixel + SNV 3 2 1 1 0.667 0.667 0.667"), std::string::npos);
  // moderate: the pole (20 px) is ignored and so is the low box on nothing; the partly hidden car counts.
  const std::string moderate = squeeze(run(base() + " --difficulty moderate 2>&1"));
  EXPECT_NE(moderate.find("KITTI moderate (height >= 25 px, occluded <= 1, truncated <= 0.3)"), std::string::npos)
      << moderate;
  EXPECT_NE(moderate.find("stixel + SNV 2 1 0 1 1.000 0.500 0.667"), std::string::npos) << moderate;
  // easy: only the fully visible car counts.
  EXPECT_NE(squeeze(run(base() + " --difficulty easy 2>&1")).find("stixel + SNV 1 1 0 0 1.000 1.000 1.000"),
            std::string::npos);
  EXPECT_NE(run(base() + " --difficulty hard --json").find("\"difficulty\":\"hard\""), std::string::npos);
  // An unknown difficulty is a one-line error naming it.
  EXPECT_NE(run(base() + " --difficulty medium 2>&1; echo rc=$?").find("unknown difficulty 'medium' (easy, moderate or hard)"),
            std::string::npos);
}

// --from-seq N: only the frames from seq N on are scored.
TEST_F(toolsEvalDetectionsCli, FromSeqScoresTheLaterFramesOnly) {
  for (const char* name : {"000001.txt", "000002.txt"})
    std::ofstream(tmp / "labels" / name) << "Car 0.00 0 -1.57 100.00 100.00 199.00 179.00 1.50 1.80 4.00 0.00 1.65 "
                                            "20.00 -1.5708\n";
  // Frame 1 misses the car, frame 2 finds it.
  writeLog(tmp / "run.lcmlog", {frame(1, {}), frame(2, {detection(100, 100, 100, 80, true, 20, 19.8f)})});
  const std::string all = squeeze(run(base() + " 2>&1"));
  EXPECT_NE(all.find("frames evaluated: 2"), std::string::npos) << all;
  EXPECT_NE(all.find("stixel + SNV 2 1 0 1 1.000 0.500"), std::string::npos) << all;
  const std::string later = squeeze(run(base() + " --from-seq 2 2>&1"));
  EXPECT_NE(later.find("frames evaluated: 1"), std::string::npos) << later;
  EXPECT_NE(later.find("stixel + SNV 1 1 0 0 1.000 1.000"), std::string::npos) << later;
}
