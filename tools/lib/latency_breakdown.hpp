// Where a frame's latency goes, from the logger's receive times alone.
//
// Every message of a frame carries the capture utime of its STEREO_FRAME, and
// lcm-logger stamps each event with the time it received it; on one bus all
// subscribers receive a message at about the same time, so the logger's stamp
// stands for the time each service got its input. For a stage with inputs
// I and output O:
//   stage time = arrival(O) - latest arrival(I)
//              = processing_ms (what the service measured around its work)
//              + the rest: waiting in the service's queue behind an earlier
//                frame, decoding the input, encoding and sending the output.
// Arrivals are relative to capture, so they add up to the end-to-end latency.
// Across hosts the stage times hold when the logger runs on one host; the
// arrivals then also carry the offset between its clock and the camera's.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace nerv {

class JsonWriter;

class LatencyBreakdown {
 public:
  // A logged message of frame `seq`: channel, logger receive time and the
  // frame's capture utime [us]; processing_ms < 0 for messages without one.
  void add(int64_t seq, const std::string& channel, int64_t log_utime, int64_t capture_utime,
           double processing_ms);

  struct Stage {
    std::string name, output;
    std::vector<std::string> inputs;
  };
  // The pipeline's stages in order (stereo_matcher, stixel, snv_extrinsic, validator).
  static const std::vector<Stage>& stages();

  struct StageFigures {
    int frames = 0;                      // frames with the output and every input logged
    double stage_p50 = 0, stage_p95 = 0;  // arrival(O) - latest arrival(I) [ms]
    double processing_p50 = 0;           // the service's own figure [ms]
    double rest_p50 = 0, rest_p95 = 0;   // stage time - processing [ms]
  };
  StageFigures figures(const Stage& stage) const;
  // p50 of a channel's arrival after capture [ms] (-1 when never logged).
  double arrivalP50(const std::string& channel) const;

  // "latency_breakdown_ms": {"arrival_p50": {...}, "stages": {...}}
  void writeJson(JsonWriter& j) const;
  // Two lines: the arrivals, then each stage as processing + rest.
  std::string text() const;

 private:
  struct Event {
    bool seen = false;
    double arrival_ms = 0, processing_ms = -1;  // arrival < 0 when clocks of two hosts differ
  };
  std::map<int64_t, std::map<std::string, Event>> frames_;
};

}  // namespace nerv
