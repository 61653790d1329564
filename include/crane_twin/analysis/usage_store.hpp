// A usage count kept in a file (docs/fatigue.md "Lifetime counts"): what a node has counted of
// its crane's lifts and hot-spot damage, so that its count outlives a restart. YAML, written
// whole to a temporary file and renamed over the old one (a crash mid-write keeps the old one).
#pragma once

#include <string>

#include "crane_twin/analysis/usage_counter.hpp"

namespace crane_twin {

/// Write `state` to `path`. Throws InputError naming the file when it cannot be written.
void saveUsageState(const UsageState& state, const std::string& path);

/// The state saved in `path`. Throws InputError naming the file and key on a missing or
/// malformed file (a negative count, a non-finite number, an unknown key).
UsageState loadUsageState(const std::string& path);

}  // namespace crane_twin
