// Sign plates above an occluder. A sign post behind a parked car shows only
// its part above the car's roof: 1-4 px of post from ~1.5 m to the sky cut
// (2.5 m), which the matcher mostly loses against the facade behind, and a
// plate of 0.4-0.8 m at 3-4 m, which keeps its disparity but lies above the sky
// cut. The second layer (occluded_stixels.hpp) counts only pixels below the sky
// cut, so the post fills less than the minimum obstacle height and the nearest
// surface that does is the facade 10-25 m behind it (urban seed 12: the signs
// to the right of the road at 15-38 m, covered in 0 of their frames).
// For each first stixel whose top is at most max_occluder_height_m over the
// road, the pixels above its top that lie farther than it and min_gap_m nearer
// than its second-layer stixel (if any), between min_plate_bottom_m and
// max_plate_top_m over the road, vote into a disparity histogram; from the
// nearest bin, a bin whose window holds a plate's worth of pixels is tested
// with the sign plate test (findPlateRows: rows filling the strip at that
// disparity, nothing at it or nearer max_plate_width_m beside, both sides in
// the image), and the plate must be closed (it ends below the search). The
// first plate found becomes the strip's second-layer stixel: from the
// occluder's top up to the plate's top, its base on the road line at the
// plate's disparity.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "sign_plates.hpp"
#include "stereo_camera.hpp"
#include "stixel_extraction.hpp"

namespace nerv::stixel {

struct OccludedPlateParams {
  float max_plate_top_m = 0.0f;  // plates are searched up to this height over the road (0 = off)
  float max_distance_m = 40.0f;  // ... at most this far ...
  float max_occluder_height_m = 2.5f;  // ... above first stixels whose top is at most this high ...
  float min_gap_m = 0.0f;        // ... and this much nearer than the strip's second-layer stixel
  SignPlateParams plate;         // the plate test (its max_foot_height_m is not used)
};

// first: first-layer stixels; behind: their second-layer stixels (sorted by u, at
// most one per strip). A strip's stixel in `behind` farther than a plate found
// above its occluder is replaced by the plate's post, a strip without one gets
// it; `behind` stays sorted by u. Returns copies of the posts (kept when alone).
std::vector<Stixel> placeOccludedPlates(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                                        const std::vector<Stixel>& first, std::vector<Stixel>& behind,
                                        const StixelExtractionParams& ep, const OccludedPlateParams& p);

}  // namespace nerv::stixel
