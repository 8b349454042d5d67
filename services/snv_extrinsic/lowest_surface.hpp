// Which ground samples lie on the road itself rather than on a raised surface
// beside it (sidewalks, kerb tops, traffic islands).
//
// Why: the ground samples hold every pixel whose normal points up, and raised
// sidewalks are parallel to the road, so they pass the normal tests and the
// mean-shift window. Where the matcher leaves the road centre sparse (nerv_sgm:
// low-texture asphalt has holes and few normals) and the camera looks up, the
// sidewalk samples outnumber the road's in the middle and far rows and capture
// the robust plane (measured on pitch_oscillation frames 8-10: plane 1.1-1.7 deg
// off, its roll 0.2 deg off; docs/snv.md).
//
// The road is the lowest of the horizontal surfaces: at the same pixel a raised
// surface is nearer, so its disparity is larger than the road plane's by the
// relative amount dh / h (15 cm over 1.65 m: +9 %). Per band of image rows the
// relative residuals r = (d - d_plane) / d to a start plane are histogrammed; the
// road is the lowest local maximum (histogram smoothed [1 2 1]) with at least
// max(min_peak_fraction of the band, min_peak_count) samples within +-tolerance. Within one band the depth range is small, so a
// pitch error of the start plane shifts all its residuals alike and does not
// merge the two surfaces. Samples within `tolerance` of their band's road peak
// are kept.
#pragma once

#include <vector>

#include "ground_plane_fit.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

struct LowestSurfaceParams {
  int band_rows = 16;               // image rows per band [px]
  float bin = 0.005f;               // histogram bin of the relative residual
  float range = 0.25f;              // residuals outside +-range are ignored
  float min_peak_fraction = 0.1f;   // a road peak has at least this share of its band within +-tolerance ...
  int min_peak_count = 8;           // ... and at least this many samples
  float tolerance = 0.035f;         // samples within this relative residual of the peak are kept
};

// keep[i] = 1 when points[i] lies on the lowest surface of its band (0 also for
// bands with no peak). Returns the number kept.
int selectLowestSurface(const std::vector<PlanePoint>& points, const DisparityPlane& start,
                        const StereoCamera& cam, const LowestSurfaceParams& params,
                        std::vector<unsigned char>& keep);

}  // namespace nerv::snv
