#pragma once

#include <string>
#include <utility>
#include <vector>

namespace biovision_monitor
{
/// How a controller's forcelets are drawn from its AttractorState (thesis Figs. 4.7 and 5.6). The message
/// carries per-section strengths, not the controller's constants: the plot rebuilds each section's curve
/// with these (defaults = the controllers' defaults) and multiplies the sum by `gain` to get rad/s.
struct AttractorModel
{
  double alpha_attraction;    ///< alpha_a (head: local attractors; base: the sine goal attractor)
  double epsilon_attraction;  ///< [rad^2] width of a local attractor (unused by the base's sine attractor)
  double alpha_repulsion;     ///< alpha_r
  double epsilon_repulsion;   ///< [rad^2] width of a repeller
  double gain;                ///< forcelet sum (thesis units) -> rad/s
  bool sine_goal;             ///< true: one global attractor -alpha_a sin(phi - target) (base, §5.4)
};

/// Parameters of the monitor's plots and panel (ROS parameters of the plot nodelets and monitor_panel,
/// config/monitor.yaml, cfg/Monitor.cfg). Defaults chosen as stated per field.
struct MonitorParameters
{
  double rate = 5.0;                 ///< [Hz] panel composition rate; the plot nodelets render at most this often
  int columns = 4;                   ///< panel tiles per row: 4 -> the thesis's eight panels as 4 x 2 (Fig. 5.1)
  int tile_width = 320;              ///< [px] one panel tile = one plot image (the simulator's 320 x 240)
  int tile_height = 240;             ///< [px]
  double stale_after = 5.0;          ///< [s] a tile whose last message is older is marked "stale"
  double saliency_threshold = 0.15;  ///< fraction of the map's maximum kept as salient (thesis L912, L1222: 15%)
  // Head pan (thesis §4.7): HeadAttractorParameters' defaults.
  double head_alpha_attraction = 50.0;
  double head_epsilon_attraction = 10.0;  ///< [rad^2]
  double head_alpha_repulsion = 50.0;
  double head_epsilon_repulsion = 15.0;  ///< [rad^2]
  double head_gain = 0.02;
  // Base heading (thesis §5.4, L1302): alpha_a = 1, alpha_r = 25, eps_r = 0.34 rad^2, gain 1 (L1310).
  double base_alpha_attraction = 1.0;
  double base_alpha_repulsion = 25.0;
  double base_epsilon_repulsion = 0.34;  ///< [rad^2]
  double base_gain = 1.0;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
  /// The head's or the base's model ("base" -> base, anything else -> head).
  AttractorModel model(const std::string& controller) const;
  /// Every double field by its ROS parameter name; and the int ones.
  static const std::vector<std::pair<std::string, double MonitorParameters::*>>& namedDoubles();
  static const std::vector<std::pair<std::string, int MonitorParameters::*>>& namedInts();
};
}  // namespace biovision_monitor
