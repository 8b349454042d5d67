#include "log_summary.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <vector>

#include "json_writer.hpp"
#include "latency_breakdown.hpp"
#include "log_decode.hpp"
#include "percentile.hpp"
#include "pipeline_prefix.hpp"
#include "resource_trend.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "health_compat.hpp"
#include "nerv/health_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

namespace nerv {
namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / v.size();
}

struct FrameRow {
  std::string frame_id;
  int64_t frame_event_utime = -1;
  int hypotheses = -1, kept = -1;
  double latency_ms = -1;
  bool has_extrinsics = false, extrinsics_valid = false;
  double pitch_deg = 0, roll_deg = 0, height_m = 0, confidence = 0;
  std::string ground_source;
  double ground_height_m = 0;
  double observed_share = -1;  // free space measured (DETECTIONS, from STIXELS.observed); -1 = not reported
  int unobserved = -1, columns = -1;
};

}  // namespace

std::string summarizeLog(const std::string& log_path, std::string* text_report,
                         const std::optional<std::string>& prefix) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("log " + log_path + " cannot be read");
  std::map<int64_t, FrameRow> frames;
  std::map<std::string, std::vector<double>> stage_ms;
  std::map<std::string, std::map<std::string, health_t>> health_by_prefix;  // prefix -> "service/instance" -> report
  std::vector<double> latencies;
  std::map<std::string, int64_t> events_per_channel;
  int64_t first_frame_utime = -1, last_detection_utime = -1, detections_events = 0;
  LatencyBreakdown breakdown;
  std::map<std::string, ResourceTrend> resources_by_prefix;
  PipelineSelection pipeline(prefix);

  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++events_per_channel[e->channel];
    if (!pipeline.take(e->channel)) continue;  // another camera's pipeline: its seqs are its own
    stereo_frame_t frame;
    disparity_t disp;
    stixels_t stix;
    surface_normals_t normals;
    extrinsics_t ext;
    detections_t det;
    health_t health;
    if (decodeEvent(*e, frame)) {
      FrameRow& r = frames[frame.header.seq];
      r.frame_id = frame.header.frame_id;
      r.frame_event_utime = e->timestamp;
      if (first_frame_utime < 0) first_frame_utime = e->timestamp;
      breakdown.add(frame.header.seq, "STEREO_FRAME", e->timestamp, frame.header.utime, -1);
    } else if (decodeEvent(*e, disp)) {
      stage_ms["stereo_matcher"].push_back(disp.processing_ms);
      breakdown.add(disp.header.seq, "DISPARITY", e->timestamp, disp.header.utime, disp.processing_ms);
    } else if (decodeEvent(*e, stix)) {
      stage_ms["stixel"].push_back(stix.processing_ms);
      breakdown.add(stix.header.seq, "STIXELS", e->timestamp, stix.header.utime, stix.processing_ms);
      FrameRow& r = frames[stix.header.seq];
      r.ground_source = stix.ground.source;
      r.ground_height_m = stix.ground.height_m;
    } else if (decodeEvent(*e, normals)) {
      stage_ms["snv_extrinsic"].push_back(normals.processing_ms);
      breakdown.add(normals.header.seq, "SURFACE_NORMALS", e->timestamp, normals.header.utime, normals.processing_ms);
    } else if (decodeEvent(*e, ext)) {
      FrameRow& r = frames[ext.header.seq];
      r.has_extrinsics = true;
      r.extrinsics_valid = ext.valid;
      r.pitch_deg = ext.pitch_deg;
      r.roll_deg = ext.roll_deg;
      r.height_m = ext.height_m;
      r.confidence = ext.confidence;
    } else if (decodeEvent(*e, det)) {
      stage_ms["validator"].push_back(det.processing_ms);
      breakdown.add(det.header.seq, "DETECTIONS", e->timestamp, det.header.utime, det.processing_ms);
      FrameRow& r = frames[det.header.seq];
      r.hypotheses = det.num_detections;
      r.kept = det.num_kept;
      if (det.num_columns > 0) {
        r.observed_share = det.observed_share;
        r.unobserved = det.num_unobserved;
        r.columns = det.num_columns;
      }
      r.latency_ms = (e->timestamp - det.header.utime) / 1000.0;
      if (r.frame_id.empty()) r.frame_id = det.header.frame_id;
      latencies.push_back(r.latency_ms);
      last_detection_utime = std::max(last_detection_utime, e->timestamp);
      ++detections_events;
    } else if (decodeHealth(e->data, e->datalen, health)) {  // any layout: older logs too
      // (kept by prefix: which pipeline is read may be decided by a later frame event)
      const std::string p = nervChannelPrefix(e->channel).value_or("");
      health_by_prefix[p][health.service + "/" + health.instance] = health;
      resources_by_prefix[p].add(health);
    }
  }

  const std::string pipelines = pipeline.note();  // (throws when the prefix asked for is absent)
  const std::map<std::string, health_t>& last_health = health_by_prefix[pipeline.selected()];
  const ResourceTrend& resources = resources_by_prefix[pipeline.selected()];
  int frames_in = 0, frames_out = 0;
  std::vector<int64_t> missing;
  for (const auto& [seq, r] : frames) {
    frames_in += r.frame_event_utime >= 0;
    frames_out += r.hypotheses >= 0;
    if (r.frame_event_utime >= 0 && r.hypotheses < 0) missing.push_back(seq);
  }
  const double duration_s =
      (first_frame_utime >= 0 && last_detection_utime > first_frame_utime)
          ? (last_detection_utime - first_frame_utime) / 1e6 : 0;

  JsonWriter j(false);
  j.beginObject();
  j.field("log", log_path);
  j.field("prefix", pipeline.selected());
  j.key("prefixes");  // every pipeline in the log; the figures are of "prefix" only
  j.beginArray();
  for (const auto& p : pipeline.prefixes()) j.value(p);
  j.endArray();
  j.field("frames_in", frames_in);
  j.field("frames_out", frames_out);
  j.key("frames_without_detections");
  j.beginArray();
  for (int64_t s : missing) j.value(s);
  j.endArray();
  j.field("duration_s", duration_s);
  j.field("fps", duration_s > 0 ? frames_out / duration_s : 0.0);
  j.key("latency_ms");
  j.beginObject();
  j.field("p50", percentile(latencies, 0.5));
  j.field("p95", percentile(latencies, 0.95));
  j.field("max", latencies.empty() ? 0.0 : *std::max_element(latencies.begin(), latencies.end()));
  j.endObject();
  j.key("stage_processing_ms");
  j.beginObject();
  for (const auto& [stage, v] : stage_ms) {
    j.key(stage);
    j.beginObject();
    j.field("mean", mean(v));
    j.field("p95", percentile(v, 0.95));
    j.endObject();
  }
  j.endObject();
  j.key("events_per_channel");
  j.beginObject();
  for (const auto& [ch, n] : events_per_channel) j.field(ch, n);
  j.endObject();
  j.key("health");
  j.beginObject();
  for (const auto& [name, h] : last_health) {
    j.key(name);
    j.beginObject();
    j.field("frames_in", h.frames_in);
    j.field("frames_out", h.frames_out);
    j.field("frames_dropped", h.frames_dropped);
    j.field("errors", h.errors);
    j.field("last_error", h.last_error);
    j.field("version", h.version);
    j.key("gauges");  // last: the tests' greps of a service's object stop at the first '}'
    j.beginObject();
    for (int i = 0; i < h.num_gauges && i < static_cast<int>(h.gauge_values.size()); ++i)
      j.field(h.gauge_names[i], h.gauge_values[i]);
    j.endObject();
    j.endObject();
  }
  j.endObject();
  breakdown.writeJson(j);
  resources.writeJson(j);
  j.key("frames");
  j.beginArray();
  for (const auto& [seq, r] : frames) {
    j.beginObject();
    j.field("seq", seq);
    j.field("frame_id", r.frame_id);
    j.field("hypotheses", r.hypotheses);
    j.field("kept", r.kept);
    j.field("latency_ms", r.latency_ms);
    j.field("extrinsics_valid", r.extrinsics_valid);
    j.field("pitch_deg", r.pitch_deg);
    j.field("roll_deg", r.roll_deg);
    j.field("height_m", r.height_m);
    j.field("confidence", r.confidence);
    j.field("ground_source", r.ground_source);
    j.field("ground_height_m", r.ground_height_m);
    j.field("observed_share", r.observed_share);
    j.field("unobserved_strips", r.unobserved);
    j.field("strips", r.columns);
    j.endObject();
  }
  j.endArray();
  j.endObject();

  if (text_report) {
    char buf[512];
    std::string t = pipelines.empty() ? "" : pipelines + "\n";
    std::snprintf(buf, sizeof buf, "frames: %d in, %d out (%zu without DETECTIONS), %.1f fps over %.2f s\n",
                  frames_in, frames_out, missing.size(), duration_s > 0 ? frames_out / duration_s : 0.0, duration_s);
    t += buf;
    std::snprintf(buf, sizeof buf, "latency capture->DETECTIONS: p50 %.1f ms, p95 %.1f ms\n",
                  percentile(latencies, 0.5), percentile(latencies, 0.95));
    t += buf;
    t += "stage ms/frame:";
    for (const auto& [stage, v] : stage_ms) {
      std::snprintf(buf, sizeof buf, " %s %.1f", stage.c_str(), mean(v));
      t += buf;
    }
    t += "\n";
    t += breakdown.text();
    // A line per frame for a short run; a long one (a soak: 18007 frames) gets its first and last
    // ten, and every frame stays in the JSON.
    constexpr size_t kAllLinesUpTo = 30, kEnds = 10;
    size_t index = 0;
    for (const auto& [seq, r] : frames) {
      const size_t i = index++;
      if (frames.size() > kAllLinesUpTo && i >= kEnds && i < frames.size() - kEnds) {
        if (i == kEnds)
          t += "  ... " + std::to_string(frames.size() - 2 * kEnds) +
               " frames between these, every one in the summary JSON's \"frames\"\n";
        continue;
      }
      std::snprintf(buf, sizeof buf,
                    "  %-28s hyp %3d kept %3d  pitch %6.2f deg  height %5.2f m  conf %.2f  ground %s %.2f m",
                    r.frame_id.c_str(), r.hypotheses, r.kept, r.pitch_deg, r.height_m, r.confidence,
                    r.ground_source.c_str(), r.ground_height_m);
      t += buf;
      if (r.columns > 0) {  // free or unseen
        std::snprintf(buf, sizeof buf, "  seen %3.0f %%, %d/%d strips unobserved", 100.0 * r.observed_share,
                      r.unobserved, r.columns);
        t += buf;
      }
      t += "\n";
    }
    std::map<std::string, int> builds;  // which builds produced the log
    for (const auto& [name, h] : last_health) {
      std::snprintf(buf, sizeof buf, "health %-22s in %lld out %lld dropped %lld errors %lld", name.c_str(),
                    (long long)h.frames_in, (long long)h.frames_out, (long long)h.frames_dropped, (long long)h.errors);
      t += buf;
      for (int i = 0; i < h.num_gauges && i < static_cast<int>(h.gauge_values.size()); ++i) {
        std::snprintf(buf, sizeof buf, "  %s %.3g", h.gauge_names[i].c_str(), h.gauge_values[i]);
        t += buf;
      }
      t += (h.last_error.empty() ? "" : "  last: " + h.last_error) + "\n";
      ++builds[h.version.empty() ? "unknown" : h.version];
    }
    for (const auto& [version, n] : builds) t += "build nerv " + version + ": " + std::to_string(n) + " processes\n";
    t += resources.text();
    *text_report = t;
  }
  return j.str();
}

}  // namespace nerv
