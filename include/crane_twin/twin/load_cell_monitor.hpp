// LoadCellMonitor: the picks and set-downs a twin sees through the crane's load cell, and the
// mass of the load it lifts (docs/twin.md "Picks and set-downs"). ROS-free; TwinRuntime feeds
// it one sample per measured top tension.
//
// The end load a top tension T implies is E = T - (mu L + m_h) g: mu L the hanging rope's
// mass, m_h a hook block on a rigging (the masses that never land). While the load hangs, E is
// about the weight of what lands (the model's end mass m_e, payload and hook block, or the
// payload alone on a rigging); while it rests on the ground, about 0.
//
// - Lift-off: E above lift_fraction m_e g (the twin's m_e) for lift_confirm seconds, with the
//   hoist reeled in by more than lift_hoisting since the load landed (its longest length since);
//   its time is the first sample above. Only the hoist lifts a load: after a set-down the jib
//   springs back and rings (0.1 to 0.8 Hz), and its pull on the landed load's rope can exceed
//   half the load's weight for more than half a second while the hoist pays out.
//   Set-down: E below set_down_fraction m_e g for set_down_confirm seconds, or at once while
//   the hoist pays out (a lowered load's rope slackens only when it lands, and the jib springing
//   back can pull it up again within the confirmation). The first sample decides between the
//   two by the lift threshold.
// - Mass: from `settle` seconds after a lift-off, over windows of `window` seconds in which the
//   load hangs in the measurement and in the twin,
//       m_e,measured = m_e,twin * sum w E_measured / sum w E_twin,
//   both taken at the same twin times, w = sin^2(pi (t - t_0) / window) (Hann): the twin
//   follows the crane's joints, so the hoist's accelerations, slewing and sway scale both alike
//   and cancel in the ratio. What rings after the lift-off, at different frequencies and
//   phases in crane and twin (they carry different loads), is suppressed by the weights to
//   (pi f T)^-1 / ((f T)^2 - 1) of its amplitude (unweighted: (pi f T)^-1): the rope's axial
//   ringing (about 1 Hz: 0.06 % over T = 8 s) and the jib's bounce (0.5 Hz: 0.5 %; over 5 s it
//   was 2.4 %, and the rostest read up to +3 %). The first estimate comes 8.5 s after the
//   first sample above the lift threshold, before the load has hung for 10 s. A window
//   whose estimate differs from the twin's m_e by more than change_threshold offers it to the twin
//   (takeEndMass); the next window then checks the twin with its new mass.
#pragma once

#include <limits>
#include <optional>

namespace crane_twin {

struct LoadCellSettings {
  double lift_fraction = 0.5;       ///< of the twin's end weight [-]
  double set_down_fraction = 0.25;  ///< of the twin's end weight [-]
  double lift_confirm = 0.5;        ///< [s]
  double lift_hoisting = 0.01;      ///< reeled in since the set-down before a lift-off [m]
  double set_down_confirm = 0.2;    ///< [s]
  double settle = 0.5;              ///< after a lift-off, before the first window [s]
  double window = 8.0;              ///< [s]
  double change_threshold = 0.01;   ///< relative [-]
  /// Throws std::invalid_argument naming the setting: fractions in (0, 1) with
  /// set_down_fraction < lift_fraction, times >= 0 (window > 0), change_threshold >= 0.
  void check() const;
};

/// One measured tension with the twin's state at the same twin time.
struct LoadCellSample {
  double t = 0.0;             ///< twin time [s]
  double measured = 0.0;      ///< measured top tension [N]
  double twin = 0.0;          ///< the twin's top tension [N]
  double unloaded = 0.0;      ///< (mu L + m_h) g: what the rope carries with the load landed [N]
  double end_mass = 0.0;      ///< the twin's end mass m_e [kg] (> 0)
  double gravity = 9.81;      ///< [m/s^2]
  bool twin_landed = false;   ///< the twin's own payload rests on its ground
  double hoist_length = 0.0;  ///< the twin's hoist rope length (following the crane's) [m]
};

class LoadCellMonitor {
 public:
  /// Throws what LoadCellSettings::check throws.
  explicit LoadCellMonitor(const LoadCellSettings& settings = LoadCellSettings());

  /// Samples in increasing time. Throws std::invalid_argument for a non-finite value or an end
  /// mass <= 0.
  void add(const LoadCellSample& s);

  bool started() const { return started_; }
  /// The load rests on the ground, as the load cell sees it.
  bool landed() const { return landed_; }
  /// Lift-offs and set-downs seen so far.
  int lifts() const { return lifts_; }
  int setDowns() const { return set_downs_; }
  /// Twin time of the last lift-off / set-down seen (NaN: none yet) [s].
  double lastLiftOff() const { return last_lift_off_; }
  double lastSetDown() const { return last_set_down_; }
  /// The last window's end mass (NaN: none yet) [kg].
  double endMassEstimate() const { return estimate_; }
  /// An end mass for the twin [kg], once per window that found one more than change_threshold
  /// from the twin's; empty otherwise.
  std::optional<double> takeEndMass();

 private:
  void startWindow(double t);
  LoadCellSettings settings_;
  bool started_ = false, landed_ = false;
  double switch_since_ = std::numeric_limits<double>::quiet_NaN();  ///< crossing pending since
  int lifts_ = 0, set_downs_ = 0;
  double last_lift_off_ = std::numeric_limits<double>::quiet_NaN();
  double last_set_down_ = std::numeric_limits<double>::quiet_NaN();
  double longest_hoist_ = -std::numeric_limits<double>::infinity();  ///< since landed
  double last_hoist_ = std::numeric_limits<double>::quiet_NaN();     ///< previous sample's
  double windows_from_ = std::numeric_limits<double>::infinity();    ///< no window before this
  double window_start_ = std::numeric_limits<double>::quiet_NaN();   ///< NaN: none open
  double window_mass_ = 0.0, sum_measured_ = 0.0, sum_twin_ = 0.0;
  double estimate_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<double> offered_;
};

}  // namespace crane_twin
