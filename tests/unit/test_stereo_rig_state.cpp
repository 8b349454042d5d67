// The rig's corrections kept across restarts (services/stereo_matcher/rig_state.hpp): the file
// read back as written, every way it can be wrong named, and the keeper's part in a run: a
// correction saved when a verdict sets it, restored from the first frame of the next run for
// the same calibration only, checked by that run's verdicts, dropped and saved as dropped.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rig_check.hpp"
#include "rig_state.hpp"
#include "stereo_moved_view.hpp"
#include "stereo_rig_findings.hpp"

namespace nerv::stereo {
namespace {

namespace fs = std::filesystem;

// A folder of its own per test, removed after it.
class stereoRigState : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("nerv_rig_state_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    path_ = (dir_ / "rig.yaml").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& text) const { std::ofstream(path_) << text; }
  fs::path dir_;
  std::string path_;
};

const RigCalibration kCalibration{0x0123456789abcdefull, 640, 240, 721.5377, 320.25, 120.5, 0.537150588, true};

RigState someState() {
  RigState s;
  s.calibration = kCalibration;
  s.rows = {0.987654321, 0.0017453292, -0.0004};
  s.offset_px = -1.2345678901;
  s.saved_utc = "2026-12-07T03:00:00Z";
  return s;
}

// The keeper asks for the calibration and the time only when it uses them.
RigStateKeeper::CalibrationOf calibrationOf(const RigCalibration& c) {
  return [c] { return c; };
}
RigStateKeeper::Now at(const std::string& t) {
  return [t] { return t; };
}

const char* const kGoodFile =
    "saved_utc: \"2026-12-07T03:00:00Z\"\n"
    "calibration: {fingerprint: \"0123456789abcdef\", width: 640, height: 240, fx: 721.5377, cx: 320.25, "
    "cy: 120.5, baseline_m: 0.537150588, rectified: true}\n"
    "row_correction: {offset_px: 1.0, slope_x: 0, slope_y: 0}\n"
    "offset_correction_px: 0.5\n";

TEST_F(stereoRigState, ReadBackAsWritten) {
  ASSERT_EQ(writeRigState(path_, someState()), "");
  RigState back;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, back, absent), "");
  EXPECT_FALSE(absent);
  const RigState s = someState();
  EXPECT_EQ(back.calibration.fingerprint, s.calibration.fingerprint);
  EXPECT_EQ(back.calibration.width, 640);
  EXPECT_EQ(back.calibration.height, 240);
  // Bit for bit: the calibration is compared exactly, the corrections restored exactly.
  EXPECT_EQ(back.calibration.fx, s.calibration.fx);
  EXPECT_EQ(back.calibration.cx, s.calibration.cx);
  EXPECT_EQ(back.calibration.cy, s.calibration.cy);
  EXPECT_EQ(back.calibration.baseline_m, s.calibration.baseline_m);
  EXPECT_TRUE(back.calibration.rectified);
  EXPECT_EQ(back.rows.offset_px, s.rows.offset_px);
  EXPECT_EQ(back.rows.slope_x, s.rows.slope_x);
  EXPECT_EQ(back.rows.slope_y, s.rows.slope_y);
  EXPECT_EQ(back.offset_px, s.offset_px);
  EXPECT_EQ(back.saved_utc, s.saved_utc);
  EXPECT_EQ(calibrationDifference(back.calibration, kCalibration), "");
  // Nothing left beside it from the write.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(stereoRigState, AMissingFileIsNoProblem) {
  RigState s;
  bool absent = false;
  EXPECT_EQ(readRigState(path_, s, absent), "");
  EXPECT_TRUE(absent);
}

