// Two Neumaier sums (util/neumaier_sum.h) run side by side: lane 0 and lane 1 each get exactly the
// operations a NeumaierSum would do on its own terms, in the same order, so value(0) and value(1)
// are bit for bit those of two NeumaierSums. On SSE2 both lanes share one instruction per step
// and the branch on |sum| >= |term| becomes a mask (an evaluation of the offset solve adds four
// or ten sums per face, and which branch is taken depends on the data).
#pragma once
#if defined(__SSE2__)
#include <emmintrin.h>
#else
#include "util/neumaier_sum.h"
#endif

namespace offsetopt {

class NeumaierPair {
 public:
#if defined(__SSE2__)
  void add(double term0, double term1) { add(_mm_set_pd(term1, term0)); }
  // Lane 0 of `terms` goes to sum 0, lane 1 to sum 1.
  void add(__m128d terms) {
    const __m128d t = _mm_add_pd(sum_, terms);
    const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
    // Scalar: |sum| >= |term| (false for NaN, as the comparison in NeumaierSum).
    const __m128d sum_larger = _mm_cmpge_pd(_mm_and_pd(sum_, magnitude), _mm_and_pd(terms, magnitude));
    const __m128d from_sum = _mm_add_pd(_mm_sub_pd(sum_, t), terms);
    const __m128d from_term = _mm_add_pd(_mm_sub_pd(terms, t), sum_);
    compensation_ = _mm_add_pd(compensation_,
                               _mm_or_pd(_mm_and_pd(sum_larger, from_sum), _mm_andnot_pd(sum_larger, from_term)));
    sum_ = t;
  }
  double value(int lane) const {
    const __m128d v = _mm_add_pd(sum_, compensation_);
    return lane == 0 ? _mm_cvtsd_f64(v) : _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
  }

 private:
  __m128d sum_ = _mm_setzero_pd();
  __m128d compensation_ = _mm_setzero_pd();
#else
  void add(double term0, double term1) {
    sums_[0].add(term0);
    sums_[1].add(term1);
  }
  double value(int lane) const { return sums_[lane].value(); }

 private:
  NeumaierSum sums_[2];
#endif
};

}  // namespace offsetopt
