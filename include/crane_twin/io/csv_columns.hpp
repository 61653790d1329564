// Numeric columns of a CSV file with a header row (the docs/cli.md time series, the nodes file):
// the analyses (crane_sim compare, crane_sim rainflow) read their inputs through it.
#pragma once

#include <string>
#include <vector>

namespace crane_twin {

/// Rows of `file` as numbers, each row holding the `wanted` columns in that order. Throws
/// InputError naming the file and, as the case may be, the missing column (with the header's
/// columns), the line whose field count differs from the header's, or the line and column of a
/// field that is not a finite number; an empty file or one without data rows too.
std::vector<std::vector<double>> readCsvColumns(const std::string& file,
                                                const std::vector<std::string>& wanted);

}  // namespace crane_twin