TEST_F(stereoRigState, EveryWayTheFileIsWrongIsNamed) {
  const std::string good = kGoodFile;
  RigState s;
  bool absent = false;
  write(good);
  ASSERT_EQ(readRigState(path_, s, absent), "");
  const auto problem = [&](const std::string& text) {
    write(text);
    RigState t;
    bool a = false;
    const std::string p = readRigState(path_, t, a);
    EXPECT_FALSE(a);
    return p;
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return problem(t);
  };
  std::string p = replaced("offset_correction_px: 0.5\n", "");
  EXPECT_NE(p.find("key 'offset_correction_px' is missing"), std::string::npos) << p;
  EXPECT_NE(p.find(path_), std::string::npos) << p;
  p = replaced("offset_correction_px", "ofset_correction_px");
  EXPECT_NE(p.find("ofset_correction_px"), std::string::npos) << p;  // unknown, or the other missing
  p = replaced("slope_x: 0,", "slope_x: 0, roll: 1,");
  EXPECT_NE(p.find("row_correction.roll"), std::string::npos) << p;
  p = replaced("offset_px: 1.0", "offset_px: .nan");
  EXPECT_NE(p.find("row_correction.offset_px"), std::string::npos) << p;
  p = replaced("fx: 721.5377", "fx: wide");
  EXPECT_NE(p.find("calibration.fx' must be a number, got 'wide'"), std::string::npos) << p;
  p = replaced("0123456789abcdef", "0123456789abcdeg");
  EXPECT_NE(p.find("calibration.fingerprint' must be hexadecimal"), std::string::npos) << p;
  p = replaced(", rectified: true", "");
  EXPECT_NE(p.find("calibration.rectified' is missing"), std::string::npos) << p;
  p = problem("calibration: [1, 2\n");
  EXPECT_NE(p.find("rig state file " + path_), std::string::npos) << p;
  p = problem("just words\n");
  EXPECT_NE(p.find("not a YAML map"), std::string::npos) << p;
  // A folder where the file should be.
  fs::remove(path_);
  fs::create_directories(path_);
  EXPECT_NE(readRigState(path_, s, absent), "");
  EXPECT_FALSE(absent);
}

TEST_F(stereoRigState, WhatDiffersBetweenTwoCalibrations) {
  RigCalibration other = kCalibration;
  EXPECT_EQ(calibrationDifference(kCalibration, other), "");
  other.fingerprint ^= 1;
  EXPECT_EQ(calibrationDifference(kCalibration, other),
            "the same focal length, centre and baseline but other fields (fy, distortion or the cameras' pose)");
  other.fx = 718.856;
  EXPECT_EQ(calibrationDifference(kCalibration, other), "fx 721.54 against 718.86");
  other.width = 1242;
  EXPECT_EQ(calibrationDifference(kCalibration, other), "640x240 against 1242x240");
}

TEST_F(stereoRigState, UnwritableIsAProblemThatNamesThePath) {
  RigState s = someState();
  const std::string nowhere = (dir_ / "missing_folder" / "rig.yaml").string();
  const std::string p = writeRigState(nowhere, s);
  EXPECT_NE(p.find("missing_folder/rig.yaml.tmp."), std::string::npos) << p;
}

// One run of frames through a keeper and a rig check, as the service runs them; the findings of
// the last frame's keeper calls and of every frame's rig check, in order.
struct KeptRun {
  std::vector<RigFinding> restore, saves, checks;
};

KeptRun runFrames(RigStateKeeper& keeper, RigCheck& rig, const RigCalibration& calibration, const cv::Mat& left,
        const cv::Mat& right, int frames) {
  KeptRun r;
  for (int f = 1; f <= frames; ++f) {
    const std::vector<RigFinding> before = keeper.beforeMatching(calibrationOf(calibration), rig);
    r.restore.insert(r.restore.end(), before.begin(), before.end());
    const std::vector<RigFinding> checks = wallFrame(rig, left, right);
    r.checks.insert(r.checks.end(), checks.begin(), checks.end());
    const std::vector<RigFinding> saves = keeper.afterMatching(calibrationOf(calibration), rig, at("2026-12-07T03:0" + std::to_string(f % 10) + ":00Z"));
    r.saves.insert(r.saves.end(), saves.begin(), saves.end());
  }
  return r;
}

