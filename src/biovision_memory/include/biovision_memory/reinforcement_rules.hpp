#pragma once

namespace biovision_memory
{
/// The strength arithmetic of thesis §5.3.2, shared by the long-term map and the object memory. Strengths
/// are integers in the thesis's units (0 … M_R).
///  (a) seen again at the same place: +P_R, capped at M_R;
///  (b) expected but not seen (in view and range, see LongTermMemory): N_R;
///  (c) every t_LTM without a change, an item below M_R is weakened by N_R; an item at M_R is fixed
///      (exempt from (c));
///  an item at ≤ 0 is removed.
/// The thesis prints "M_R = 200, P_R = 40, M_R = 200, N_R = −40": the second M_R is a typo. A new item
/// starts at `initial_strength` = P_R = 40 (chosen: one sighting is worth one reinforcement, so a
/// one-frame phantom dies at the first look that misses it, or after one t_LTM out of view, while a
/// thing seen 5 times is fixed). (b) also applies to fixed items: a moved table must leave the map.
struct ReinforcementRules
{
  int initial_strength = 40;     ///< strength of a new item, [1, max_strength] (the thesis's gap; = P_R)
  int reinforcement = 40;        ///< P_R, [1, max_strength]
  int max_strength = 200;        ///< M_R, [1, 100000]; an item at M_R is fixed
  int penalty = -40;             ///< N_R (negative), [−max_strength, −1]
  double forget_period = 300.0;  ///< t_LTM [s], (0, 1e6]

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;

  int reinforce(int strength) const
  {
    return strength + reinforcement > max_strength ? max_strength : strength + reinforcement;
  }
  int weaken(int strength) const { return strength + penalty; }
  bool fixed(int strength) const { return strength >= max_strength; }
  /// Rule (c) from `last_change` to `now` [s]: the strength after the whole periods that passed, and
  /// `last_change` advanced by those periods (so the remainder keeps counting). Fixed items are unchanged.
  int decay(int strength, double& last_change, double now) const;
};
}  // namespace biovision_memory
