// Two-node 3D Timoshenko (shear) beam element, 6 DOF per node (docs/model.md).
//
// Node DOF order [u_x, u_y, u_z, th_x, th_y, th_z] in the global frame (m, rad).
// Local axes: x1 along node1 -> node2, y1 in the plane of x1 and the orientation vector v,
// z1 = x1 x y1. Linear small-deformation theory.
// Bending in each principal plane uses the interdependent interpolation (IIE) of
// Friedman & Kosmatka (Comput. Struct. 47, 1993): cubic deflection and quadratic rotation tied
// by the shear parameter Phi = 12 EI / (G A_s L^2). The stiffness and the consistent mass
// (translational and rotary inertia) are integrated from those shape functions:
//   K = int [EI psi'^2 + G A_s (v' - psi)^2] dx,   M = int [rho A v^2 + rho I psi^2] dx,
// so the element reproduces the exact cantilever tip deflection P L^3/3EI + P L/(G A_s).
// Axial and torsion use linear shape functions (EA, GJ; rho A, rho (Iy + Iz)).
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Cross-section and material. Units: Pa, m^2, m^4, kg/m^3.
struct BeamSection {
  double E = 2.06e11;         ///< Young's modulus
  double G = 7.9e10;          ///< shear modulus
  double density = 7850.0;    ///< rho
  double area = 0.0;          ///< A
  double shear_area_y = 0.0;  ///< A_sy (shear along local y); 0 = rigid in shear (Euler-Bernoulli)
  double shear_area_z = 0.0;  ///< A_sz
  double Iy = 0.0;            ///< second moment about local y (bending in the x-z plane)
  double Iz = 0.0;            ///< second moment about local z (bending in the x-y plane)
  double J = 0.0;             ///< torsion constant
  double outer_diameter = 0.0;  ///< tube's D [m], the width the wind sees (0: no wind area)

  /// Thin-walled circular tube of outer diameter D and wall t (A_s = A/2, J = 2I).
  static BeamSection circularTube(double D, double t, double E, double G, double density);
  /// Solid rectangle b (local y) x h (local z), shear factor 5/6, Saint-Venant J approximation.
  static BeamSection rectangle(double b, double h, double E, double G, double density);
};

/// Element matrices in the global frame (12 x 12).
struct BeamElementMatrices {
  Eigen::Matrix<double, 12, 12> K;
  Eigen::Matrix<double, 12, 12> M;
};

/// Rotation matrix R whose rows are the local axes (x1, y1, z1) in global coordinates.
/// Throws std::invalid_argument when the nodes coincide or v is parallel to the axis.
Eigen::Matrix3d beamLocalAxes(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& orientation);

/// Local-frame stiffness and consistent mass of a Timoshenko beam of length L.
BeamElementMatrices timoshenkoBeamLocal(const BeamSection& s, double L);

/// Global-frame stiffness and consistent mass: T^T K_local T with T = blockdiag(R, R, R, R).
BeamElementMatrices timoshenkoBeamGlobal(const BeamSection& s, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2,
                                         const Eigen::Vector3d& orientation);

}  // namespace crane_twin
