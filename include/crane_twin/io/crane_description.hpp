// Crane description (config/cranes/*.yaml): geometry, member sections, lumped masses, drive
// limits and default rope data of a flat-top tower crane. Units SI. Every value is validated
// when read (see config_reader.hpp); defaults are not taken for anything physical: the file
// must state it.
#pragma once

#include <string>
#include <vector>

#include "crane_twin/elements/timoshenko_beam_element.hpp"

namespace crane_twin {

class ConfigNode;

/// A lattice member group: circular tube D x t [m].
struct TubeSpec {
  double outer_diameter = 0.0;
  double wall = 0.0;
};

/// Triangular lattice boom (jib or counter-jib): two bottom chords, one top chord.
struct LatticeBoomSpec {
  double length = 0.0;     ///< from the slewing-unit face to the tip [m]
  double width = 0.0;      ///< distance between the bottom chords [m]
  double height = 0.0;     ///< top chord above the bottom chords [m]
  double panel = 0.0;      ///< station spacing [m]
  int chord_segments = 1;  ///< beam elements per chord between two stations
  TubeSpec top_chord, bottom_chord, diagonal, horizontal;
};

/// A point mass attached to the structure [kg], at a position in the slewing frame [m]; it is
/// shared equally by the listed structure nodes nearest to that position (count nodes).
struct LumpedMassSpec {
  std::string name;
  double mass = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int nodes = 1;
};

/// Speed and acceleration limits of one drive.
struct DriveLimits {
  double max_speed = 0.0;
  double max_acceleration = 0.0;
};

/// Default wire rope data per fall (docs/model.md).
struct RopeSpec {
  double mass_per_length = 1.9;
  double axial_stiffness = 2.2e7;
  double bending_stiffness = 78.5;
  double breaking_force = 345e3;
  int falls = 2;
};

/// A fatigue hot spot (docs/fatigue.md): the member whose end node is nearest `point` among
/// those along `along`, at that end's section, the tube's outer fibre toward `fibre` (projected
/// on the section), an EN 13001-3-1 detail category.
struct HotSpotSpec {
  std::string name;                                  ///< the CSV column is stress_<name>
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< slewing frame [m]
  Eigen::Vector3d along = Eigen::Vector3d::UnitZ();  ///< the member's axis (either sense)
  Eigen::Vector3d fibre = Eigen::Vector3d::UnitX();  ///< toward the fibre (slewing frame)
  double detail_category = 0.0;                      ///< ds_c [MPa]
};

struct CraneDescription {
  std::string name;
  std::string file;
  double E = 0.0, G = 0.0, density = 0.0;
  // Mast: square lattice, K (chevron) bracing on each face, base nodes clamped.
  double mast_height = 0.0, mast_width = 0.0, mast_panel = 0.0;
  TubeSpec mast_chord, mast_diagonal, mast_horizontal;
  // Slewing unit: a stiff box between the mast top and the jib root.
  double slewing_height = 0.0;
  TubeSpec slewing_member;
  LatticeBoomSpec jib, counter_jib;
  Eigen::Vector3d cab_position = Eigen::Vector3d::Zero();  ///< slewing frame [m]
  std::vector<LumpedMassSpec> lumped_masses;
  std::vector<HotSpotSpec> hot_spots;  ///< `hot_spots:` (none: no stress output)
  /// `design_hours:` the hours of use the steel is designed for [h] (0: not given), against
  /// which a usage count projects its hot spots' lives (docs/fatigue.md "Usage").
  double design_hours = 0.0;
  double trolley_mass = 0.0, hook_block_mass = 0.0;
  double min_radius = 0.0, max_radius = 0.0;
  double min_rope_length = 0.0, max_rope_length = 0.0;
  double max_load = 0.0, rated_moment = 0.0, load_at_max_radius = 0.0;
  DriveLimits slewing, trolley, hoist;
  RopeSpec rope;

  /// Height of the jib's bottom chords (the trolley rail) above the base [m].
  double jibRailHeight() const { return mast_height + slewing_height; }
};

/// Allowed payload [kg] at radius r [m] (the load chart, docs/model.md data): max_load out to the
/// radius where max_load reaches the rated moment, then a load moment falling linearly in r
/// from rated_moment there to load_at_max_radius x max_radius at the jib tip. (An assumption
/// shaped like published T8036 charts; the paper gives only the three figures.)
double allowedLoad(const CraneDescription& c, double radius);

/// Read and validate a crane description file. Throws InputError naming file and key.
CraneDescription loadCraneDescription(const std::string& path);

/// Section of a tube member from the crane's material.
BeamSection tubeSection(const CraneDescription& c, const TubeSpec& t);

}  // namespace crane_twin
