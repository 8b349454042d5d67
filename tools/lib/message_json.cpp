#include "message_json.hpp"

#include <cstring>

#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "health_compat.hpp"
#include "message_fingerprint.hpp"
#include "nerv/health_t.hpp"
#include "nerv/health_v1_t.hpp"
#include "nerv/health_v2_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

namespace nerv {
namespace {

// Declared up front so the array helpers below can see every overload.
void write(JsonWriter& j, double v);
void write(JsonWriter& j, const std::string& v);
void write(JsonWriter& j, int64_t v);
void write(JsonWriter& j, const stixel_t& m);
void write(JsonWriter& j, const roi_t& m);
void write(JsonWriter& j, const normal_stats_t& m);
void write(JsonWriter& j, const detection_t& m);

template <class T>
void array(JsonWriter& j, const std::string& k, const T* v, size_t n) {
  j.key(k);
  j.beginArray();
  for (size_t i = 0; i < n; ++i) write(j, v[i]);
  j.endArray();
}
template <class T>
void array(JsonWriter& j, const std::string& k, const std::vector<T>& v) {
  array(j, k, v.data(), v.size());
}

void write(JsonWriter& j, double v) { j.value(v); }
void write(JsonWriter& j, const std::string& v) { j.value(v); }
void write(JsonWriter& j, int64_t v) { j.value(v); }

void write(JsonWriter& j, const header_t& m) {
  j.beginObject();
  j.field("seq", m.seq);
  j.field("utime", m.utime);
  j.field("frame_id", m.frame_id);
  j.endObject();
}

void write(JsonWriter& j, const stereo_calibration_t& m) {
  j.beginObject();
  j.field("width", m.width);
  j.field("height", m.height);
  j.field("fx", m.fx);
  j.field("fy", m.fy);
  j.field("cx", m.cx);
  j.field("cy", m.cy);
  j.field("baseline_m", m.baseline_m);
  j.field("rectified", m.rectified != 0);  // LCM boolean
  array(j, "left_K", m.left_K, 9);
  array(j, "left_D", m.left_D, 5);
  array(j, "right_K", m.right_K, 9);
  array(j, "right_D", m.right_D, 5);
  array(j, "R", m.R, 9);
  array(j, "T", m.T, 3);
  j.endObject();
}

void write(JsonWriter& j, const image_t& m) {
  j.beginObject();
  j.field("width", m.width);
  j.field("height", m.height);
  j.field("channels", m.channels);
  j.field("encoding", m.encoding);
  j.field("size", m.size);
  j.field("data", m.data);
  j.endObject();
}

void write(JsonWriter& j, const stereo_frame_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.key("calib"); write(j, m.calib);
  j.key("left"); write(j, m.left);
  j.key("right"); write(j, m.right);
  j.endObject();
}

void write(JsonWriter& j, const disparity_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.key("calib"); write(j, m.calib);
  j.field("width", m.width);
  j.field("height", m.height);
  j.field("scale", m.scale);
  j.field("encoding", m.encoding);
  j.field("size", m.size);
  j.field("data", m.data);
  j.field("confidence_size", m.confidence_size);
  j.field("confidence", m.confidence);
  j.field("algorithm", m.algorithm);
  j.field("min_disparity", m.min_disparity);
  j.field("max_disparity", m.max_disparity);
  j.field("processing_ms", m.processing_ms);
  j.endObject();
}

void write(JsonWriter& j, const ground_model_t& m) {
  j.beginObject();
  j.field("valid", m.valid != 0);  // LCM boolean
  j.field("source", m.source);
  j.field("vd_slope", m.vd_slope);
  j.field("vd_intercept", m.vd_intercept);
  j.field("horizon_row", m.horizon_row);
  j.field("pitch_deg", m.pitch_deg);
  j.field("roll_deg", m.roll_deg);
  j.field("height_m", m.height_m);
  j.field("inliers", m.inliers);
  j.field("residual_px", m.residual_px);
  j.endObject();
}

void write(JsonWriter& j, const stixel_t& m) {
  j.beginObject();
  j.field("u", m.u);
  j.field("width", m.width);
  j.field("top_row", m.top_row);
  j.field("bottom_row", m.bottom_row);
  j.field("disparity", m.disparity);
  j.field("depth_m", m.depth_m);
  j.field("base_x_m", m.base_x_m);
  j.field("base_y_m", m.base_y_m);
  j.field("base_z_m", m.base_z_m);
  j.endObject();
}

void write(JsonWriter& j, const roi_t& m) {
  j.beginObject();
  j.field("id", m.id);
  j.field("x", m.x);
  j.field("y", m.y);
  j.field("w", m.w);
  j.field("h", m.h);
  j.field("x_m", m.x_m);
  j.field("y_m", m.y_m);
  j.field("z_m", m.z_m);
  j.field("width_m", m.width_m);
  j.field("height_m", m.height_m);
  j.field("distance_m", m.distance_m);
  j.field("nearest_z_m", m.nearest_z_m);
  j.field("nearest_z_sigma_m", m.nearest_z_sigma_m);
  j.field("disparity", m.disparity);
  j.field("num_stixels", m.num_stixels);
  j.endObject();
}

void write(JsonWriter& j, const stixels_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.key("ground"); write(j, m.ground);
  j.field("num_stixels", m.num_stixels);
  array(j, "stixels", m.stixels);
  j.field("num_rois", m.num_rois);
  array(j, "rois", m.rois);
  j.field("column_width_px", m.column_width_px);
  j.field("num_columns", m.num_columns);
  array(j, "observed", m.observed);
  j.field("min_observed", m.min_observed);
  j.field("observed_share", m.observed_share);
  j.field("num_unobserved", m.num_unobserved);
  j.field("processing_ms", m.processing_ms);
  j.endObject();
}

void write(JsonWriter& j, const normal_stats_t& m) {
  j.beginObject();
  j.field("roi_id", m.roi_id);
  j.field("num_samples", m.num_samples);
  j.field("num_normals", m.num_normals);
  j.field("density", m.density);
  j.field("ground_fraction", m.ground_fraction);
  j.field("object_fraction", m.object_fraction);
  j.field("error_fraction", m.error_fraction);
  j.field("normal_x", m.normal_x);
  j.field("normal_y", m.normal_y);
  j.field("normal_z", m.normal_z);
  j.field("pitch_deg", m.pitch_deg);
  j.field("yaw_deg", m.yaw_deg);
  j.field("tilt_from_ground_deg", m.tilt_from_ground_deg);
  j.endObject();
}

void write(JsonWriter& j, const surface_normals_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.field("interval_px", m.interval_px);
  j.field("ground_samples", m.ground_samples);
  j.field("ground_normal_x", m.ground_normal_x);
  j.field("ground_normal_y", m.ground_normal_y);
  j.field("ground_normal_z", m.ground_normal_z);
  j.field("num_rois", m.num_rois);
  array(j, "rois", m.rois);
  j.field("processing_ms", m.processing_ms);
  j.endObject();
}

void write(JsonWriter& j, const extrinsics_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.field("valid", m.valid != 0);  // LCM boolean
  j.field("status", m.status);
  j.field("pitch_deg", m.pitch_deg);
  j.field("roll_deg", m.roll_deg);
  j.field("height_m", m.height_m);
  j.field("instant_pitch_deg", m.instant_pitch_deg);
  j.field("instant_roll_deg", m.instant_roll_deg);
  j.field("instant_height_m", m.instant_height_m);
  j.field("pitch_mode_deg", m.pitch_mode_deg);
  j.field("pitch_mean_deg", m.pitch_mean_deg);
  j.field("pitch_mean_shift_deg", m.pitch_mean_shift_deg);
  j.field("entropy", m.entropy);
  j.field("confidence", m.confidence);
  j.field("num_normals", m.num_normals);
  j.field("inliers", m.inliers);
  j.field("filter_pitch_var", m.filter_pitch_var);
  j.field("processing_ms", m.processing_ms);
  j.endObject();
}

void write(JsonWriter& j, const detection_t& m) {
  j.beginObject();
  j.field("roi_id", m.roi_id);
  j.field("x", m.x);
  j.field("y", m.y);
  j.field("w", m.w);
  j.field("h", m.h);
  j.field("x_m", m.x_m);
  j.field("y_m", m.y_m);
  j.field("z_m", m.z_m);
  j.field("width_m", m.width_m);
  j.field("height_m", m.height_m);
  j.field("distance_m", m.distance_m);
  j.field("nearest_z_m", m.nearest_z_m);
  j.field("nearest_z_sigma_m", m.nearest_z_sigma_m);
  j.field("label", m.label);
  j.field("score", m.score);
  j.field("kept", m.kept != 0);  // LCM boolean
  j.field("reason", m.reason);
  j.endObject();
}

void write(JsonWriter& j, const detections_t& m) {
  j.beginObject();
  j.key("header"); write(j, m.header);
  j.field("num_detections", m.num_detections);
  array(j, "detections", m.detections);
  j.field("num_kept", m.num_kept);
  j.field("num_columns", m.num_columns);
  j.field("num_unobserved", m.num_unobserved);
  j.field("observed_share", m.observed_share);
  j.field("processing_ms", m.processing_ms);
  j.endObject();
}

void write(JsonWriter& j, const health_t& m) {
  j.beginObject();
  j.field("utime", m.utime);
  j.field("service", m.service);
  j.field("instance", m.instance);
  j.field("host", m.host);
  j.field("pid", m.pid);
  j.field("frames_in", m.frames_in);
  j.field("frames_out", m.frames_out);
  j.field("frames_dropped", m.frames_dropped);
  j.field("errors", m.errors);
  j.field("num_counters", m.num_counters);
  array(j, "counter_names", m.counter_names);
  array(j, "counter_values", m.counter_values);
  j.field("num_gauges", m.num_gauges);
  array(j, "gauge_names", m.gauge_names);
  array(j, "gauge_values", m.gauge_values);
  j.field("latency_p50_ms", m.latency_p50_ms);
  j.field("latency_p95_ms", m.latency_p95_ms);
  j.field("processing_ms", m.processing_ms);
  j.field("status", m.status);
  j.field("last_error", m.last_error);
  j.field("version", m.version);
  j.endObject();
}

template <class T>
bool tryType(const void* data, int size, JsonWriter& json, std::string& name) {
  if (messageFingerprint(data, size) != T::getHash()) return false;
  T msg;
  try {
    if (msg.decode(data, 0, size) < 0) return true;  // right type, broken payload
  } catch (const std::exception&) {
    return true;  // a corrupt array length makes the decoder throw
  }
  write(json, msg);
  name = std::string("nerv.") + T::getTypeName();
  return true;
}

// NERV_HEALTH of an older layout (logs recorded before health_t gained its build stamp or its
// gauges): written as a health_t, the fields it lacked empty, under its own type's name.
bool tryOlderHealth(const void* data, int size, JsonWriter& json, std::string& name) {
  const int64_t fp = messageFingerprint(data, size);
  if (fp != health_v1_t::getHash() && fp != health_v2_t::getHash()) return false;
  health_t m;
  if (!decodeHealth(data, size, m)) return true;  // right type, broken payload
  write(json, m);
  name = std::string("nerv.") + (fp == health_v1_t::getHash() ? health_v1_t::getTypeName() : health_v2_t::getTypeName());
  return true;
}

}  // namespace

std::string writeMessageJson(const void* data, int size, JsonWriter& json) {
  std::string name;
  tryType<stereo_frame_t>(data, size, json, name) || tryType<disparity_t>(data, size, json, name) ||
      tryType<stixels_t>(data, size, json, name) ||
      tryType<surface_normals_t>(data, size, json, name) ||
      tryType<extrinsics_t>(data, size, json, name) ||
      tryType<detections_t>(data, size, json, name) || tryType<health_t>(data, size, json, name) ||
      tryOlderHealth(data, size, json, name);
  return name;
}

}  // namespace nerv
