#include "biovision_attractor/forcelets.hpp"

#include <algorithm>
#include <cmath>

namespace biovision_attractor
{
// The products keep the operation order of the original HeadAttractor::update, so extracting them did not
// change a bit of its results.

double attraction(double phi, double psi, double alpha, double weight, double epsilon)
{
  const double d = psi - phi;
  return alpha * d * weight * std::exp(-d * d / epsilon);
}

double sineAttraction(double phi, double psi, double alpha)
{
  return -alpha * std::sin(phi - psi);
}

double repulsion(double phi, double psi, double alpha, double strength, double epsilon)
{
  const double d = phi - psi;
  return alpha * d * strength * std::exp(-d * d / epsilon);
}

double repulsionStrength(double level, double beta)
{
  return std::exp((1.0 - level) / beta) - 1.0;
}

double walls(double phi, double lower, double upper, double alpha, double beta, double epsilon)
{
  const double strength = repulsionStrength(0.0, beta);
  return repulsion(phi, lower, alpha, strength, epsilon) + repulsion(phi, upper, alpha, strength, epsilon);
}

std::vector<double> softmaxWeights(const std::vector<double>& strengths, double threshold, double beta)
{
  std::vector<double> w(strengths.size(), 0.0);
  double largest = 0.0;
  for (double a : strengths)
    if (a >= threshold)
      largest = std::max(largest, a);
  double sum = 0.0;
  for (size_t i = 0; i < strengths.size(); ++i)
    if (strengths[i] >= threshold)
      sum += w[i] = std::exp((strengths[i] - largest) / beta);
  if (sum > 0)
    for (double& x : w)
      x /= sum;
  return w;
}

int dominantIndex(const std::vector<double>& weights)
{
  int dominant = -1;
  for (int i = 0; i < static_cast<int>(weights.size()); ++i)
    if (weights[i] > 0 && (dominant < 0 || weights[i] > weights[dominant]))
      dominant = i;
  return dominant;
}

int selectWithPersistence(std::vector<double>& weights, int selected, double bonus)
{
  const int n = static_cast<int>(weights.size());
  const int dominant = dominantIndex(weights);
  if (selected < 0 || selected >= n || weights[selected] <= 0 ||
      (dominant >= 0 && weights[dominant] > weights[selected] * (1 + bonus)))
    selected = dominant;
  if (selected >= 0)
    weights[selected] *= 1 + bonus;
  return selected;
}

double sectorCentre(int i, int n, double field)
{
  return -field / 2 + field / n * (i + 0.5);
}

int sectorOf(double angle, int n, double field)
{
  // Clamped before the conversion to int: a non-finite or huge index would be undefined behaviour.
  const double index = std::floor((angle + field / 2) / (field / n));
  if (!(index >= 0))  // also NaN
    return 0;
  return index >= n - 1 ? n - 1 : static_cast<int>(index);
}
}  // namespace biovision_attractor
