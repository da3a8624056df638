#include "biovision_recognition/lda_hash_trainer.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace biovision_recognition
{
namespace
{
using MatrixD = Eigen::MatrixXd;

/// Leading `rank` eigenpairs of the symmetric matrix `cov`, descending.
void leadingEigenpairs(const MatrixD& cov, int rank, int exact_limit, int iterations, unsigned seed,
                       Eigen::VectorXd& values, MatrixD& vectors)
{
  const Eigen::Index n = cov.cols();
  if (n <= exact_limit)
  {
    Eigen::SelfAdjointEigenSolver<MatrixD> eig(cov);
    const Eigen::Index r = std::min<Eigen::Index>(rank, n);
    values = eig.eigenvalues().reverse().head(r);
    vectors = eig.eigenvectors().rowwise().reverse().leftCols(r);
    return;
  }
  // Randomised subspace iteration: an n x (rank + 32) basis, never an n x n decomposition.
  const Eigen::Index l = std::min<Eigen::Index>(n, rank + 32);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  MatrixD q(n, l);
  for (Eigen::Index i = 0; i < q.size(); ++i)
    q.data()[i] = gauss(rng);
  for (int it = 0; it <= iterations; ++it)
  {
    const MatrixD y = cov * q;  // n x l
    Eigen::HouseholderQR<MatrixD> qr(y);
    q = qr.householderQ() * MatrixD::Identity(n, l);
  }
  const MatrixD small = q.transpose() * cov * q;
  Eigen::SelfAdjointEigenSolver<MatrixD> eig(small);
  const Eigen::Index r = std::min<Eigen::Index>(rank, l);
  values = eig.eigenvalues().reverse().head(r);
  vectors = q * eig.eigenvectors().rowwise().reverse().leftCols(r);
}
}  // namespace

DescriptorModel LdaHashTrainer::train(const Matrix& pa, const Matrix& pb, const Matrix& na, const Matrix& nb) const
{
  if (pa.rows() != pb.rows() || na.rows() != nb.rows() || pa.cols() != pb.cols() || na.cols() != nb.cols())
    throw std::invalid_argument("LdaHashTrainer: the pair matrices disagree in size");
  return trainOnDifferences(pa, pa - pb, na, na - nb);
}

DescriptorModel LdaHashTrainer::trainOnDifferences(const Matrix& pa, const Matrix& dp, const Matrix& na,
                                                   const Matrix& dn) const
{
  if (pa.rows() != dp.rows() || na.rows() != dn.rows() || pa.cols() != dp.cols() || pa.cols() != na.cols() ||
      na.cols() != dn.cols())
    throw std::invalid_argument("LdaHashTrainer: the pair matrices disagree in size");
  if (pa.rows() < 2 * parameters_.bits || na.rows() < 2 * parameters_.bits)  // before the statistics' own checks
    throw std::invalid_argument("LdaHashTrainer: need at least 2 * bits positive and negative pairs");
  using Kind = LdaHashStatistics::Kind;
  LdaHashStatistics statistics(static_cast<int>(pa.cols()), static_cast<int>(std::max(pa.rows(), na.rows())),
                               parameters_.seed);
  statistics.add(Kind::positive, pa, dp);
  statistics.add(Kind::negative, na, dn);
  return train(statistics);
}

DescriptorModel LdaHashTrainer::train(const LdaHashStatistics& statistics) const
{
  using Kind = LdaHashStatistics::Kind;
  const int bits = parameters_.bits;
  const long positives = statistics.pairs(Kind::positive), negatives = statistics.pairs(Kind::negative);
  if (positives < 2 * bits || negatives < 2 * bits)
    throw std::invalid_argument("LdaHashTrainer: need at least 2 * bits positive and negative pairs");
  if (parameters_.whitening_rank < bits || statistics.features() < bits)
    throw std::invalid_argument("LdaHashTrainer: whitening_rank and the feature count must be >= bits");

  // 1. Regularised Sigma_N^-1/2 on the leading eigenpairs.
  Eigen::VectorXd lambda;
  MatrixD u;
  leadingEigenpairs(statistics.moment(Kind::negative) / static_cast<double>(negatives), parameters_.whitening_rank,
                    parameters_.exact_limit, parameters_.power_iterations, parameters_.seed, lambda, u);
  const double floor = parameters_.ridge * std::max(lambda(0), 1e-30);
  const Eigen::VectorXd inv_sqrt = (lambda.array().max(0.0) + floor).rsqrt();
  const MatrixD w = inv_sqrt.asDiagonal() * u.transpose();  // rank x n

  // 2. Smallest eigenvectors of the whitened positive covariance W Sigma_P W^T.
  const MatrixD sp = w * statistics.moment(Kind::positive) * w.transpose() / static_cast<double>(positives);
  Eigen::SelfAdjointEigenSolver<MatrixD> eig(sp);  // ascending
  const Eigen::VectorXd s = eig.eigenvalues().head(bits).array().max(1e-12);
  const MatrixD v = eig.eigenvectors().leftCols(bits);
  const MatrixD p = s.array().rsqrt().matrix().asDiagonal() * v.transpose() * w;

  DescriptorModel model;
  model.projection = p.cast<float>();
  // 3. On the sample; b = a - difference, so P b = P a - P difference.
  const Matrix pt = model.projection.transpose();
  const Matrix ya = statistics.sampleA(Kind::positive) * pt;
  const Matrix yb = ya - statistics.sampleDifference(Kind::positive) * pt;
  const Matrix za = statistics.sampleA(Kind::negative) * pt;
  const Matrix zb = za - statistics.sampleDifference(Kind::negative) * pt;
  model.thresholds = thresholds(ya, yb, za, zb);
  return model;
}

Eigen::VectorXf LdaHashTrainer::thresholds(const Matrix& ya, const Matrix& yb, const Matrix& za, const Matrix& zb) const
{
  const int k = std::max(2, parameters_.threshold_candidates);
  Eigen::VectorXf t(ya.cols());
  std::vector<long> pos_delta(k + 1), neg_delta(k + 1);
  for (Eigen::Index b = 0; b < ya.cols(); ++b)
  {
    const float lo = std::min({ya.col(b).minCoeff(), yb.col(b).minCoeff(), za.col(b).minCoeff(), zb.col(b).minCoeff()});
    const float hi = std::max({ya.col(b).maxCoeff(), yb.col(b).maxCoeff(), za.col(b).maxCoeff(), zb.col(b).maxCoeff()});
    const double step = (hi - lo) / (k - 1);
    if (!(step > 0))
    {
      t(b) = lo;
      continue;
    }
    // Candidate c = lo + c * step separates a pair (u, v) iff min(u,v) <= c < max(u,v) (bit = value > t).
    auto first = [&](float value) { return static_cast<long>(std::ceil((value - lo) / step - 1e-9)); };
    std::fill(pos_delta.begin(), pos_delta.end(), 0);
    std::fill(neg_delta.begin(), neg_delta.end(), 0);
    auto add = [&](std::vector<long>& delta, float u, float v) {
      const long from = std::max(0L, first(std::min(u, v)));
      const long to = std::min<long>(k, first(std::max(u, v)));  // exclusive
      if (from < to)
      {
        ++delta[from];
        --delta[to];
      }
    };
    for (Eigen::Index i = 0; i < ya.rows(); ++i)
      add(pos_delta, ya(i, b), yb(i, b));
    for (Eigen::Index i = 0; i < za.rows(); ++i)
      add(neg_delta, za(i, b), zb(i, b));
    long pos_split = 0, neg_split = 0, best = -1;
    int best_c = 0;
    for (int c = 0; c < k; ++c)
    {
      pos_split += pos_delta[c];
      neg_split += neg_delta[c];
      const long correct = (static_cast<long>(ya.rows()) - pos_split) + neg_split;
      if (correct > best)
      {
        best = correct;
        best_c = c;
      }
    }
    t(b) = static_cast<float>(lo + best_c * step);
  }
  return t;
}
}  // namespace biovision_recognition
