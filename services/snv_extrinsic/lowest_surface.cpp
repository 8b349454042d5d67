#include "lowest_surface.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::snv {

int selectLowestSurface(const std::vector<PlanePoint>& pts, const DisparityPlane& start,
                        const StereoCamera& cam, const LowestSurfaceParams& p,
                        std::vector<unsigned char>& keep) {
  keep.assign(pts.size(), 0);
  if (pts.empty() || !start.valid || p.band_rows < 1 || !(p.bin > 0)) return 0;
  const int bins = std::max(3, static_cast<int>(std::ceil(2 * p.range / p.bin)));
  const int bands = cam.height / p.band_rows + 1;
  std::vector<float> res(pts.size());
  std::vector<int> band_of(pts.size()), hist(static_cast<size_t>(bands) * bins, 0), total(bands, 0);
  for (size_t i = 0; i < pts.size(); ++i) {
    res[i] = static_cast<float>((pts[i].d - start.disparity(cam, pts[i].u, pts[i].v)) / pts[i].d);
    band_of[i] = std::clamp(static_cast<int>(pts[i].v) / p.band_rows, 0, bands - 1);
    const int b = static_cast<int>(std::floor((res[i] + p.range) / p.bin));
    if (b < 0 || b >= bins) continue;
    ++hist[static_cast<size_t>(band_of[i]) * bins + b];
    ++total[band_of[i]];
  }
  // Road residual of each band: the lowest local maximum of the [1 2 1]-smoothed
  // histogram that is large enough; NaN = none.
  std::vector<float> road(bands, std::nanf(""));
  std::vector<float> smooth(bins);
  for (int band = 0; band < bands; ++band) {
    if (total[band] == 0) continue;
    const int* h = &hist[static_cast<size_t>(band) * bins];
    for (int b = 0; b < bins; ++b)
      smooth[b] = 0.25f * ((b > 0 ? h[b - 1] : 0) + 2.0f * h[b] + (b + 1 < bins ? h[b + 1] : 0));
    // Mass within +-tolerance of a bin, from the raw counts.
    const int half = std::max(0, static_cast<int>(p.tolerance / p.bin));
    const float need = std::max(p.min_peak_fraction * total[band], static_cast<float>(p.min_peak_count));
    for (int b = 0; b < bins; ++b) {
      const bool peak = (b == 0 || smooth[b] >= smooth[b - 1]) && (b + 1 == bins || smooth[b] > smooth[b + 1]);
      if (!peak || smooth[b] <= 0) continue;
      int mass = 0;
      for (int k = std::max(0, b - half); k <= std::min(bins - 1, b + half); ++k) mass += h[k];
      if (mass >= need) {
        road[band] = -p.range + (b + 0.5f) * p.bin;
        break;
      }
    }
  }
  // Centre each band's peak on its samples: a few mean-shift steps (mean of the
  // residuals within +-tolerance), so the symmetric cut below does not clip one
  // side of the road's noise (a bin-centre peak is up to half a bin off).
  for (int it = 0; it < 3; ++it) {
    std::vector<double> sum(bands, 0.0);
    std::vector<int> n(bands, 0);
    for (size_t i = 0; i < pts.size(); ++i) {
      const float r0 = road[band_of[i]];
      if (std::isfinite(r0) && std::abs(res[i] - r0) <= p.tolerance) {
        sum[band_of[i]] += res[i];
        ++n[band_of[i]];
      }
    }
    for (int band = 0; band < bands; ++band)
      if (n[band] > 0) road[band] = static_cast<float>(sum[band] / n[band]);
  }
  int kept = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const float r0 = road[band_of[i]];
    if (std::isfinite(r0) && std::abs(res[i] - r0) <= p.tolerance) {
      keep[i] = 1;
      ++kept;
    }
  }
  return kept;
}

}  // namespace nerv::snv
