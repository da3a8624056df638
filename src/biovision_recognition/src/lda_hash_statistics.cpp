#include "biovision_recognition/lda_hash_statistics.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace biovision_recognition
{
namespace
{
/// Rows folded into the moment at once: the float product of a block this tall runs near the GEMM peak,
/// and converting its features^2 result to double is paid once per block (about 100 MB pending at 12,832
/// features).
constexpr Eigen::Index kBlockRows = 2048;
}  // namespace

LdaHashStatistics::LdaHashStatistics(int features, int sample_pairs, unsigned seed)
  : features_(features), sample_pairs_(sample_pairs)
{
  if (features < 1 || sample_pairs < 1)
    throw std::invalid_argument("LdaHashStatistics: features and sample_pairs must be >= 1");
  positive_.rng.seed(seed);
  negative_.rng.seed(seed + 1);
  for (Accumulator* acc : {&positive_, &negative_})
  {
    acc->moment = Eigen::MatrixXd::Zero(features, features);
    // Allocated at full size here: the pages of large buffers are only committed as rows are written.
    acc->sample_a.resize(sample_pairs, features);
    acc->sample_difference.resize(sample_pairs, features);
    acc->pending.resize(kBlockRows, features);
  }
}

void LdaHashStatistics::add(Kind kind, const Matrix& a, const Matrix& difference)
{
  if (a.rows() != difference.rows() || a.cols() != features_ || difference.cols() != features_)
    throw std::invalid_argument("LdaHashStatistics: a block's sides disagree in size or do not have " +
                                std::to_string(features_) + " features");
  Accumulator& acc = accumulator(kind);
  for (Eigen::Index i = 0; i < a.rows(); ++i)
  {
    // Algorithm R: row t (0-based) replaces a uniformly chosen slot with probability sample_pairs / (t + 1).
    const long t = acc.pairs++;
    long slot = t;
    if (t >= sample_pairs_)
      slot = std::uniform_int_distribution<long>(0, t)(acc.rng);
    if (slot < sample_pairs_)
    {
      acc.sample_a.row(slot) = a.row(i);
      acc.sample_difference.row(slot) = difference.row(i);
    }
    acc.pending.row(acc.pending_rows++) = difference.row(i);
    if (acc.pending_rows == kBlockRows)
      flush(acc);
  }
}

void LdaHashStatistics::flush(Accumulator& acc) const
{
  if (acc.pending_rows == 0)
    return;
  const auto block = acc.pending.topRows(acc.pending_rows);
  product_.resize(features_, features_);  // allocates once
  product_.noalias() = block.transpose() * block;
  acc.moment += product_.cast<double>();
  acc.pending_rows = 0;
}

const Eigen::MatrixXd& LdaHashStatistics::moment(Kind kind) const
{
  Accumulator& acc = kind == Kind::positive ? positive_ : negative_;
  flush(acc);
  return acc.moment;
}

Eigen::Ref<const LdaHashStatistics::Matrix> LdaHashStatistics::sampleA(Kind kind) const
{
  const Accumulator& acc = accumulator(kind);
  return acc.sample_a.topRows(std::min<long>(acc.pairs, acc.sample_a.rows()));
}

Eigen::Ref<const LdaHashStatistics::Matrix> LdaHashStatistics::sampleDifference(Kind kind) const
{
  const Accumulator& acc = accumulator(kind);
  return acc.sample_difference.topRows(std::min<long>(acc.pairs, acc.sample_difference.rows()));
}
}  // namespace biovision_recognition
