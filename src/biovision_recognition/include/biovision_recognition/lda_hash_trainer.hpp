#pragma once

#include <Eigen/Core>

#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/lda_hash_statistics.hpp"

namespace biovision_recognition
{
/// LDAHash (Strecha et al. 2012), as the thesis trains it (3.3.3-3.3.4).
///
/// With positive differences x - x' (matching pairs) and negative differences x - x'' (non-matching):
/// 1. Sigma_N^-1/2, regularised: the leading `whitening_rank` eigenpairs (U, L) of Sigma_N, and
///    W = (L + ridge * l_1)^-1/2 U^T. Directions where non-matching pairs barely differ carry no
///    contrast and only amplify noise, so they are dropped instead of inverted. The eigenpairs come
///    exactly (Eigen's self-adjoint solver) up to `exact_limit` features and from randomised subspace
///    iteration (Halko, Martinsson & Tropp 2011) on the covariance above it.
/// 2. In the whitened space, Sigma_P' = W Sigma_P W^T; its m eigenvectors V with the smallest eigenvalues
///    S give P = S^-1/2 V^T W (eq. 3.2: minimises the positive-pair spread relative to the negative).
/// 3. Thresholds, on LdaHashStatistics' uniform sample of the pairs: per bit, K candidates equally spaced
///    between the smallest and largest projected value; the one with most correct matches (both codes on one side) plus correct non-matches (on
///    different sides). Counted with interval histograms, O(pairs + K) per bit instead of O(pairs * K).
class LdaHashTrainer
{
public:
  struct Parameters
  {
    int bits = 128;
    int whitening_rank = 512;         ///< eigenpairs of Sigma_N kept. >= bits
    double ridge = 1e-3;              ///< added to the eigenvalues, relative to the largest
    int threshold_candidates = 3000;  ///< K
    int exact_limit = 2000;           ///< exact eigen-decomposition up to this many features
    int power_iterations = 3;         ///< randomised subspace iterations
    unsigned seed = 1;
  };
  using Matrix = LdaHashStatistics::Matrix;

  explicit LdaHashTrainer(const Parameters& parameters) : parameters_(parameters) {}

  /// Returns projection and thresholds (layout and provenance are the caller's) from statistics gathered
  /// block by block (train_descriptor: the training set is bounded by the feature count, not the pairs).
  /// Throws std::invalid_argument on too few pairs (< 2 * bits of either kind) or features (< bits).
  DescriptorModel train(const LdaHashStatistics& statistics) const;

  /// The same on pairs in memory: rows are features x of the pairs' two sides (every pair is kept for the
  /// thresholds). Throws std::invalid_argument on inconsistent sizes or too few pairs.
  DescriptorModel train(const Matrix& positive_a, const Matrix& positive_b, const Matrix& negative_a,
                        const Matrix& negative_b) const;

  /// The same from one side of each pair and the pair differences (a - b).
  DescriptorModel trainOnDifferences(const Matrix& positive_a, const Matrix& positive_difference,
                                     const Matrix& negative_a, const Matrix& negative_difference) const;

  /// Step 3 alone: thresholds for given projected pairs (rows = pairs, columns = bits).
  Eigen::VectorXf thresholds(const Matrix& positive_a, const Matrix& positive_b, const Matrix& negative_a,
                             const Matrix& negative_b) const;

private:
  Parameters parameters_;
};
}  // namespace biovision_recognition
