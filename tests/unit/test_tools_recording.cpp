// nerv_up's recorder (recording.hpp): run.record is read and checked, lcm-logger is
// asked for split files named by their start, only the logger's own files are
// counted and deleted, oldest first and never the one being written, and recording
// pauses on a full disk and resumes once a whole file fits again.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "recording.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

std::string errorOf(const std::string& yaml) {
  try {
    readRecordSettings(ConfigSection(YAML::Load(yaml), "run.record"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

RecordingFile file(const std::string& path, uint64_t mb, int64_t t) { return {path, mb << 20, t}; }

std::vector<std::string> paths(const std::vector<RecordingFile>& files) {
  std::vector<std::string> out;
  for (const auto& f : files) out.push_back(f.path);
  return out;
}

}  // namespace

TEST(toolsRecording, OffByDefaultAndReadFromTheConfig) {
  const RecordSettings off = readRecordSettings(ConfigSection(YAML::Node(), "run.record"));
  EXPECT_FALSE(off.enabled());
  const RecordSettings s = readRecordSettings(ConfigSection(
      YAML::Load("{folder: /var/lib/nerv/recordings, channels: 'DET.*', split_mb: 256, keep_mb: 4096, min_free_mb: 100, "
                 "max_unwritten_mb: 500}"),
      "run.record"));
  EXPECT_TRUE(s.enabled());
  EXPECT_EQ(s.folder, "/var/lib/nerv/recordings");
  EXPECT_EQ(s.channels, "DET.*");
  EXPECT_EQ(s.split_mb, 256);
  EXPECT_EQ(s.keep_mb, 4096);
  EXPECT_EQ(s.min_free_mb, 100);
  EXPECT_EQ(s.max_unwritten_mb, 500);
  EXPECT_EQ(off.max_unwritten_mb, 100);  // lcm-logger's own default
}

TEST(toolsRecording, BadSettingsNameTheKey) {
  EXPECT_NE(errorOf("{folder: /r, split: 5}").find("'run.record.split'"), std::string::npos) << errorOf("{folder: /r, split: 5}");
  EXPECT_NE(errorOf("{folder: /r, split_mb: 0}").find("'run.record.split_mb'"), std::string::npos);
  EXPECT_NE(errorOf("{folder: /r, min_free_mb: -1}").find("'run.record.min_free_mb'"), std::string::npos);
  EXPECT_NE(errorOf("{folder: /r, split_mb: .nan}").find("'run.record.split_mb'"), std::string::npos);
  EXPECT_NE(errorOf("{folder: /r, max_unwritten_mb: 0}").find("'run.record.max_unwritten_mb'"), std::string::npos);
  EXPECT_NE(errorOf("{folder: recordings}").find("must be an absolute path"), std::string::npos);
  EXPECT_NE(errorOf("{folder: /data/100%}").find("'run.record.folder' must not contain '%'"), std::string::npos);
  EXPECT_NE(errorOf("{folder: /r, channels: ''}").find("'run.record.channels' is empty"), std::string::npos);
  // The file being written is never deleted, so the budget must hold two files.
  const std::string small = errorOf("{folder: /r, split_mb: 100, keep_mb: 150}");
  EXPECT_NE(small.find("'run.record.keep_mb' (150) must be 0 (no limit) or at least twice run.record.split_mb (100)"),
            std::string::npos) << small;
  EXPECT_EQ(errorOf("{folder: /r, split_mb: 100, keep_mb: 200}"), "");
  EXPECT_EQ(errorOf("{folder: /r, split_mb: 100, keep_mb: 0}"), "");
}

TEST(toolsRecording, TheLoggerSplitsIntoFilesNamedByTheirStartInUtc) {
  RecordSettings s;
  s.folder = "/data/rec";
  s.channels = "FRONT_.*";
  s.split_mb = 512;
  const auto argv = loggerArgv(s, "/usr/bin/lcm-logger", "udpm://239.255.76.67:7667?ttl=1");
  const std::vector<std::string> expected = {
      "/usr/bin/env", "TZ=UTC0", "/usr/bin/lcm-logger", "--lcm-url=udpm://239.255.76.67:7667?ttl=1",
      "--channel=FRONT_.*", "--max-unwritten-mb=100", "-i", "-s", "--split-mb=512",
      "/data/rec/nerv-%Y%m%d-%H%M%S.lcmlog"};
  EXPECT_EQ(argv, expected);
  s.split_mb = 0.5;
  EXPECT_EQ(loggerArgv(s, "lcm-logger", "u")[8], "--split-mb=0.5");
}

// The lines of LCM 1.3.1's lcm-logger, as it prints them without --quiet.
TEST(toolsRecording, TheLoggersDropsAreReadFromItsOutput) {
  const LoggerLine dropped = parseLoggerLine("Can't write to log fast enough.  Dropped 12 packets");
  EXPECT_EQ(dropped.kind, LoggerLine::kDropped);
  EXPECT_EQ(dropped.dropped, 12);
  const LoggerLine one = parseLoggerLine("Can't write to log fast enough.  Dropped 1 packet");
  EXPECT_EQ(one.kind, LoggerLine::kDropped);
  EXPECT_EQ(one.dropped, 1);
  const LoggerLine opened = parseLoggerLine("Opening log file \"/data/rec/nerv-20261207-071700.lcmlog.03\"");
  EXPECT_EQ(opened.kind, LoggerLine::kOpened);
  EXPECT_EQ(opened.file, "/data/rec/nerv-20261207-071700.lcmlog.03");
  EXPECT_EQ(parseLoggerLine("Summary: /tmp/x.lcmlog ti:   1sec Events: 3         (    0 MB )      TPS:     1.71       KB/s:     0.30").kind,
            LoggerLine::kSummary);
  for (const char* other : {"", "Can't write to log fast enough.  Dropped x packets", "Opening log file \"", "Logger exiting",
                            "ERROR!  Unable to rotate [/data/rec/x]"}) {
    EXPECT_EQ(parseLoggerLine(other).kind, LoggerLine::kOther) << other;
    EXPECT_EQ(parseLoggerLine(other).dropped, 0) << other;
  }
}

TEST(toolsRecording, LinesAreWholeWhateverPiecesThePipeGives) {
  LineSplitter split;
  auto add = [&](const std::string& piece) { return split.add(piece.data(), piece.size()); };
  EXPECT_TRUE(add("Open").empty());
  EXPECT_EQ(add("ing\nSumm"), std::vector<std::string>{"Opening"});
  EXPECT_EQ(add("ary\n\nCan't\n"), (std::vector<std::string>{"Summary", "", "Can't"}));
  EXPECT_TRUE(add("").empty());
  EXPECT_TRUE(add("tail").empty());
  EXPECT_EQ(split.rest(), "tail");
  EXPECT_EQ(split.rest(), "");
}

TEST(toolsRecording, OnlyTheLoggersFilesAreRecordings) {
  EXPECT_TRUE(isRecordingName("nerv-20261207-050102.lcmlog.00"));
  EXPECT_TRUE(isRecordingName("nerv-20261207-050102.lcmlog.123"));
  EXPECT_TRUE(isRecordingName("nerv-x.lcmlog"));
  EXPECT_FALSE(isRecordingName("drive_monday.lcmlog"));
  EXPECT_FALSE(isRecordingName("nerv-notes.txt"));
  EXPECT_FALSE(isRecordingName("lcmlog-2026-12-07.00"));

  const fs::path dir = fs::temp_directory_path() / ("nerv_recording_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "nerv-sub.lcmlog");  // a folder, even with a matching name
  std::ofstream(dir / "nerv-20261207-050102.lcmlog.00") << std::string(1000, 'x');
  std::ofstream(dir / "nerv-20261207-050102.lcmlog.01") << std::string(10, 'x');
  std::ofstream(dir / "drive_monday.lcmlog") << std::string(5000, 'x');
  const auto files = listRecordings(dir.string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(totalBytes(files), 1010u);
  EXPECT_TRUE(listRecordings((dir / "missing").string()).empty());
  fs::remove_all(dir);
}

TEST(toolsRecording, OldestDeletedFirstUntilTheRestFits) {
  // Written in this order: a (t 1), c (t 2), b (t 3), d (t 4, being written).
  const std::vector<RecordingFile> files = {file("b", 100, 3), file("d", 100, 4), file("a", 100, 1), file("c", 100, 2)};
  EXPECT_TRUE(recordingsToDelete(files, 400ull << 20).empty());
  EXPECT_EQ(paths(recordingsToDelete(files, 399ull << 20)), std::vector<std::string>({"a"}));
  EXPECT_EQ(paths(recordingsToDelete(files, 200ull << 20)), std::vector<std::string>({"a", "c"}));
  // Same time: by name, the logger's numbering.
  EXPECT_EQ(paths(recordingsToDelete({file("r.01", 1, 5), file("r.00", 1, 5), file("r.02", 1, 6)}, 1ull << 20)),
            std::vector<std::string>({"r.00", "r.01"}));
}

TEST(toolsRecording, TheFileBeingWrittenIsNeverDeleted) {
  EXPECT_TRUE(recordingsToDelete({file("only", 5000, 9)}, 1).empty());
  EXPECT_EQ(paths(recordingsToDelete({file("old", 1, 1), file("huge", 5000, 9)}, 0)), std::vector<std::string>({"old"}));
  EXPECT_TRUE(recordingsToDelete({}, 0).empty());
}

TEST(toolsRecording, PausesBelowTheFloorAndResumesWhenAFileFitsAgain) {
  RecordingGate gate(/*min_free*/ 1000, /*split*/ 300);
  EXPECT_TRUE(gate.update(5000));
  EXPECT_TRUE(gate.update(1000));
  EXPECT_FALSE(gate.update(999));
  EXPECT_TRUE(gate.paused());
  EXPECT_FALSE(gate.update(1200));  // above the floor, but the next file would not fit
  EXPECT_FALSE(gate.update(1299));
  EXPECT_TRUE(gate.update(1300));
  EXPECT_FALSE(gate.paused());
  EXPECT_TRUE(gate.update(1100));  // running again: the floor alone counts
}

TEST(toolsRecording, TheFolderIsMadeAndCheckedWritable) {
  const fs::path dir = fs::temp_directory_path() / ("nerv_recording_dir_" + std::to_string(getpid()));
  fs::remove_all(dir);
  EXPECT_EQ(prepareRecordingFolder((dir / "a" / "b").string()), "");
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  std::ofstream(dir / "plain") << "x";
  const std::string not_folder = prepareRecordingFolder((dir / "plain").string());
  EXPECT_NE(not_folder.find("run.record.folder " + (dir / "plain").string()), std::string::npos) << not_folder;
  const std::string below_file = prepareRecordingFolder((dir / "plain" / "x").string());
  EXPECT_NE(below_file.find("cannot be created"), std::string::npos) << below_file;
  uint64_t bytes = 0;
  std::string error;
  EXPECT_TRUE(freeBytes(dir.string(), bytes, error));
  EXPECT_GT(bytes, 0u);
  EXPECT_FALSE(freeBytes((dir / "missing").string(), bytes, error));
  EXPECT_FALSE(error.empty());
  fs::remove_all(dir);
}

TEST(toolsRecording, TheLoggerIsFoundOnPath) {
  EXPECT_EQ(findOnPath("sh").empty(), false);
  EXPECT_EQ(findOnPath("nerv-no-such-program"), "");
}
