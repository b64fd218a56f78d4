// src/util (no header is central, so this one, the heart of the determinism rules, opens the
// folder): the small deterministic building blocks every other folder uses: elementary functions
// from +, -, *, / and sqrt (this header), exact expansions, deterministic Eigen kernels,
// compensated sums, dual numbers, the SplitMix64 RNG, shortest round-trip number text, byte
// quoting, the fixed-partition worker pool (parallel.h) and stage timing (seconds_since.h). It is
// the bottom layer: it includes only the standard library, Eigen and itself.
//
// Deterministic elementary functions. glibc picks sin/cos/atan implementations at run time by
// CPU features (FMA or not), so libm results may differ in the last bit between x86-64 machines;
// anything that reaches an output file uses these instead: only +, -, *, / and sqrt (all
// correctly rounded by IEEE 754), evaluated in a fixed order with -ffp-contract=off.
// Accuracy is a few ulp, far below every tolerance the project uses.
#pragma once

namespace offsetopt {

constexpr double kPi = 3.141592653589793238462643383279502884;

double det_sin(double x);
double det_cos(double x);
void det_sincos(double x, double& s, double& c);
double det_atan(double x);
double det_atan2(double y, double x);
double det_acos(double x);  // x clamped to [-1, 1]
double det_asin(double x);  // x clamped to [-1, 1]

}  // namespace offsetopt