const RigFinding* firstLog(const std::vector<RigFinding>& findings) {
  return firstFinding(findings, RigFinding::Kind::Log);
}

TEST_F(stereoRigState, ACorrectionIsSavedAndRestoredFromTheFirstFrameOfTheNextRun) {
  const cv::Mat left = wallTexture(11), moved = movedRightView(left, 1.0), aligned = movedRightView(left, 0);
  {
    RigCheck rig;
    RigStateKeeper keeper(path_);
    const KeptRun first = runFrames(keeper, rig, kCalibration, left, moved, 9);
    EXPECT_EQ(findingNames(first.restore), "log");  // the file does not exist yet
    EXPECT_NE(firstLog(first.restore)->message.find("does not exist yet"), std::string::npos);
    EXPECT_EQ(findingNames(first.saves), "");       // nothing corrected yet, nothing written
    EXPECT_FALSE(fs::exists(path_));
    const KeptRun tenth = runFrames(keeper, rig, kCalibration, left, moved, 1);
    EXPECT_EQ(findingNames(tenth.saves), "rig_state_saved");
    const KeptRun more = runFrames(keeper, rig, kCalibration, left, moved, 20);
    EXPECT_EQ(findingNames(more.saves), "");  // kept, not written again
  }
  RigState saved;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, saved, absent), "");
  EXPECT_NEAR(saved.rows.offset_px, 1.0, 0.05);
  EXPECT_EQ(saved.offset_px, 0.0);
  EXPECT_EQ(saved.calibration.fingerprint, kCalibration.fingerprint);

  // The next run: corrected from its first frame, said, still an error at its first verdict.
  RigCheck rig;
  RigStateKeeper keeper(path_);
  const std::vector<RigFinding> restore = keeper.beforeMatching(calibrationOf(kCalibration), rig);
  EXPECT_EQ(findingNames(restore), "rig_state_restored log");
  const std::string& line = firstLog(restore)->message;
  EXPECT_NE(line.find("from the first frame the right views are resampled by 1.0"), std::string::npos) << line;
  EXPECT_NEAR(findingGauge(restore, "row_correction_px"), 1.0, 0.05);
  EXPECT_EQ(rig.rowCorrection().offset_px, saved.rows.offset_px);
  EXPECT_LT(meanViewDifference(rig.rightToMatch(moved), aligned), 3.0);
  const KeptRun next = runFrames(keeper, rig, kCalibration, left, moved, 10);
  EXPECT_EQ(findingNames(next.restore), "");  // only the first frame reads the file
  EXPECT_EQ(findingNames(next.checks), "row_checks row_checks row_checks row_checks row_checks row_checks "
                                       "row_checks row_checks row_checks row_checks row_misaligned");
  EXPECT_LT(findingGauge(next.checks, "row_residual_px"), 0.1);  // the restored correction was right
  EXPECT_EQ(findingNames(next.saves), "");
  EXPECT_EQ(rig.rowCorrection().offset_px, saved.rows.offset_px);
}

TEST_F(stereoRigState, BothCorrectionsAreRestoredAndSaid) {
  ASSERT_EQ(writeRigState(path_, someState()), "");
  RigCheck rig;
  RigStateKeeper keeper(path_);
  const std::vector<RigFinding> f = keeper.beforeMatching(calibrationOf(kCalibration), rig);
  ASSERT_EQ(findingNames(f), "rig_state_restored log");
  EXPECT_EQ(firstLog(f)->message, "rig state: from the first frame the right views are resampled by 1.59 px at most "
                                  "and 1.23 px is added to every disparity, as saved in " + path_ +
                                      " at 2026-12-07T03:00:00Z; the first verdicts check it");
  EXPECT_EQ(rig.offsetCorrection(), someState().offset_px);
  EXPECT_EQ(findingGauge(f, "offset_correction_px"), someState().offset_px);
  // Nothing changed: nothing written.
  EXPECT_EQ(findingNames(keeper.afterMatching(calibrationOf(kCalibration), rig, at("later"))), "");
}

