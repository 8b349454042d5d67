// Whether a noisy rig reading (the shutter delay, the disparity offset) says the rig changed
// since the last verdict. The verdicts are medians of 10 checks of every tenth frame, 100
// frames apart: a camera knocked or a trigger lost mid-drive would become an error only once
// its readings outvote the old ones in the window, 10-100 s later. A single reading on the
// other side of the limit from the last verdict is only suspect: single readings cross the
// limit on 0-27 % of the checks of a rig in order (13 synthetic sets and KITTI 0926, median
// under it on all), so it asks for one more check on the next frame. A second one in a row is
// a change: the caller forgets the window and checks every frame until the next verdict,
// which is then of those readings alone, 11-20 frames after the change. Only readings clearly
// across count (a margin of 1.25 around the limit): a rig 1.8 ms late against a 2 ms limit set
// off 4 bursts in 100 frames and turned its verdict four times without it, none with it.
#pragma once

#include <cmath>

namespace nerv::stereo {

class ChangeWatch {
 public:
  enum class Step {
    Nothing,  // in line with the last verdict, or no verdict yet, or a change already watched
    Confirm,  // suspect: check the next frame too
    Restart,  // a change: forget the window, check every frame until the next verdict
  };
  // A verdict was given: beyond the limit or not, on `median`. Watching starts (again) from it.
  void verdict(bool beyond, float median) {
    state_ = beyond ? State::Beyond : State::Within;
    verdict_value_ = median;
    suspect_ = watching_ = false;
  }
  // A measured reading (the caller leaves out what could not be measured); `value` is kept for
  // the caller's line.
  Step reading(float value, float limit) {
    // Against the verdict only clearly: beyond margin x the limit after a verdict within it,
    // under the limit / margin after one beyond it.
    const float v = std::abs(value);
    const bool against = state_ == State::Within ? v > limit * kMargin : v < limit / kMargin;
    if (state_ == State::None || watching_ || !against) {
      suspect_ = false;
      return Step::Nothing;
    }
    if (!suspect_) {
      suspect_ = true;
      suspect_value_ = value;
      return Step::Confirm;
    }
    suspect_ = false;
    watching_ = true;
    return Step::Restart;
  }
  // The suspect reading a Restart confirmed, and the last verdict's median.
  float suspectValue() const { return suspect_value_; }
  float verdictValue() const { return verdict_value_; }

 private:
  enum class State { None, Within, Beyond } state_ = State::None;
  bool suspect_ = false, watching_ = false;
  float suspect_value_ = 0, verdict_value_ = 0;
  static constexpr float kMargin = 1.25f;
};

}  // namespace nerv::stereo
