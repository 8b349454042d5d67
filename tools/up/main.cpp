// nerv_up: starts the services a pipeline config describes, keeps them running
// and shows their health.
//
//   nerv_up --config FILE [--lcm-url URL] [--prefix P] [--services a,b] [--quiet] [--exit-when-idle S]
//   nerv_up --status [--lcm-url URL] [--prefix P] [--listen S]
//   nerv_up --config FILE [--services a,b] --list   the instances it would start, one
//                                                   "service/instance" a line (what a
//                                                   source waits for before its first frame)
//   nerv_up --config FILE [--lcm-url URL] [--prefix P] --print lcm_url|channel_prefix
//                                                   the bus or channel prefix the services
//                                                   would use (flags, else the config, else the
//                                                   default), after the whole config is checked
//
// The `run:` section of the config says which services to start and how many
// shards of each (`shards: {stereo_matcher: 2}`). A service that exits is
// restarted after a back-off that doubles from restart_backoff_s up to
// restart_backoff_max_s (and resets once it has run for 30 s). A service whose
// own NERV_HEALTH stops for run.watchdog_s (10 s; 0 = off), or that sends none
// within run.watchdog_startup_s (30 s) of its start, is hung: it is killed
// (SIGKILL) and restarted the same way (service_watchdog.hpp). nerv_up reports
// on NERV_HEALTH itself (service "nerv_up", instance = host), once a second and
// at every restart: errors = restarts so far, a counter per restarted service,
// the last restart as last_error, so a log shows when and why a stage was
// missing. With `run.record.folder` set it also records the bus: lcm-logger,
// restarted like a service, writes FOLDER/nerv-<UTC start>.lcmlog.NN files of
// run.record.split_mb each; nerv_up deletes the oldest beyond run.record.keep_mb
// and stops the logger while the disk has less than run.record.min_free_mb free
// (recording.hpp); it reads the logger's standard output for the messages the logger
// dropped (more than run.record.max_unwritten_mb waiting for a slow disk), which it
// counts in its health as recording_dropped. A status line
// per service is printed every second from NERV_HEALTH. SIGINT/SIGTERM stop
// every child (SIGTERM, then SIGKILL after 3 s) and exit 0.
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "build_version.hpp"
#include "config.hpp"
#include "pipeline_keys.hpp"
#include "lcm_node.hpp"
#include "health_compat.hpp"
#include "nerv/health_t.hpp"
#include "recording.hpp"
#include "service_watchdog.hpp"

#ifndef NERV_MARCH_NAME
#define NERV_MARCH_NAME "?"
#endif

using namespace nerv;
using Clock = std::chrono::steady_clock;

