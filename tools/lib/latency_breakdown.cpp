#include "latency_breakdown.hpp"

#include <algorithm>
#include <cstdio>

#include "json_writer.hpp"
#include "percentile.hpp"

namespace nerv {
namespace {

const char* kChannels[] = {"STEREO_FRAME", "DISPARITY", "STIXELS", "SURFACE_NORMALS", "DETECTIONS"};

}  // namespace

void LatencyBreakdown::add(int64_t seq, const std::string& channel, int64_t log_utime, int64_t capture_utime,
                           double processing_ms) {
  Event& e = frames_[seq][channel];
  // A frame answered twice (a restarted shard): the first answer is the one that counted.
  if (e.seen) return;
  e.seen = true;
  e.arrival_ms = (log_utime - capture_utime) / 1000.0;
  e.processing_ms = processing_ms;
}

const std::vector<LatencyBreakdown::Stage>& LatencyBreakdown::stages() {
  static const std::vector<Stage> s = {
      {"stereo_matcher", "DISPARITY", {"STEREO_FRAME"}},
      {"stixel", "STIXELS", {"DISPARITY"}},
      {"snv_extrinsic", "SURFACE_NORMALS", {"DISPARITY", "STIXELS"}},
      {"validator", "DETECTIONS", {"STIXELS", "SURFACE_NORMALS"}},
  };
  return s;
}

LatencyBreakdown::StageFigures LatencyBreakdown::figures(const Stage& stage) const {
  std::vector<double> total, processing, rest;
  for (const auto& [seq, events] : frames_) {
    const auto out = events.find(stage.output);
    if (out == events.end()) continue;
    double latest_in = -1e300;
    bool complete = true;
    for (const std::string& in : stage.inputs) {
      const auto it = events.find(in);
      if (it == events.end()) {
        complete = false;
        break;
      }
      latest_in = std::max(latest_in, it->second.arrival_ms);
    }
    if (!complete) continue;
    const double t = out->second.arrival_ms - latest_in;
    total.push_back(t);
    if (out->second.processing_ms >= 0) {
      processing.push_back(out->second.processing_ms);
      rest.push_back(t - out->second.processing_ms);
    }
  }
  StageFigures f;
  f.frames = static_cast<int>(total.size());
  f.stage_p50 = percentile(total, 0.5);
  f.stage_p95 = percentile(total, 0.95);
  f.processing_p50 = percentile(processing, 0.5);
  f.rest_p50 = percentile(rest, 0.5);
  f.rest_p95 = percentile(rest, 0.95);
  return f;
}

double LatencyBreakdown::arrivalP50(const std::string& channel) const {
  std::vector<double> v;
  for (const auto& [seq, events] : frames_)
    if (const auto it = events.find(channel); it != events.end()) v.push_back(it->second.arrival_ms);
  return v.empty() ? -1 : percentile(v, 0.5);
}

void LatencyBreakdown::writeJson(JsonWriter& j) const {
  j.key("latency_breakdown_ms");
  j.beginObject();
  j.key("arrival_p50");
  j.beginObject();
  for (const char* ch : kChannels) j.field(ch, arrivalP50(ch));
  j.endObject();
  j.key("stages");
  j.beginObject();
  for (const Stage& s : stages()) {
    const StageFigures f = figures(s);
    j.key(s.name);
    j.beginObject();
    j.field("frames", f.frames);
    j.field("stage_p50", f.stage_p50);
    j.field("stage_p95", f.stage_p95);
    j.field("processing_p50", f.processing_p50);
    j.field("rest_p50", f.rest_p50);
    j.field("rest_p95", f.rest_p95);
    j.endObject();
  }
  j.endObject();
  j.endObject();
}

std::string LatencyBreakdown::text() const {
  std::string t = "arrival after capture, p50 [ms]:";
  char buf[160];
  for (const char* ch : kChannels) {
    std::snprintf(buf, sizeof buf, " %s %.1f", ch, arrivalP50(ch));
    t += buf;
  }
  t += "\nstage time, p50 [ms] = processing + the rest (queue, decode, encode, transport):";
  for (const Stage& s : stages()) {
    const StageFigures f = figures(s);
    std::snprintf(buf, sizeof buf, " %s %.1f = %.1f + %.1f (rest p95 %.1f);", s.name.c_str(), f.stage_p50,
                  f.processing_p50, f.rest_p50, f.rest_p95);
    t += buf;
  }
  t += "\n";
  return t;
}

}  // namespace nerv
