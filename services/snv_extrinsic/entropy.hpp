// Entropy confidence of a super-SNV estimate (NERV slides 27-28).
//
// What is computed: for an estimate c, take the `fraction` of all samples
// nearest to c (the same window the adaptive mean shift uses), bin them at
// bin_deg (bins centred on c, so an exact cluster at c is one bin whatever the
// histogram's alignment) and
// return the Shannon entropy H = -sum p_k log2 p_k of that window histogram in
// bits. A tight cluster around c occupies few bins (low H); a window that must
// stretch into a tail to hold the same share occupies many (high H). For a
// skewed sample this orders H(mean) >= H(mode) > H(mean shift), as in the
// reference. Confidence maps H to 0..1: 1 - H / full_scale_bits, clamped
// (full_scale_bits = 6 bits: the window spread evenly over 64 bins = 6.4 deg).
#pragma once

#include <vector>

namespace nerv::snv {

// sorted: ascending, non-empty; fraction in (0, 1].
float windowEntropyBits(const std::vector<float>& sorted, float centre, float fraction,
                        float bin_deg);

// Shannon entropy [bits] of the whole sample binned at bin (bins centred on 0),
// e.g. the disparity residuals of every ground sample to the fitted road plane:
// SGBM noise alone fills a few bins; trap pixels (puddle mirrors, wrong
// matches) that pass the ground tests spread into many. Sorts `values`.
float sampleEntropyBits(std::vector<float>& values, float bin);

float entropyConfidence(float entropy_bits, float full_scale_bits);

}  // namespace nerv::snv