namespace {

volatile sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

const char* const kServices[] = {"stereo_matcher", "stixel", "snv_extrinsic", "validator"};

struct Child {
  std::string service, instance;
  bool reports_health = true;  // false for lcm-logger: no watchdog, not a source's wait
  std::vector<std::string> argv;
  pid_t pid = -1;
  int restarts = 0;
  int hangs = 0;  // of the restarts, after the watchdog killed it
  double backoff_s = 0;
  ServiceWatchdog watchdog;
  bool hung = false;  // killed by the watchdog, not yet reaped
  bool held = false;  // stopped on purpose (the recorder on a full disk): not restarted until released
  bool capture_stdout = false;  // the logger: its standard output read by nerv_up (readLoggerOutput)
  int out_fd = -1;              // the read end of that pipe while the process runs
  LineSplitter out_lines;
  Clock::time_point started, restart_at;
};

struct Options {
  std::string config, lcm_url, prefix, bin_dir, services;
  bool has_prefix = false;  // --prefix given, possibly empty: it replaces the config's channel_prefix
  bool status_only = false, quiet = false, list_only = false;
  std::string print_key;  // --print: lcm_url or channel_prefix, as the services would use them
  double listen_s = 2.0, exit_when_idle_s = 0;
};

// The recording's figures for nerv_up's own health report.
struct RecorderState {
  RecordSettings settings;
  std::unique_ptr<RecordingGate> gate;
  int64_t deleted = 0, pauses = 0, dropped = 0;  // dropped: what the logger said it lost (at least that)
  double recording_mb = 0, free_mb = -1;
  std::string free_error;  // the last failure to read the free space, said once
};

// The bus: --lcm-url (or the config's lcm_url), else LCM_DEFAULT_URL, else nerv's default.
std::string busUrl(const std::string& flag) {
  if (!flag.empty()) return flag;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env ? env : kDefaultLcmUrl;
}

double seconds(Clock::time_point t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

struct HealthBoard {
  std::map<std::string, health_t> last;  // "service/instance" -> report
  std::map<std::string, Clock::time_point> seen;
  std::map<int32_t, Clock::time_point> seen_pid;  // the latest report of each process on this host
  std::string host;
  int64_t broken = 0;
  void onHealth(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    health_t h;  // any layout: a computer still on an older build is shown too (health_compat.hpp)
    if (!decodeHealth(rbuf->data, static_cast<int>(rbuf->data_size), h)) return void(++broken);
    const std::string key = h.service + "/" + h.instance;
    last[key] = h;
    seen[key] = Clock::now();
    if (h.host == host) seen_pid[h.pid] = seen[key];
  }
  void print(FILE* out) const {
    for (const auto& [key, h] : last) {
      const double age = std::chrono::duration<double>(Clock::now() - seen.at(key)).count();
      // Frames out before their capture time: this computer's clock lags the camera's.
      std::string skew;
      for (int i = 0; i < h.num_counters; ++i)
        if (h.counter_names[i] == "clock_skew_frames" && h.counter_values[i] > 0)
          skew = "  clock behind the camera's: " + std::to_string(h.counter_values[i]) + " frames";
      std::string gauges;  // "  row_offset_px 0.10  view_delay_ms 0.4"
      for (int i = 0; i < h.num_gauges; ++i) {
        char g[120];
        std::snprintf(g, sizeof g, "  %s %.3g", h.gauge_names[i].c_str(), h.gauge_values[i]);
        gauges += g;
      }
      std::fprintf(out, "%-26s pid %-7d %-8s in %-6lld out %-6lld dropped %-4lld errors %-4lld p95 %6.1f ms  %5.1f ms/frame%s%s%s%s\n",
                   key.c_str(), h.pid, age > 3 ? "silent" : h.status.c_str(), (long long)h.frames_in,
                   (long long)h.frames_out, (long long)h.frames_dropped, (long long)h.errors,
                   h.latency_p95_ms, h.processing_ms, skew.c_str(), gauges.c_str(),
                   h.last_error.empty() ? "" : "  last: ", h.last_error.c_str());
    }
  }
  // The builds heard: one line naming each when they differ (always with `always`).
  void printBuilds(FILE* out, bool always) const {
    std::map<std::string, std::string> who;  // version -> "service/instance ..."
    for (const auto& [key, h] : last) who[h.version.empty() ? "unknown" : h.version] += " " + key;
    if (who.size() > 1) {
      std::fprintf(out, "builds differ:");
      for (const auto& [version, keys] : who) std::fprintf(out, "  nerv %s:%s;", version.c_str(), keys.c_str());
      std::fprintf(out, "\n");
    } else if (always && !who.empty()) {
      std::fprintf(out, "build: nerv %s on all %zu\n", who.begin()->first.c_str(), last.size());
    }
  }
};

// The supervisor's own report: how often each child was restarted and why the last time.
void publishSupervisorHealth(lcm::LCM& lcm, const std::string& channel, const std::string& host,
                             const std::vector<Child>& children, const RecorderState* recorder,
                             const std::string& last_event, bool restarted_since_last) {
  static CpuShare cpu_share;
  health_t h{};  // every count zero until set: lcm-gen's structs leave them uninitialised
  h.utime = nowUtime();
  h.service = "nerv_up";
  h.instance = host;
  h.host = host;
  h.pid = static_cast<int32_t>(getpid());
  h.frames_in = h.frames_out = h.frames_dropped = 0;
  h.errors = 0;
  bool all_running = true;
  for (const Child& c : children) {
    h.errors += c.restarts;
    all_running = all_running && c.pid > 0;
    if (c.restarts == 0) continue;
    h.counter_names.push_back("restarts_" + c.service + "/" + c.instance);
    h.counter_values.push_back(c.restarts);
    if (c.hangs == 0) continue;
    h.counter_names.push_back("hung_" + c.service + "/" + c.instance);
    h.counter_values.push_back(c.hangs);
  }
  if (recorder) {
    h.counter_names.insert(h.counter_names.end(), {"recordings_deleted", "recording_paused", "recording_dropped"});
    h.counter_values.insert(h.counter_values.end(), {recorder->deleted, recorder->pauses, recorder->dropped});
    h.gauge_names = {"recording_mb", "disk_free_mb"};
    h.gauge_values = {recorder->recording_mb, recorder->free_mb};
  }
  h.num_counters = static_cast<int32_t>(h.counter_names.size());
  addProcessGauges(h, cpu_share);  // and num_gauges
  h.latency_p50_ms = h.latency_p95_ms = h.processing_ms = 0;
  // degraded: a service is down (waiting for its restart) or was restarted since the last report.
  h.status = all_running && !restarted_since_last ? "ok" : "degraded";
  h.last_error = last_event;
  h.version = buildVersion();
  lcm.publish(channel, &h);
}

pid_t spawn(Child& c) {
  int out[2] = {-1, -1};
  if (c.capture_stdout && pipe2(out, O_CLOEXEC) != 0) {
    std::fprintf(stderr, "nerv_up: no pipe for %s's output (%s): its drops go unread\n", c.service.c_str(), std::strerror(errno));
    out[0] = out[1] = -1;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the supervisor, even after kill -9
    if (out[1] >= 0) dup2(out[1], STDOUT_FILENO);  // dup2 clears close-on-exec on the copy
    std::vector<char*> args;
    for (const auto& a : c.argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    std::fprintf(stderr, "nerv_up: cannot start %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  if (out[1] >= 0) close(out[1]);
  if (out[0] >= 0) {
    if (pid < 0) close(out[0]);
    else {
      fcntl(out[0], F_SETFL, fcntl(out[0], F_GETFL) | O_NONBLOCK);
      c.out_fd = out[0];
    }
  }
  return pid;
}

// What the logger printed since the last call: its drops counted and said, the file it
// opened said, anything unexpected passed on; its once-a-second summaries are not.
// `closing` reads to the end and closes the pipe (the logger has exited).
void readLoggerOutput(Child& c, RecorderState& r, std::string& last_event, bool& event, bool closing) {
  if (c.out_fd < 0) return;
  std::vector<std::string> lines;
  char buf[4096];
  for (ssize_t n; (n = read(c.out_fd, buf, sizeof buf)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;  // EAGAIN: nothing more for now
    }
    for (auto& l : c.out_lines.add(buf, static_cast<size_t>(n))) lines.push_back(std::move(l));
  }
  if (closing) {
    if (std::string rest = c.out_lines.rest(); !rest.empty()) lines.push_back(rest);
    close(c.out_fd);
    c.out_fd = -1;
  }
  for (const std::string& line : lines) {
    const LoggerLine said = parseLoggerLine(line);
    if (said.kind == LoggerLine::kDropped) {
      r.dropped += said.dropped;
      char text[512];
      // The logger says its drops at most once a second, those since its last such line, and
      // the rest of a burst only with a later drop: a lower bound.
      std::snprintf(text, sizeof text,
                    "lcm-logger is dropping messages: more than run.record.max_unwritten_mb %g waited for the disk "
                    "of %s (it says %lld since its last word, at least %lld in all); the recording has gaps",
                    r.settings.max_unwritten_mb, r.settings.folder.c_str(), (long long)said.dropped, (long long)r.dropped);
      std::fprintf(stderr, "nerv_up: %s\n", text);
      last_event = text;
      event = true;
    } else if (said.kind == LoggerLine::kOpened) {
      std::fprintf(stderr, "nerv_up: recording into %s\n", said.file.c_str());
    } else if (said.kind == LoggerLine::kOther && !line.empty()) {
      std::fprintf(stderr, "nerv_up: lcm-logger: %s\n", line.c_str());
    }
  }
}

// Once a second: the oldest recordings beyond keep_mb deleted, and the logger stopped while
// the disk is below min_free_mb (started again once a file more fits).
void checkRecording(RecorderState& r, std::vector<Child>& children, std::string& last_event, bool& event) {
  Child* logger = nullptr;
  for (auto& c : children)
    if (!c.reports_health) logger = &c;
  if (!logger) return;
  const RecordSettings& s = r.settings;
  auto files = listRecordings(s.folder);
  if (s.keep_mb > 0) {
    for (const RecordingFile& f : recordingsToDelete(files, static_cast<uint64_t>(s.keep_mb * 1048576.0))) {
      std::error_code ec;
      if (!std::filesystem::remove(f.path, ec) && ec) {
        std::fprintf(stderr, "nerv_up: recording %s cannot be deleted: %s\n", f.path.c_str(), ec.message().c_str());
        continue;
      }
      ++r.deleted;
      std::fprintf(stderr, "nerv_up: deleted the recording %s (%.1f MB): the folder holds more than run.record.keep_mb %g\n",
                   f.path.c_str(), f.bytes / 1048576.0, s.keep_mb);
    }
    files = listRecordings(s.folder);
  }
  r.recording_mb = totalBytes(files) / 1048576.0;
  uint64_t free_bytes = 0;
  std::string error;
  if (!freeBytes(s.folder, free_bytes, error)) {
    if (error != r.free_error) std::fprintf(stderr, "nerv_up: free space of %s cannot be read: %s\n", s.folder.c_str(), error.c_str());
    r.free_error = error;
    r.free_mb = -1;
    return;
  }
  r.free_error.clear();
  r.free_mb = free_bytes / 1048576.0;
  const bool was_paused = r.gate->paused();
  const bool may_run = r.gate->update(free_bytes);
  char line[512];
  if (!may_run && !was_paused) {
    ++r.pauses;
    std::snprintf(line, sizeof line, "recording paused: %.0f MB free on %s, below run.record.min_free_mb %g; it resumes at %g MB",
                  r.free_mb, s.folder.c_str(), s.min_free_mb, s.min_free_mb + s.split_mb);
    std::fprintf(stderr, "nerv_up: %s\n", line);
    last_event = line;
    event = true;
    logger->held = true;
    if (logger->pid > 0) kill(logger->pid, SIGTERM);  // reaped in the loop, not restarted while held
  } else if (may_run && was_paused) {
    std::snprintf(line, sizeof line, "recording resumed: %.0f MB free on %s", r.free_mb, s.folder.c_str());
    std::fprintf(stderr, "nerv_up: %s\n", line);
    last_event = line;
    event = true;
    logger->held = false;
    if (logger->pid < 0) {  // started again at once; not a restart of a failed process
      logger->pid = spawn(*logger);
      logger->started = Clock::now();
      std::fprintf(stderr, "nerv_up: started lcm-logger/0 (pid %d)\n", logger->pid);
    }
  }
}

int status(const Options& o) {
  lcm::LCM lcm(busUrl(o.lcm_url));
  if (!lcm.good()) throw std::runtime_error("LCM cannot start");
  HealthBoard board;
  lcm.subscribe(o.prefix + "NERV_HEALTH", &HealthBoard::onHealth, &board);
  const auto end = Clock::now() + std::chrono::duration<double>(o.listen_s);
  while (Clock::now() < end && !g_stop) lcm.handleTimeout(50);
  if (board.last.empty()) {
    std::printf("no NERV_HEALTH heard in %.1f s\n", o.listen_s);
    return 1;
  }
  board.print(stdout);
  board.printBuilds(stdout, true);
  return 0;
}

int up(const Options& flags) {
  Options o = flags;
  ConfigSection root(loadConfigFile(o.config), "");
  // The bus and prefix come from the flags, else from the config (as the services read them).
  std::string config_url, config_prefix;
  root.get("lcm_url", config_url);
  root.get("channel_prefix", config_prefix);
  if (o.lcm_url.empty()) o.lcm_url = config_url;
  if (!o.has_prefix) o.prefix = config_prefix;
  allowPipelineTopLevelKeys(root);  // what the services and the source read
  ConfigSection run = root.section("run");
  std::string services_csv = "stereo_matcher,stixel,snv_extrinsic,validator";
  run.get("services", services_csv);
  if (!o.services.empty()) services_csv = o.services;
  double backoff0 = 0.5, backoff_max = 10;
  run.get("restart_backoff_s", backoff0, 0.05, 60);
  run.get("restart_backoff_max_s", backoff_max, 0.05, 600);
  WatchdogSettings watchdog;
  run.get("watchdog_s", watchdog.silent_s, 0, 600);
  run.get("watchdog_startup_s", watchdog.startup_s, 1, 3600);
  if (watchdog.silent_s > 0 && watchdog.silent_s < 2)
    throw ConfigError("config key 'run.watchdog_s' must be 0 (off) or at least 2 s: services report once a second");
  const RecordSettings record = readRecordSettings(run.section("record"));
  ConfigSection shards = run.section("shards");
  std::map<std::string, int> shard_count;
  for (const char* s : kServices) {
    shard_count[s] = 1;
    shards.get(s, shard_count[s], 1, 64);
  }
  shards.finish();
  run.finish();
  root.finish();

  std::vector<Child> children;
  std::stringstream list(services_csv);
  for (std::string s; std::getline(list, s, ',');) {
    if (!shard_count.count(s)) throw ConfigError("config key 'run.services' names unknown service '" + s + "'");
    for (int k = 0; k < shard_count[s]; ++k) {
      Child c;
      c.service = s;
      c.instance = shard_count[s] > 1 ? "shard" + std::to_string(k) : "0";
      c.argv = {o.bin_dir + "/" + s, "--config", o.config};
      if (!o.lcm_url.empty()) c.argv.insert(c.argv.end(), {"--lcm-url", o.lcm_url});
      if (o.has_prefix || !o.prefix.empty()) c.argv.insert(c.argv.end(), {"--prefix", o.prefix});
      if (shard_count[s] > 1) c.argv.insert(c.argv.end(), {"--shard", std::to_string(k) + "/" + std::to_string(shard_count[s])});
      if (!std::filesystem::exists(c.argv[0])) throw std::runtime_error("service binary " + c.argv[0] + " is missing");
      c.watchdog = ServiceWatchdog(watchdog);
      children.push_back(c);
    }
  }
  const std::string url = busUrl(o.lcm_url);
  std::unique_ptr<RecorderState> recorder;
  if (record.enabled() && !o.list_only && o.print_key.empty()) {
    const std::string logger = findOnPath("lcm-logger");
    if (logger.empty()) throw ConfigError("run.record.folder is set, but lcm-logger is not on PATH (Debian package liblcm-bin)");
    const std::string problem = prepareRecordingFolder(record.folder);
    if (!problem.empty()) throw ConfigError(problem);
    recorder = std::make_unique<RecorderState>();
    recorder->settings = record;
    recorder->gate = std::make_unique<RecordingGate>(static_cast<uint64_t>(record.min_free_mb * 1048576.0),
                                                      static_cast<uint64_t>(record.split_mb * 1048576.0));
    Child c;
    c.service = "lcm-logger";
    c.instance = "0";
    c.reports_health = false;
    c.capture_stdout = true;
    c.argv = loggerArgv(record, logger, url);
    children.push_back(c);
  }
  if (o.print_key == "lcm_url") return std::printf("%s\n", url.c_str()), 0;
  if (o.print_key == "channel_prefix") return std::printf("%s\n", o.prefix.c_str()), 0;
  if (o.list_only) {
    for (const auto& c : children) std::printf("%s/%s\n", c.service.c_str(), c.instance.c_str());
    return 0;
  }
  // Configuration problems show now, once, not as a restart loop.
  for (const auto& c : children) {
    if (!c.reports_health) continue;
    std::string cmd = c.argv[0] + " --config '" + o.config + "' --check-config 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    char line[512] = {0};
    if (p && std::fgets(line, sizeof line, p)) {}
    if (!p || pclose(p) != 0) throw ConfigError(std::string(line[0] ? line : "config check failed\n").substr(0, std::strlen(line) - 1));
  }

  lcm::LCM lcm(url);
  if (!lcm.good()) throw std::runtime_error("LCM cannot start on " + url);
  HealthBoard board;
  board.host = hostName();
  lcm.subscribe(o.prefix + "NERV_HEALTH", &HealthBoard::onHealth, &board);

  std::fprintf(stderr, "nerv_up: nerv %s\n", buildVersion());
  std::string last_event;
  bool event_since_report = false;
  if (recorder) checkRecording(*recorder, children, last_event, event_since_report);
  for (auto& c : children) {
    if (c.held) continue;
    c.pid = spawn(c);
    c.started = Clock::now();
    c.watchdog.started(seconds(c.started));
    c.backoff_s = backoff0;
    std::fprintf(stderr, "nerv_up: started %s/%s (pid %d)\n", c.service.c_str(), c.instance.c_str(), c.pid);
  }
  auto last_print = Clock::now();
  auto last_activity = Clock::now();
  auto last_report = Clock::now() - std::chrono::seconds(1);
  while (!g_stop) {
    lcm.handleTimeout(50);
    if (recorder)
      for (auto& c : children) readLoggerOutput(c, *recorder, last_event, event_since_report, /*closing*/ false);
    for (auto& c : children) {
      if (c.pid > 0) {
        int wstatus = 0;
        if (waitpid(c.pid, &wstatus, WNOHANG) == c.pid) {
          if (recorder) readLoggerOutput(c, *recorder, last_event, event_since_report, /*closing*/ true);
          const double ran = std::chrono::duration<double>(Clock::now() - c.started).count();
          if (ran > 30) c.backoff_s = backoff0;
          char event[512];
          // SIGILL: an instruction this CPU lacks, a build made for another one (copied by hand;
          // the Debian package's preinst refuses such a computer). Restarts cannot mend it.
          const bool illegal = WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGILL;
          std::snprintf(event, sizeof event, "%s/%s (pid %d) %s %d%s%s; restart in %.1f s", c.service.c_str(),
                        c.instance.c_str(), c.pid, WIFSIGNALED(wstatus) ? "killed by signal" : "exited with",
                        WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : WEXITSTATUS(wstatus), c.hung ? " (hung)" : "",
                        illegal ? " (illegal instruction: built with -march=" NERV_MARCH_NAME
                                  " for another CPU? build nerv on this computer, or with a -march it has)"
                                : "",
                        c.backoff_s);
          if (c.held) {  // stopped by checkRecording, which said why
            c.pid = -1;
            continue;
          }
          std::fprintf(stderr, "nerv_up: %s\n", event);
          last_event = event;
          event_since_report = true;
          if (c.hung) ++c.hangs;
          c.pid = -1;
          c.hung = false;
          c.restart_at = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(c.backoff_s));
          c.backoff_s = std::min(backoff_max, c.backoff_s * 2);
        } else if (!c.hung && c.reports_health) {
          if (auto it = board.seen_pid.find(c.pid); it != board.seen_pid.end())
            c.watchdog.reported(seconds(it->second));
          const double now = seconds(Clock::now());
          if (c.watchdog.hung(now)) {
            // Stopped, deadlocked or stuck in one frame: it still exists, so only a kill
            // brings it back. Reaped (and restarted after the back-off) above.
            std::fprintf(stderr, "nerv_up: %s/%s (pid %d) sent no health for %.1f s%s: hung (run.%s), killing it\n",
                         c.service.c_str(), c.instance.c_str(), c.pid, c.watchdog.silentFor(now),
                         c.watchdog.hasReported() ? "" : " since its start",
                         c.watchdog.hasReported() ? "watchdog_s" : "watchdog_startup_s");
            kill(c.pid, SIGKILL);
            c.hung = true;
          }
        }
      } else if (!c.held && Clock::now() >= c.restart_at) {
        c.pid = spawn(c);
        c.started = Clock::now();
        c.watchdog.started(seconds(c.started));
        ++c.restarts;
        std::fprintf(stderr, "nerv_up: restarted %s/%s (pid %d, restart %d)\n", c.service.c_str(),
                     c.instance.c_str(), c.pid, c.restarts);
        event_since_report = true;
      }
    }
    // Once a second, and at once when a service went down or came back.
    if (event_since_report || Clock::now() - last_report >= std::chrono::seconds(1)) {
      if (recorder) checkRecording(*recorder, children, last_event, event_since_report);
      publishSupervisorHealth(lcm, o.prefix + "NERV_HEALTH", board.host, children, recorder.get(), last_event,
                              event_since_report);
      last_report = Clock::now();
      event_since_report = false;
    }
    for (const auto& [k, h] : board.last)
      if (h.status == "ok" && h.service != "nerv_up") last_activity = std::max(last_activity, board.seen[k]);
    if (!o.quiet && Clock::now() - last_print > std::chrono::seconds(1)) {
      std::fprintf(stderr, "---\n");
      board.print(stderr);
      board.printBuilds(stderr, false);
      last_print = Clock::now();
    }
    if (o.exit_when_idle_s > 0 &&
        std::chrono::duration<double>(Clock::now() - last_activity).count() > o.exit_when_idle_s)
      break;
  }
  for (auto& c : children)
    if (c.pid > 0) kill(c.pid, SIGTERM);
  const auto deadline = Clock::now() + std::chrono::seconds(3);
  for (auto& c : children) {
    while (c.pid > 0) {
      if (waitpid(c.pid, nullptr, WNOHANG) == c.pid) c.pid = -1;
      else if (Clock::now() > deadline) {
        kill(c.pid, SIGKILL);
        waitpid(c.pid, nullptr, 0);
        c.pid = -1;
      } else std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  if (recorder)  // the logger's last words, e.g. drops of the last second
    for (auto& c : children) readLoggerOutput(c, *recorder, last_event, event_since_report, /*closing*/ true);
  std::fprintf(stderr, "nerv_up: all services stopped\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  o.bin_dir = std::filesystem::canonical("/proc/self/exe").parent_path().string();
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error("flag " + a + " needs a value");
        return argv[++i];
      };
      if (a == "--config") o.config = value();
      else if (a == "--lcm-url") o.lcm_url = value();
      else if (a == "--prefix") o.prefix = value(), o.has_prefix = true;
      else if (a == "--services") o.services = value();
      else if (a == "--status") o.status_only = true;
      else if (a == "--listen") o.listen_s = std::stod(value());
      else if (a == "--quiet") o.quiet = true;
      else if (a == "--list") o.list_only = true;
      else if (a == "--print") {
        o.print_key = value();
        if (o.print_key != "lcm_url" && o.print_key != "channel_prefix")
          throw std::runtime_error("--print takes lcm_url or channel_prefix, not '" + o.print_key + "'");
      }
      else if (a == "--version") return std::printf("nerv_up: nerv %s\n", buildVersion()), 0;
      else if (a == "--exit-when-idle") o.exit_when_idle_s = std::stod(value());
      else throw std::runtime_error("unknown flag '" + a + "'");
    }
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    if (o.status_only) return status(o);
    if (o.config.empty()) throw std::runtime_error("--config FILE is required");
    return up(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nerv_up: %s\n", e.what());
    return 2;
  }
}
