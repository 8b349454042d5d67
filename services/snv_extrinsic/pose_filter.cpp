#include "pose_filter.hpp"

namespace nerv::snv {

void ScalarKalman::update(float z, float measurement_var) {
  if (!initialised_) {
    reset(z, measurement_var);
    return;
  }
  const float gain = p_ / (p_ + measurement_var);
  x_ += gain * (z - x_);
  p_ *= 1.0f - gain;
}

void PoseFilter::predict() {
  pitch_.predict(params_.pitch_process_var_deg2);
  roll_.predict(params_.roll_process_var_deg2);
  height_.predict(params_.height_process_var_m2);
}

void PoseFilter::update(float pitch_deg, float roll_deg, float height_m) {
  pitch_.update(pitch_deg, params_.pitch_measurement_var_deg2);
  roll_.update(roll_deg, params_.roll_measurement_var_deg2);
  height_.update(height_m, params_.height_measurement_var_m2);
}

}  // namespace nerv::snv
