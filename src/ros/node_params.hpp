// Private-parameter helpers of the nodes: a parameter that is present must have the right type
// and range (a silently ignored typo is worse than a refusal); errors name the parameter.
#pragma once

#include <ros/ros.h>

#include <cmath>
#include <sstream>
#include <string>

#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

template <typename T>
void optionalParam(const ros::NodeHandle& pnh, const std::string& name, T& value,
                   const char* type) {
  if (!pnh.hasParam(name)) return;
  if (!pnh.getParam(name, value)) {
    throw InputError("parameter '" + pnh.resolveName(name) + "' must be " + type);
  }
}

inline void requireFinite(const std::string& name, double v, double min, bool strict) {
  if (!std::isfinite(v) || v < min || (strict && v == min)) {
    std::ostringstream s;
    s << "parameter '~" << name << "' = " << v << " must be a finite number "
      << (strict ? "> " : ">= ") << min;
    throw InputError(s.str());
  }
}

}  // namespace crane_twin
