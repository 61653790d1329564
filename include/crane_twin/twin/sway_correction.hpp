// The estimator's correction carried into a running simulation (docs/twin.md): the structure's
// modal coordinates and rates by d_eta, d_eta' (the trolley point moves by D d_eta, the whole
// rope translated with it so it stays attached), then the rope turned rigidly about its top
// node so that its end moves by dp relative to the trolley, with the rigid rotation rate that
// adds dv to the end's velocity relative to the top. ANCF coordinates (positions r_j and slopes
// r'_j per node): with rho = r_end - r_top, theta = rho x dp / |rho|^2, R = exp(theta),
//   r_j -> r_top + R (r_j - r_top),   r'_j -> R r'_j,
//   v_j -> v_top + R (v_j - v_top) + w x R (r_j - r_top),   v'_j -> R v'_j + w x R r'_j,
// w = R rho x u / |rho|^2 with u = dv - (R - I)(v_end - v_top). Components of dp and dv along
// the rope (stretching it) are not applied.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/twin/sway_estimator.hpp"

namespace crane_twin {

/// The rope's full coordinates (q, v) turned rigidly about the top (q's first 3) so that the
/// end (the last position block) moves by dp's part across the chord and gains dv's. q is read
/// as 3-vectors: `position_blocks[b]` says block b is a point (turned about the top), otherwise
/// a direction (a slope, turned); empty: ANCF's 6 per node, point then slope
/// (Simulation::fullStatePositionBlocks gives any model's). Throws std::invalid_argument for
/// sizes that do not fit or an end at the top.
void rotateRopeAboutTop(Eigen::VectorXd& q, Eigen::VectorXd& v, const Eigen::Vector3d& dp,
                        const Eigen::Vector3d& dv, std::vector<bool> position_blocks = {});

/// The whole update: modal coordinates `modes` (indices into the support's z) by the update's
/// structure corrections (none for an empty list), then the swing. Throws what
/// Simulation::setMotion throws.
void applyTwinCorrection(Simulation& sim, const SwayUpdate& update, const std::vector<int>& modes);

/// Structure modes a payload measurement can see: those of a modal structure under max_hz that
/// move the trolley point more sideways than up or down, by at least 5 % of the largest sideways
/// motion (at the current pose); at most max_modes, lowest first. Empty for a rigid or full
/// structure or no crane.
std::vector<int> swayCouplingModes(const Simulation& sim, double max_hz = 1.0, int max_modes = 6);

/// The estimator's linearised model at the simulation's current pose for those modes; `row` is
/// the simulation's current output row (series()), which the caller usually has already.
SwayModel swayModelAt(const Simulation& sim, const SeriesValues& row, const std::vector<int>& modes,
                      double gravity);

/// |Phi_k| of those modes at the current pose [m per unit modal coordinate].
Eigen::VectorXd modeMotionNorms(const Simulation& sim, const std::vector<int>& modes);

}  // namespace crane_twin
