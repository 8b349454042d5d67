#include "recording.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace nerv {

namespace fs = std::filesystem;

RecordSettings readRecordSettings(ConfigSection record) {
  RecordSettings s;
  record.get("folder", s.folder);
  record.get("channels", s.channels);
  record.get("split_mb", s.split_mb, 1, 1e6);
  record.get("keep_mb", s.keep_mb, 0, 1e9);
  record.get("min_free_mb", s.min_free_mb, 0, 1e9);
  record.get("max_unwritten_mb", s.max_unwritten_mb, 0.1, 65536);
  record.finish();
  if (s.channels.empty()) throw ConfigError("config key '" + record.path() + ".channels' is empty: use \".*\" for every channel");
  // The newest file is never deleted and grows to split_mb before the next starts: a budget
  // under two files could be kept only by deleting the file being written.
  if (s.keep_mb > 0 && s.keep_mb < 2 * s.split_mb) {
    std::ostringstream m;
    m << "config key '" << record.path() << ".keep_mb' (" << s.keep_mb << ") must be 0 (no limit) or at least twice "
      << record.path() << ".split_mb (" << s.split_mb << "): the file being written is never deleted";
    throw ConfigError(m.str());
  }
  if (s.enabled() && s.folder.front() != '/')
    throw ConfigError("config key '" + record.path() + ".folder' must be an absolute path: '" + s.folder + "'");
  // The logger formats the whole path with strftime (-s): a '%' in the folder would be expanded.
  if (s.folder.find('%') != std::string::npos)
    throw ConfigError("config key '" + record.path() + ".folder' must not contain '%': '" + s.folder + "'");
  return s;
}

std::vector<std::string> loggerArgv(const RecordSettings& s, const std::string& logger_path,
                                    const std::string& lcm_url) {
  char split[32], unwritten[32];
  std::snprintf(split, sizeof split, "%g", s.split_mb);
  std::snprintf(unwritten, sizeof unwritten, "%g", s.max_unwritten_mb);
  // env TZ=UTC0: the file names' start time in UTC whatever the computer's zone.
  return {"/usr/bin/env",
          "TZ=UTC0",
          logger_path,
          "--lcm-url=" + lcm_url,  // -l URL is broken in LCM 1.3.1
          "--channel=" + s.channels,
          // Not --quiet: that also silences the only word of its drops (parseLoggerLine).
          std::string("--max-unwritten-mb=") + unwritten,
          "-i",  // --increment
          "-s",  // --strftime; the long form is ignored by LCM 1.3.1's lcm-logger
          std::string("--split-mb=") + split,
          (fs::path(s.folder) / "nerv-%Y%m%d-%H%M%S.lcmlog").string()};
}

LoggerLine parseLoggerLine(const std::string& line) {
  LoggerLine out;
  static const std::string kDropped = "Can't write to log fast enough.  Dropped ";
  static const std::string kOpened = "Opening log file \"";
  if (line.rfind(kDropped, 0) == 0) {
    char* end = nullptr;
    const long long n = std::strtoll(line.c_str() + kDropped.size(), &end, 10);
    if (end != line.c_str() + kDropped.size() && n > 0) {
      out.kind = LoggerLine::kDropped;
      out.dropped = n;
    }
  } else if (line.rfind(kOpened, 0) == 0 && line.size() > kOpened.size() + 1 && line.back() == '"') {
    out.kind = LoggerLine::kOpened;
    out.file = line.substr(kOpened.size(), line.size() - kOpened.size() - 1);
  } else if (line.rfind("Summary: ", 0) == 0) {
    out.kind = LoggerLine::kSummary;
  }
  return out;
}

std::vector<std::string> LineSplitter::add(const char* data, size_t n) {
  std::vector<std::string> lines;
  partial_.append(data, n);
  size_t start = 0;
  for (size_t nl; (nl = partial_.find('\n', start)) != std::string::npos; start = nl + 1)
    lines.push_back(partial_.substr(start, nl - start));
  partial_.erase(0, start);
  return lines;
}

bool isRecordingName(const std::string& name) {
  return name.rfind("nerv-", 0) == 0 && name.find(".lcmlog") != std::string::npos;
}

std::vector<RecordingFile> listRecordings(const std::string& folder) {
  std::vector<RecordingFile> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code fec;
    if (!it->is_regular_file(fec) || !isRecordingName(it->path().filename().string())) continue;
    RecordingFile f;
    f.path = it->path().string();
    f.bytes = it->file_size(fec);
    if (fec) continue;  // deleted meanwhile
    f.mtime_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                     it->last_write_time(fec).time_since_epoch()).count();
    if (!fec) files.push_back(f);
  }
  return files;
}

uint64_t totalBytes(const std::vector<RecordingFile>& files) {
  uint64_t total = 0;
  for (const auto& f : files) total += f.bytes;
  return total;
}

std::vector<RecordingFile> recordingsToDelete(std::vector<RecordingFile> files, uint64_t keep_bytes) {
  std::sort(files.begin(), files.end(), [](const RecordingFile& a, const RecordingFile& b) {
    return a.mtime_ns != b.mtime_ns ? a.mtime_ns < b.mtime_ns : a.path < b.path;
  });
  std::vector<RecordingFile> doomed;
  uint64_t total = totalBytes(files);
  for (size_t i = 0; i + 1 < files.size() && total > keep_bytes; ++i) {
    doomed.push_back(files[i]);
    total -= files[i].bytes;
  }
  return doomed;
}

bool RecordingGate::update(uint64_t free_bytes) {
  if (paused_) paused_ = free_bytes < resume_at_;
  else paused_ = free_bytes < min_free_;
  return !paused_;
}

bool freeBytes(const std::string& folder, uint64_t& bytes, std::string& error) {
  struct statvfs st {};
  if (statvfs(folder.c_str(), &st) != 0) {
    error = std::strerror(errno);
    return false;
  }
  bytes = static_cast<uint64_t>(st.f_bavail) * st.f_frsize;
  return true;
}

std::string prepareRecordingFolder(const std::string& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) return "run.record.folder " + folder + " cannot be created: " + ec.message();
  if (!fs::is_directory(folder, ec)) return "run.record.folder " + folder + " is not a folder";
  if (access(folder.c_str(), W_OK | X_OK) != 0)
    return "run.record.folder " + folder + " is not writable: " + std::strerror(errno);
  return "";
}

std::string findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const std::string candidate = (fs::path(dir) / program).string();
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

}  // namespace nerv
