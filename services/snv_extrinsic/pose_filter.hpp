// Temporal filter of the camera pose: one scalar Kalman filter per quantity
// (pitch, roll, height) with a random-walk model. Each frame predict() grows the
// variance by the process noise; a valid measurement update()s it. The state
// variance is what extrinsics_t.filter_pitch_var reports.
#pragma once

namespace nerv::snv {

class ScalarKalman {
 public:
  bool initialised() const { return initialised_; }
  float value() const { return x_; }
  float variance() const { return p_; }
  void reset(float x, float var) {
    x_ = x;
    p_ = var;
    initialised_ = true;
  }
  void predict(float process_var) {
    if (initialised_) p_ += process_var;
  }
  // First measurement initialises the state with the measurement variance.
  // adaptive: before the gain, the prior variance is raised to innovation^2 -
  // measurement_var when that is larger (the random walk underestimated the
  // motion: a +-2 deg pitch swing moves ~1 deg per frame), so the state tracks
  // fast motion and still averages the noise when the pose is steady.
  void update(float z, float measurement_var, bool adaptive = false);

 private:
  bool initialised_ = false;
  float x_ = 0, p_ = 0;
};

struct PoseFilterParams {
  float pitch_process_var_deg2 = 0.05f;   // pitch random walk per frame [deg^2]
  float roll_process_var_deg2 = 0.05f;    // roll random walk per frame [deg^2]
  float height_process_var_m2 = 1e-4f;    // height random walk per frame [m^2]
  float pitch_measurement_var_deg2 = 0.04f;  // variance of one frame's pitch [deg^2]
  float roll_measurement_var_deg2 = 0.04f;   // variance of one frame's roll [deg^2]
  float height_measurement_var_m2 = 4e-4f;   // variance of one frame's height [m^2]
  bool adaptive = false;                      // innovation-based prior inflation (ScalarKalman::update)
};

class PoseFilter {
 public:
  explicit PoseFilter(const PoseFilterParams& params = {}) : params_(params) {}
  void predict();
  void update(float pitch_deg, float roll_deg, float height_m);
  bool initialised() const { return pitch_.initialised(); }
  const ScalarKalman& pitch() const { return pitch_; }
  const ScalarKalman& roll() const { return roll_; }
  const ScalarKalman& height() const { return height_; }

 private:
  PoseFilterParams params_;
  ScalarKalman pitch_, roll_, height_;
};

}  // namespace nerv::snv
