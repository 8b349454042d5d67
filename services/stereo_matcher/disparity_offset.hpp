// Is every disparity off by the same amount? A right camera turned about its vertical axis
// since calibration (a knock, a loosening mount, heat), or principal points that differ from
// the calibration's, add a constant to every disparity: 0.5 px is a 5 % error in every
// distance at 40 m with the KITTI rig (d = 9.7 px there). The rows stay aligned, and on a
// flat road the offset looks like a pitch change, so one pair cannot show it. The vehicle's
// own forward motion can: a step s along the optical axis moves a static point at depth
// Z = f B / d from u' in the earlier view to u = u' (1 + s / Z), exactly, so
//   u - u' = k u' (d_true) = k u' (d - e),   k = s / (f B),
// where d = d_true + e is the disparity the matcher measured. Points at every depth in the
// same columns tell the slope k from the offset e. Fitted robustly (Huber) in the earlier
// view's coordinates (u', v'), with the rotation between the frames (yaw wy (f + u'^2 / f),
// pitch wx u' v' / f, roll wz v') and a sideways step (h d):
//   u - u' = wy (f + u'^2 / f) + wx u' v' / f + wz v' + h d + k u' d - k e u'
// e is minus the coefficient of u' over the coefficient of u' d. Only the horizontal flow is
// used: the vertical one carries the same e but read 0.6-1.2 px off on KITTI 0926 (its
// terms are harder to tell apart on a road, where v' d grows like v'^2).
#pragma once

#include <string>

#include "motion_tracks.hpp"
#include "verdict_window.hpp"

namespace nerv::stereo {

struct DisparityOffsetParams {
  int min_points = 60;          // fewer tracked points: no measurement
  // The step must move the columns by at least this much at the points (90th percentile of
  // |k u' d|): standing or creeping, there is nothing to compare the disparity with.
  float min_motion_px = 1.5f;
  // The offset's standard error from the fit above this: the points do not tell the offset
  // from the step (on a motorway most points lie on rails and lane edges parallel to the
  // motion, where u' is proportional to d and the terms coincide: highway seed 23 2.4-84 px,
  // against 0.10-0.30 px on urban seed 11 and KITTI 0926).
  float max_sigma_px = 0.5f;
};

struct DisparityOffset {
  bool valid = false;
  int points = 0;          // points in the fit
  double k = 0;            // the forward step / (f B) [1/px^2]; > 0 forward
  float motion_px = 0;     // 90th percentile of |k u' d| at the points [px]
  float offset_px = 0;     // e: what the matcher's disparity reads more than the motion says [px]
  float sigma_px = 0;      // its standard error from the fit [px]
};

// tracks: trackMotion() of the earlier left view, the left view and its disparity; (cx, cy)
// and fx: the rectified camera [px]. Throws nothing: too few points, a standing or reversing
// vehicle or a fit that cannot tell its terms apart give valid = false.
DisparityOffset measureDisparityOffset(const MotionTracks& tracks, double fx, double cx, double cy,
                                       const DisparityOffsetParams& params = {});

// One line of a verdict over offsets [px]: "the disparity reads 0.62 px more than the forward
// motion says (median of the last 10 checks while moving, 0.41 to 0.80 px)". applied: the
// offset the right views were corrected by while the checks read them, added back, so the
// line is the rig's against its calibration.
std::string describeDisparityOffset(const MedianVerdict& offsets, double applied = 0);

}  // namespace nerv::stereo
