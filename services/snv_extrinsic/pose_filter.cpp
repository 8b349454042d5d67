#include "pose_filter.hpp"

#include <algorithm>

namespace nerv::snv {

void ScalarKalman::update(float z, float measurement_var, bool adaptive) {
  if (!initialised_) {
    reset(z, measurement_var);
    return;
  }
  if (adaptive) {
    const float innovation = z - x_;
    p_ = std::max(p_, innovation * innovation - measurement_var);
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
  pitch_.update(pitch_deg, params_.pitch_measurement_var_deg2, params_.adaptive);
  roll_.update(roll_deg, params_.roll_measurement_var_deg2, params_.adaptive);
  height_.update(height_m, params_.height_measurement_var_m2, params_.adaptive);
}

}  // namespace nerv::snv