TEST_F(stereoRigState, AMendedRigDropsTheRestoredCorrectionAndSavesThat) {
  RigState s = someState();
  s.rows = {1.0, 0, 0};
  s.offset_px = 0;
  ASSERT_EQ(writeRigState(path_, s), "");
  const cv::Mat left = wallTexture(12), aligned = movedRightView(left, 0);
  RigCheck rig;
  RigStateKeeper keeper(path_);
  const KeptRun r = runFrames(keeper, rig, kCalibration, left, aligned, 10);
  EXPECT_EQ(findingNames(r.restore), "rig_state_restored log");
  EXPECT_NE(findingNames(r.checks).find("row_corrections"), std::string::npos) << findingNames(r.checks);
  EXPECT_TRUE(rig.rowCorrection().zero());
  EXPECT_EQ(findingNames(r.saves), "rig_state_saved");
  RigState back;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, back, absent), "");
  EXPECT_TRUE(back.rows.zero());
  EXPECT_EQ(back.saved_utc, "2026-12-07T03:00:00Z");  // the tenth frame's time
}

TEST_F(stereoRigState, AnotherCalibrationsFileIsNotUsedAndReplacedAtTheFirstCorrection) {
  ASSERT_EQ(writeRigState(path_, someState()), "");
  RigCalibration recalibrated = kCalibration;
  recalibrated.fingerprint = 42;
  recalibrated.cx = 321.0;
  const cv::Mat left = wallTexture(13), moved = movedRightView(left, -1.0);
  RigCheck rig;
  RigStateKeeper keeper(path_);
  const KeptRun nine = runFrames(keeper, rig, recalibrated, left, moved, 9);
  EXPECT_EQ(findingNames(nine.restore), "rig_state_other_calibration log");
  const std::string& line = firstLog(nine.restore)->message;
  EXPECT_NE(line.find("is of another calibration (cx 320.25 against 321.00): not used"), std::string::npos) << line;
  EXPECT_TRUE(rig.rowCorrection().zero());
  EXPECT_EQ(rig.offsetCorrection(), 0.0);
  EXPECT_EQ(findingNames(nine.saves), "");  // the other calibration's file left until there is something to keep
  const KeptRun tenth = runFrames(keeper, rig, recalibrated, left, moved, 1);
  EXPECT_EQ(findingNames(tenth.saves), "rig_state_saved");
  RigState back;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, back, absent), "");
  EXPECT_EQ(back.calibration.fingerprint, 42u);
  EXPECT_NEAR(back.rows.offset_px, -1.0, 0.05);
  EXPECT_EQ(back.offset_px, 0.0);
}

TEST_F(stereoRigState, ABadFileIsAnErrorAndTheRigIsMeasuredAgain) {
  write("row_correction: {offset_px: 1.0}\n");
  RigCheck rig;
  RigStateKeeper keeper(path_);
  const std::vector<RigFinding> f = keeper.beforeMatching(calibrationOf(kCalibration), rig);
  ASSERT_EQ(findingNames(f), "bad_rig_state");
  EXPECT_NE(f[0].message.find("not used: the rig's corrections are measured again"), std::string::npos)
      << f[0].message;
  EXPECT_TRUE(rig.rowCorrection().zero());
}

TEST_F(stereoRigState, CorrectionsSwitchedOffRestoreNothingAndLeaveTheFile) {
  ASSERT_EQ(writeRigState(path_, someState()), "");
  RigCheckParams p;
  p.row_correction = false;
  p.offset_correction = false;
  RigCheck rig(p);
  RigStateKeeper keeper(path_);
  const cv::Mat left = wallTexture(14), aligned = movedRightView(left, 0);
  const KeptRun r = runFrames(keeper, rig, kCalibration, left, aligned, 12);
  EXPECT_EQ(findingNames(r.restore), "log");
  EXPECT_TRUE(rig.rowCorrection().zero());
  EXPECT_EQ(findingNames(r.saves), "");
  RigState back;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, back, absent), "");
  EXPECT_EQ(back.rows.offset_px, someState().rows.offset_px);
}

