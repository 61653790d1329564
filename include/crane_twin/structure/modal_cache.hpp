// A disk cache of lowestModes' results (docs/architecture.md "Mode cache"). The structure's
// modes depend only on K, M and the options: every run of the same crane (without P-delta,
// whose K_G follows the scene's load) asks ARPACK for the same 100 modes, 0.3 to 0.5 s of a
// run's start. The cache keeps them bit for bit: a run that reads them computes exactly what a
// run that solved for them computes.
//
// Key: two 64-bit FNV-1a hashes (different offset bases) over K's and M's sizes, sparsity
// pattern and values and the options, as the file's name; the file repeats the key and carries
// a hash of its contents, so a truncated, corrupted or foreign file is recomputed and replaced.
// A file is written under a temporary name and renamed into place, so runs in parallel never
// read half a file. At most kMaxModalCacheFiles files are kept (the oldest go first).
#pragma once

#include <optional>
#include <string>

#include "crane_twin/structure/modal_analysis.hpp"

namespace crane_twin {

/// Files the cache keeps (P-delta scenes add one per load and radius; ~3.2 MB for the T8036's
/// 100 modes).
constexpr int kMaxModalCacheFiles = 16;

/// The cache's folder: $CRANE_TWIN_CACHE_DIR where set (set and empty: no cache), else
/// $XDG_CACHE_HOME/crane_twin, else $HOME/.cache/crane_twin; none of these: no cache.
std::optional<std::string> modalCacheDirectory();

/// What cachedLowestModes did (for tests and diagnostics).
enum class ModalCacheOutcome { read, computed_and_written, computed_not_written, no_cache };

/// lowestModes(K, M, opt) through the cache in `directory` (nullopt: no cache). A folder that
/// cannot be created or written costs nothing but the cache: the modes are computed.
ModalBasis cachedLowestModes(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt,
                             const std::optional<std::string>& directory,
                             ModalCacheOutcome* outcome = nullptr);

/// The same in modalCacheDirectory().
ModalBasis cachedLowestModes(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt);

}  // namespace crane_twin
