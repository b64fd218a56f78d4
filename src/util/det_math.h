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