TEST_F(stereoRigState, RestoredAsFarAsThisConfigurationCorrects) {
  RigCheckParams p;
  p.max_row_correction_px = 0.5f;
  p.max_offset_correction_px = 1.0f;
  RigCheck rig(p);
  EXPECT_TRUE(rig.restore({2.0, 0, 0}, -1.5, cv::Size(640, 240)));
  EXPECT_NEAR(rig.rowCorrection().offset_px, 0.5, 1e-9);
  EXPECT_EQ(rig.offsetCorrection(), -1.0);
  RigCheck none;
  EXPECT_FALSE(none.restore({}, 0, cv::Size(640, 240)));
}

TEST_F(stereoRigState, AFailedWriteIsSaidOncePerChange) {
  const std::string nowhere = (dir_ / "missing_folder" / "rig.yaml").string();
  const cv::Mat left = wallTexture(15), moved = movedRightView(left, 1.0);
  RigCheck rig;
  RigStateKeeper keeper(nowhere);
  const KeptRun r = runFrames(keeper, rig, kCalibration, left, moved, 30);
  ASSERT_EQ(findingNames(r.saves), "rig_state_not_saved");
  EXPECT_NE(r.saves[0].message.find("the corrections apply in this run"), std::string::npos) << r.saves[0].message;
  EXPECT_NEAR(rig.rowCorrection().offset_px, 1.0, 0.05);  // corrected all the same
}

// Frames of another calibration mid-run, the corrections unchanged: the file keeps the calibration
// they were measured under.
TEST_F(stereoRigState, ACalibrationChangeAloneWritesNothing) {
  ASSERT_EQ(writeRigState(path_, someState()), "");
  RigCheck rig;
  RigStateKeeper keeper(path_);
  ASSERT_EQ(findingNames(keeper.beforeMatching(calibrationOf(kCalibration), rig)), "rig_state_restored log");
  RigCalibration other = kCalibration;
  other.fingerprint = 7;
  EXPECT_EQ(findingNames(keeper.afterMatching(calibrationOf(other), rig, at("later"))), "");
  RigState back;
  bool absent = true;
  ASSERT_EQ(readRigState(path_, back, absent), "");
  EXPECT_EQ(back.calibration.fingerprint, kCalibration.fingerprint);
}

// Not on every frame: the calibration at the first frame and at the write, the time at the write.
TEST_F(stereoRigState, TheCalibrationAndTimeAreAskedForOnlyWhenUsed) {
  const cv::Mat left = wallTexture(17), moved = movedRightView(left, 1.0);
  RigCheck rig;
  RigStateKeeper keeper(path_);
  int calibrations = 0, times = 0;
  const RigStateKeeper::CalibrationOf calibration = [&] {
    ++calibrations;
    return kCalibration;
  };
  const RigStateKeeper::Now now = [&] {
    ++times;
    return std::string("2026-12-07T04:00:00Z");
  };
  for (int f = 1; f <= 30; ++f) {
    keeper.beforeMatching(calibration, rig);
    wallFrame(rig, left, moved);
    keeper.afterMatching(calibration, rig, now);
  }
  EXPECT_EQ(calibrations, 2);  // the first frame, the write at the 10th
  EXPECT_EQ(times, 1);
  EXPECT_TRUE(fs::exists(path_));
}

TEST_F(stereoRigState, NoFileNoKeeping) {
  RigCheck rig;
  RigStateKeeper keeper("");
  EXPECT_FALSE(keeper.enabled());
  const cv::Mat left = wallTexture(16), moved = movedRightView(left, 1.0);
  const KeptRun r = runFrames(keeper, rig, kCalibration, left, moved, 12);
  EXPECT_EQ(findingNames(r.restore) + findingNames(r.saves), "");
  EXPECT_NEAR(rig.rowCorrection().offset_px, 1.0, 0.05);
}

}  // namespace
}  // namespace nerv::stereo
