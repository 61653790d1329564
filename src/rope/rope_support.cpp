#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

void RopeSupport::setPoseStep(double theta0, double radius0, double theta1, double radius1) {
  theta0_ = theta0;
  radius0_ = radius0;
  theta1_ = theta1;
  radius1_ = radius1;
  fraction_ = 1.0;  // (the caller set the end pose)
  pose_moves_ = theta0 != theta1 || radius0 != radius1;
}

void RopeSupport::setStepFraction(double f) {
  if (!pose_moves_ || f == fraction_) return;
  fraction_ = f;
  if (f == 1.0) return setPose(theta1_, radius1_);  // (the end pose exactly, not to round-off)
  setPose(theta0_ + f * (theta1_ - theta0_), radius0_ + f * (radius1_ - radius0_));
}

}  // namespace crane_twin
