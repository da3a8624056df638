#pragma once

#include <vector>

/// The forcelets of attractor dynamics (thesis §4.7 for the head's pan, §5.4 for the base's heading), as
/// free functions of the standard library only, shared by HeadAttractor and the base heading controller.
///
/// Conventions for every function here:
///  - angles in rad, REP-103: + = left (counter-clockwise seen from above); phi is the controlled angle
///    (the head's pan, the base's heading), psi where the forcelet sits;
///  - a forcelet is a contribution to dphi/dt in the thesis' units: multiply the sum by the controller's
///    gain to get rad/s (the head: HeadAttractorParameters::gain);
///  - positive output turns left (increases phi);
///  - widths are given as epsilon = 2 sigma^2 [rad^2]: the window is exp(-(phi - psi)^2 / epsilon), as the
///    thesis prints it;
///  - nothing throws: non-finite inputs give non-finite outputs, which the controllers drop.
///
/// A base heading controller (§5.4) over the 9 sectors of short-term memory reads:
///   dphi/dt = gain * ( sineAttraction(phi, psi_goal, alpha_a)
///                      + sum_i repulsion(phi, sectorCentre(i, 9, M_PI), alpha_r, strength_i, epsilon_r) )
/// with strength_i from the sector's obstacle (e.g. repulsionStrength of its nearness), and walls() if the
/// heading has limits. See the package README.
namespace biovision_attractor
{
/// Windowed linear attraction towards psi (the head's reading of §4.7, see the package README):
///   f = alpha * (psi - phi) * weight * exp(-(psi - phi)^2 / epsilon).
/// Zero at phi = psi with negative slope there (a stable fixed point: phi is pulled onto psi from either
/// side), odd about psi, local (vanishes far from psi). |f| <= alpha * |weight| * sqrt(epsilon / 2) * e^(-1/2),
/// reached at |psi - phi| = sqrt(epsilon / 2).
/// alpha: strength (thesis alpha_a, >= 0); weight: the attractor's share (softmax weight, 0..1);
/// epsilon [rad^2] > 0.
double attraction(double phi, double psi, double alpha, double weight, double epsilon);

/// Global attraction towards a goal direction (§5.4, Bicho et al. 1998): f = -alpha * sin(phi - psi).
/// Stable fixed point at phi = psi, unstable one at psi + pi; |f| <= alpha. alpha >= 0.
double sineAttraction(double phi, double psi, double alpha);

/// Repulsion away from psi (§4.7 and §5.4):
///   f = alpha * strength * (phi - psi) * exp(-(phi - psi)^2 / epsilon).
/// Zero at phi = psi with positive slope (an unstable fixed point: phi is pushed off psi towards the side
/// it is already on), odd about psi, local. |f| <= alpha * strength * sqrt(epsilon / 2) * e^(-1/2).
/// alpha >= 0; strength >= 0 (0 = no repulsion); epsilon [rad^2] > 0.
double repulsion(double phi, double psi, double alpha, double strength, double epsilon);

/// Strength of a repeller from its repulsion level A_r (§4.7; 1 = minimum repulsion):
///   s = exp((1 - level) / beta) - 1,
/// 0 at level 1, growing as the level falls; the maximum, at level 0, is exp(1 / beta) - 1. beta > 0.
double repulsionStrength(double level, double beta);

/// Walls: two repellers of the maximum strength (level 0) at `lower` and `upper` [rad], placed just
/// outside the controlled range so that they turn phi back before it reaches the range's ends:
///   f = repulsion(phi, lower, alpha, s_max, epsilon) + repulsion(phi, upper, alpha, s_max, epsilon).
/// Narrow epsilon (the head: 0.02 rad^2): broad walls cancel attractors in mid-field.
double walls(double phi, double lower, double upper, double alpha, double beta, double epsilon);

/// Softmax weights of attraction strengths (§4.7's exp(A_s / beta_a), normalised): entries below
/// `threshold` get 0; the others exp((a_i - max) / beta) / sum, so the strongest dominates as beta -> 0.
/// All zeros when no entry reaches the threshold. beta > 0.
std::vector<double> softmaxWeights(const std::vector<double>& strengths, double threshold, double beta);

/// Index of the largest positive weight (the first of equals), -1 when none is positive.
int dominantIndex(const std::vector<double>& weights);

/// Target selection with persistence (beyond the thesis; see the package README): keeps `selected` while
/// its weight is positive and no rival's weight exceeds it times (1 + bonus), else takes the dominant one;
/// then multiplies the selected weight by (1 + bonus) in `weights`. Breaks ties between equal targets and
/// stops dithering between near-equal ones. Returns the selected index, -1 when no weight is positive.
/// `selected` may be -1 or out of range (= none). bonus >= 0.
int selectWithPersistence(std::vector<double>& weights, int selected, double bonus);

/// Centre [rad] of sector i of n splitting `field` [rad] symmetrically about 0, from the right:
/// -field/2 + field/n * (i + 1/2). The thesis' 9 sectors of 180 deg: -80, -60, ..., +80 deg.
double sectorCentre(int i, int n, double field);

/// The sector of n (see sectorCentre) that contains `angle` [rad]; angles beyond the field belong to the
/// end sectors. n >= 1.
int sectorOf(double angle, int n, double field);
}  // namespace biovision_attractor
