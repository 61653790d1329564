// Geometric (initial-stress) stiffness of a beam carrying an axial force N [N], positive in
// tension (docs/model.md "Geometric stiffness"): the second variation of N/2 int (v'^2 + w'^2) dx
// with the cubic Hermite lateral shapes (Przemieniecki, Theory of Matrix Structural Analysis,
// 1968, ch. 15), per bending plane (v, psi) with psi = v' (DOF order as timoshenkoBeamLocal):
//   K_G = N / (30 L) [[36, 3L, -36, 3L], [3L, 4L^2, -3L, -L^2], [-36, -3L, 36, -3L],
//                     [3L, -L^2, -3L, 4L^2]],
// and the torsional term N I_p / (A L) [[1, -1], [-1, 1]] (I_p = I_y + I_z). Compression (N < 0)
// softens: a cantilever column buckles at P = pi^2 EI / (4 L^2).
#pragma once

#include <Eigen/Dense>

#include "crane_twin/elements/timoshenko_beam_element.hpp"

namespace crane_twin {

using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// Local-frame K_G of a beam of length L > 0 with axial force N.
Matrix12d beamGeometricStiffnessLocal(const BeamSection& s, double L, double N);

/// Global-frame K_G = T^T K_G,local T (T of timoshenkoBeamGlobal).
Matrix12d beamGeometricStiffnessGlobal(const BeamSection& s, const Eigen::Vector3d& p1,
                                       const Eigen::Vector3d& p2,
                                       const Eigen::Vector3d& orientation, double N);

/// Axial force N = EA / L (R (u2 - u1))_x [N] of a beam from its end translations u1, u2
/// (global frame) [m].
double beamAxialForce(const BeamSection& s, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& u1, const Eigen::Vector3d& u2);

}  // namespace crane_twin
