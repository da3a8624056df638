#pragma once

#include <random>

#include <Eigen/Core>

namespace biovision_recognition
{
/// What LDAHash training (LdaHashTrainer, thesis 3.3.3-3.3.4) needs of a set of feature pairs, gathered one
/// block of pairs at a time, so a training set is bounded by the feature count rather than the pair count:
/// - the second moment sum_i d_i d_i^T of the pair differences d = a - b of each kind (matching, non-matching),
///   summed in double (uncentred, as Strecha et al. 2012: a difference of two views is as likely either sign);
/// - a uniform sample of at most `sample_pairs` pairs of each kind, one side a and the difference
///   (reservoir sampling, Vitter 1985), for the thresholds, which need projected values and so come after the
///   projection is known.
/// Memory: 2 moments of features^2 doubles, a features^2 float product, 4 samples of sample_pairs x features
/// floats, 2 pending blocks (12,832 features, 20,000 pairs: 2.6 + 0.66 + 4.1 + 0.2 GB). Not thread-safe, even
/// through const accessors (they fold the pending block in).
class LdaHashStatistics
{
public:
  using Matrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  enum class Kind
  {
    positive,  ///< matching pairs
    negative   ///< non-matching pairs
  };

  /// features: the columns of every block; sample_pairs: pairs of each kind kept for the thresholds.
  /// Throws std::invalid_argument when either is < 1.
  LdaHashStatistics(int features, int sample_pairs, unsigned seed = 1);

  /// Adds a block: rows = pairs, a = one side, difference = a - b. Throws std::invalid_argument when the
  /// two disagree in size or the columns are not `features`.
  void add(Kind kind, const Matrix& a, const Matrix& difference);

  int features() const { return features_; }
  /// Pairs of this kind added so far.
  long pairs(Kind kind) const { return accumulator(kind).pairs; }
  /// sum over the pairs of d d^T, features x features.
  const Eigen::MatrixXd& moment(Kind kind) const;
  /// The sample, rows = min(pairs, sample_pairs), in no particular order.
  Eigen::Ref<const Matrix> sampleA(Kind kind) const;
  Eigen::Ref<const Matrix> sampleDifference(Kind kind) const;

private:
  struct Accumulator
  {
    long pairs = 0;
    Eigen::MatrixXd moment;
    Matrix sample_a, sample_difference;  // sample_pairs rows allocated up front, min(pairs, sample_pairs) used
    Matrix pending;                      // differences not yet in the moment: a few big products, not many thin
    Eigen::Index pending_rows = 0;
    std::mt19937_64 rng;
  };
  const Accumulator& accumulator(Kind kind) const { return kind == Kind::positive ? positive_ : negative_; }
  Accumulator& accumulator(Kind kind) { return kind == Kind::positive ? positive_ : negative_; }
  void flush(Accumulator& accumulator) const;

  int features_;
  int sample_pairs_;
  mutable Accumulator positive_, negative_;  // moment() folds the pending block in
  mutable Eigen::MatrixXf
      product_;  // kept: a fresh features^2 buffer per block cost as much in page faults as the product
};
}  // namespace biovision_recognition
