#pragma once
// A select without a branch, for a choice on data that a branch predictor cannot
// learn. GCC turns `c ? a : b` on doubles into a branch on x86-64 (SSE2 has no
// conditional move); that is right when the predictor is (the CPU then runs ahead on
// the predicted side) and costs a pipeline flush each time it is not.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tetrapulse {

// pick ? a : b.
inline double select_if(bool pick, double a, double b) {
#if defined(__SSE2__)
  const __m128d mask = _mm_castsi128_pd(_mm_set1_epi64x(-static_cast<long long>(pick)));
  return _mm_cvtsd_f64(_mm_or_pd(_mm_and_pd(mask, _mm_set_sd(a)), _mm_andnot_pd(mask, _mm_set_sd(b))));
#else
  return pick ? a : b;
#endif
}

}  // namespace tetrapulse
