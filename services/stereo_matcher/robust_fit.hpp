// Linear least squares of y on N terms, iteratively reweighted with Huber's weights (k = 1.345
// robust sigmas, the scale from the residuals' median absolute deviation), from a plain least
// squares start: the fits of the stereo_matcher's checks that compare tracked points with a
// motion model (shutter_sync.hpp, disparity_offset.hpp).
#pragma once

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "percentile.hpp"

namespace nerv::stereo {

template <int N>
using FitRow = std::array<double, N>;

template <int N>
using FitCovariance = cv::Matx<double, N, N>;

// coef: the N coefficients; covariance (when given): their covariance, the weighted residual
// variance times the inverse of the last weighted normal matrix. False when the terms cannot be
// told apart at these points (or a coefficient is not finite).
template <int N>
bool huberFit(const std::vector<FitRow<N>>& x, const std::vector<double>& y, FitRow<N>& coef,
              FitCovariance<N>* covariance = nullptr, int iterations = 10) {
  coef.fill(0);
  if (x.size() != y.size() || y.size() < static_cast<size_t>(N)) return false;
  std::vector<double> res(y.size()), abs_res(y.size()), weight(y.size(), 1.0);
  cv::Matx<double, N, N> ata;
  for (int iter = 0; iter < iterations; ++iter) {
    for (size_t i = 0; i < y.size(); ++i) {
      double m = 0;
      for (int j = 0; j < N; ++j) m += coef[j] * x[i][j];
      res[i] = y[i] - m;
      abs_res[i] = std::abs(res[i]);
    }
    const double scale = std::max(1e-3, 1.4826 * percentile(abs_res, 0.5));
    ata = cv::Matx<double, N, N>::zeros();
    cv::Vec<double, N> atb = cv::Vec<double, N>::all(0);
    for (size_t i = 0; i < y.size(); ++i) {
      const double r = std::abs(res[i]) / scale, w = iter == 0 || r <= 1.345 ? 1.0 : 1.345 / r;
      weight[i] = w;
      for (int j = 0; j < N; ++j) {
        atb[j] += w * x[i][j] * y[i];
        for (int k = 0; k < N; ++k) ata(j, k) += w * x[i][j] * x[i][k];
      }
    }
    cv::Vec<double, N> sol;
    if (!cv::solve(ata, atb, sol, cv::DECOMP_CHOLESKY)) return false;
    for (int j = 0; j < N; ++j) coef[j] = sol[j];
  }
  for (double c : coef)
    if (!std::isfinite(c)) return false;
  if (covariance) {
    double wrr = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      double m = 0;
      for (int j = 0; j < N; ++j) m += coef[j] * x[i][j];
      wrr += weight[i] * (y[i] - m) * (y[i] - m);
    }
    const double dof = std::max<double>(1.0, static_cast<double>(y.size()) - N);
    *covariance = ata.inv(cv::DECOMP_CHOLESKY) * (wrr / dof);
  }
  return true;
}

}  // namespace nerv::stereo
