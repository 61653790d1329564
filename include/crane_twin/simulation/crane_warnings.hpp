// The physical warnings of an output row (docs/cli.md, the warnings column): what the rope's
// tension and the drives' state say about the crane's limits.
#pragma once

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

/// The physical warnings of an output row from its rope_top_tension and the drives:
/// tension_ratio = tension / breaking force of all falls, load_chart_ratio = payload / allowed
/// load at the current radius, and the warning bits (over breaking force, outside the load
/// chart, rope length or radius at a limit, a command limited).
void setCraneWarnings(const CraneModel& model, const CraneDrives& drives, SeriesValues& v);

/// The tension warning bits (over the breaking force, over the working load limit) for the
/// largest top tension of the steps since the previous row, peak_tension [N]
/// (StepTensionPeak): a snatch's crest between two rows warns at the next row. The row's
/// tension_ratio stays its own.
void addStepPeakTensionWarnings(const CraneModel& model, double peak_tension, SeriesValues& v);

}  // namespace crane_twin
