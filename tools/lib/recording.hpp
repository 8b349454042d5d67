// nerv_up's recorder: the bus recorded by lcm-logger under supervision, in files
// of bounded size, the folder's total bounded when asked, and never onto a full
// disk. On a test car the services run from systemd for days; a logger started
// by hand is forgotten, and one left running writes 2.35 MB a frame (about
// 85 GB an hour at 10 Hz) until the disk is full and every program on the
// computer that writes fails with it.
//
// The decisions are here, free of LCM and of processes: which files are
// recordings, which of them to delete, when to pause and resume. nerv_up
// (tools/up/main.cpp) runs lcm-logger and applies them.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config.hpp"

namespace nerv {

// `run.record` of a pipeline config.
struct RecordSettings {
  std::string folder;           // "" = no recording
  std::string channels = ".*";  // lcm-logger's channel regex (anchored)
  double split_mb = 1024;       // a new file once the current one passes this
  double keep_mb = 0;           // the oldest recordings deleted beyond this total; 0 = never deleted
  double min_free_mb = 2048;    // recording pauses while the disk has less free than this
  double max_unwritten_mb = 100;  // the logger's queue for a slow disk; beyond it messages are dropped
  bool enabled() const { return !folder.empty(); }
};

// Reads and checks `run.record` (unknown keys, ranges, keep_mb smaller than two files).
RecordSettings readRecordSettings(ConfigSection record);

// lcm-logger's command line: files FOLDER/nerv-<UTC start>.lcmlog.NN, a new one every split_mb.
std::vector<std::string> loggerArgv(const RecordSettings& s, const std::string& logger_path,
                                    const std::string& lcm_url);

// What a line of lcm-logger's standard output says. The logger queues what it receives for
// its writer thread and drops messages once more than max_unwritten_mb wait (a disk that
// stalls); it says so only there, on standard output, at most once a second with the
// drops since its last such line ("Can't write to log fast enough.  Dropped 12 packets"),
// and only without --quiet. The drops of a last burst are said with the next drop a second
// later, or never: the count is a lower bound, the line a certainty.
struct LoggerLine {
  enum Kind { kOpened, kDropped, kSummary, kOther } kind = kOther;
  int64_t dropped = 0;  // kDropped: messages lost since the logger's previous such line
  std::string file;     // kOpened: the file it now writes
};
LoggerLine parseLoggerLine(const std::string& line);

// Whole lines out of the bytes read from a pipe in pieces.
class LineSplitter {
 public:
  std::vector<std::string> add(const char* data, size_t n);
  std::string rest() { return std::exchange(partial_, std::string()); }  // an unterminated last line

 private:
  std::string partial_;
};

// A recording file of the folder: the logger's names only (nerv-*.lcmlog*), so nothing
// else in the folder is ever counted or deleted.
struct RecordingFile {
  std::string path;
  uint64_t bytes = 0;
  int64_t mtime_ns = 0;
};
bool isRecordingName(const std::string& file_name);
std::vector<RecordingFile> listRecordings(const std::string& folder);
uint64_t totalBytes(const std::vector<RecordingFile>& files);

// The files to delete, oldest first (by time written, then name), until the rest fit in
// keep_bytes. The newest file is never among them: the logger is writing it.
std::vector<RecordingFile> recordingsToDelete(std::vector<RecordingFile> files, uint64_t keep_bytes);

// Pauses below min_free, resumes once a whole file more is free again, so a disk near
// the limit does not start and stop the logger at every file.
class RecordingGate {
 public:
  RecordingGate(uint64_t min_free_bytes, uint64_t split_bytes)
      : min_free_(min_free_bytes), resume_at_(min_free_bytes + split_bytes) {}
  // The free space now; true while recording may run.
  bool update(uint64_t free_bytes);
  bool paused() const { return paused_; }

 private:
  uint64_t min_free_, resume_at_;
  bool paused_ = false;
};

// Free bytes for an unprivileged writer on the folder's filesystem; false (and errno's
// text in `error`) when it cannot be read.
bool freeBytes(const std::string& folder, uint64_t& bytes, std::string& error);

// The folder made if missing and checked writable; "" or what is wrong with it.
std::string prepareRecordingFolder(const std::string& folder);

// lcm-logger's path on PATH, or "".
std::string findOnPath(const std::string& program);

}  // namespace nerv
