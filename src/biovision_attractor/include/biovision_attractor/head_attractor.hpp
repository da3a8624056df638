#pragma once

#include <string>
#include <vector>

#include "biovision_attractor/head_attractor_parameters.hpp"

namespace biovision_attractor
{
/// A salient thing seen this frame, as the head controller needs it.
struct SeenRegion
{
  double pan = 0.0;   ///< head-centred direction of its peak [rad, + = left]
  double tilt = 0.0;  ///< [rad, + = down]
  double peak = 0.0;  ///< saliency [0, 1]
  double area = 0.0;  ///< [px^2]
};

/// Attractor dynamics for the head's pan (thesis §4.7), read so that it does what the thesis describes
/// (see the package README for each reading):
///  rate = gain * ( sum_i alpha_a * d_i * w_i * exp(-d_i^2/eps_a)  -  sum_i alpha_r * d_i * s_i * exp(-d_i^2/eps_r) )
///  d_i = direction_i - pan, direction_i = where the section's strongest region was seen (its centre
///  when nothing was: beyond the thesis, which attracts to section centres, 20 deg apart);  w_i = softmax weight of the section's saliency (0 when not salient);
///  s_i = exp((Ar_max - Ar_i)/beta_r) - 1, the section's repulsion, growing while the head dwells there;
/// plus permanent repellers just outside +-90 deg (the walls). Behaviours change the forcelets:
/// explore (as above), track (only the tracked direction attracts; no repulsion), look_ahead (a periodic
/// attractor at 0 deg), hold (rate 0). The tilt follows the same attractor form, towards the selected
/// target's tilt (or default_tilt) -- the thesis' "future work" of 2-D control. The selected attractor gets a persistence bonus, which breaks
/// ties between equal targets and stops dithering between near-equal ones. Beyond the thesis, a target
/// the head fixates habituates (its attraction fades over habituation_time and recovers when it is not
/// fixated): with the thesis' spatial boredom alone, a head between two sections alternates boredom
/// between them and never leaves (measured on two targets at +-15 deg).
///
/// The forcelets, softmax weights and selection are those of forcelets.hpp (shared with the base's heading
/// controller). update() runs, in order: sanitise the inputs, remember saliency per section, inhibition of
/// return (boredom), the idle clock, habituation, the behaviour's attraction, softmax weights and selection,
/// the forcelet sum (rate), the pan command (with saccades), the tilt command.
class HeadAttractor
{
public:
  enum class Behaviour
  {
    kExplore,
    kTrack,
    kLookAhead,
    kHold
  };

  struct Output
  {
    double rate = 0.0;          ///< [rad/s] after limits
    double command = 0.0;       ///< pan position command [rad], inside the limits
    double tilt_rate = 0.0;     ///< [rad/s]
    double tilt_command = 0.0;  ///< tilt position command [rad], inside the tilt limits
    double tilt_target = 0.0;   ///< the tilt the dynamics head for [rad]
    double target = 0.0;        ///< angle the dynamics head for (the dominant attractor), NaN if none
    bool saccade = false;       ///< the command jumps straight to the target
    std::vector<double> attraction, repulsion, forcelet;  ///< per section
  };

  /// Throws std::invalid_argument (from HeadAttractorParameters::validate) on bad parameters.
  explicit HeadAttractor(const HeadAttractorParameters& parameters);

  /// One control step at time t [s] with the head at `pan` [rad, + = left] and `tilt` [rad, + = down];
  /// `regions` are this frame's (may be empty). dt: time since the previous step [s]; half_fov: half the
  /// camera's horizontal field of view [rad]. Never throws: a non-finite pan counts as 0, a non-finite
  /// tilt as default_tilt, a non-finite dt as 0; regions with a non-finite pan or peak are ignored.
  Output update(const std::vector<SeenRegion>& regions, double pan, double t, double dt, double half_fov,
                double tilt = 0.0);

  /// Forgets everything learnt over time -- remembered saliency, boredom (inhibition of return),
  /// habituation, the selected target, the idle clock -- as at construction; keeps the parameters and the
  /// behaviour. For a restart of time (a looped bag, a restarted simulator): the idle clock would otherwise
  /// wait for a time that never comes again.
  void reset();

  /// Replaces the parameters, keeping the state (a different sections or field resets it). Throws
  /// std::invalid_argument on bad parameters, leaving the previous ones in place.
  void setParameters(const HeadAttractorParameters& parameters);

  /// Switches the behaviour; `track_angle` [rad] is the direction kTrack follows. Throws
  /// std::invalid_argument, keeping the current behaviour, for kTrack with a NaN/Inf angle: a non-finite
  /// value never enters the state (it froze the attractor at rate 0, issue #23 item 8).
  void setBehaviour(Behaviour b, double track_angle = 0.0);
  Behaviour behaviour() const { return behaviour_; }
  static bool parseBehaviour(const std::string& name, Behaviour& out);
  static const char* name(Behaviour b);
  const HeadAttractorParameters& parameters() const { return p_; }
  std::vector<double> sectionAngles() const;

private:
  /// update()'s inputs made safe (see update()).
  struct StepInput
  {
    double pan, tilt, t, dt, half_fov;
  };
  /// This frame's strongest region per section: its peak (0 = none), direction and tilt.
  struct SeenPerSection
  {
    std::vector<double> peak, direction, tilt;
  };

  StepInput sanitise(double pan, double tilt, double t, double dt, double half_fov) const;
  SeenPerSection strongestPerSection(const std::vector<SeenRegion>& regions) const;
  void rememberSaliency(const SeenPerSection& seen, const StepInput& in);
  void inhibitReturn(double pan);
  void updateIdleClock(double t);
  void habituate(const StepInput& in);
  std::vector<double> behaviourAttraction(double t);
  /// Where section i's inhibition-of-return repeller sits [rad]: its centre, or the pan limit it holds.
  double repellerAngle(int i) const;
  double panRate(double pan, const std::vector<double>& weights, Output& out) const;
  void commandPan(const StepInput& in, Output& out) const;
  void commandTilt(const StepInput& in, Output& out) const;

  HeadAttractorParameters p_;
  Behaviour behaviour_ = Behaviour::kExplore;
  double track_angle_ = 0.0;
  std::vector<double> saliency_;     // A_s (remembered for out-of-view sections)
  std::vector<double> direction_;    // where in each section its strongest region was seen [rad]
  std::vector<double> tilt_;         // and at which tilt [rad]
  std::vector<double> repulsion_;    // A_r in [0, 1]; 1 = no repulsion
  double last_salient_time_;         // [s] kNever until the first update
  int selected_;                     // the attractor the head is going to (kept while it stays competitive), -1 = none
  std::vector<double> habituation_;  // per section, 0..0.9: how much a fixated target has lost its pull
};
}  // namespace biovision_attractor
