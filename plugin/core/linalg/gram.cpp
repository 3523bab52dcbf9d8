#include "linalg/gram.hpp"

#include <algorithm>
#include <numeric>

namespace nbm {
namespace {

// Largest dense block of rows gathered into one run, and the row chunks of a
// larger block applied at once (16 MiB).
constexpr Index kGramBlockEntries = Index(1) << 21;

}  // namespace

GramAccumulator::GramAccumulator(Index m) : m_(m), W_(Matrix::Zero(m, m)), local_(m, -1) {}

template <class Columns, class Put>
void GramAccumulator::append(Index rows, Index nonzeros, const Columns& columns, Put put) {
  Index added = 0;
  for (int c : columns) added += local_[c] < 0;
  const Index height = height_ + rows, width = static_cast<Index>(columns_.size()) + added;
  if (!columns_.empty() &&
      (2 * (filled_ + nonzeros) < height * width || height * width > kGramBlockEntries))
    flush();
  for (int c : columns)
    if (local_[c] < 0) {
      local_[c] = static_cast<int>(columns_.size());
      columns_.push_back(c);
    }
  put(height_, local_);
  height_ += rows;
  filled_ += nonzeros;
}

void GramAccumulator::add(const Eigen::Ref<const Matrix>& D, const std::vector<int>& columns) {
  if (D.rows() == 0 || columns.empty()) return;
  if (D.size() > kGramBlockEntries) {
    flush();
    update(D, columns);
    return;
  }
  append(D.rows(), D.size(), columns, [&](Index first, const std::vector<int>& local) {
    for (Index c = 0; c < D.cols(); ++c)
      for (Index i = 0; i < D.rows(); ++i) entries_.emplace_back(first + i, local[columns[c]], D(i, c));
  });
}

void GramAccumulator::add_row(const Eigen::SparseMatrix<double, Eigen::RowMajor, int>& Y,
                              Index row) {
  using It = Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator;
  const Index nonzeros = Y.outerIndexPtr()[row + 1] - Y.outerIndexPtr()[row];
  if (nonzeros == 0) return;
  const auto* begin = Y.innerIndexPtr() + Y.outerIndexPtr()[row];
  const std::vector<int> columns(begin, begin + nonzeros);
  append(1, nonzeros, columns, [&](Index first, const std::vector<int>& local) {
    for (It it(Y, row); it; ++it) entries_.emplace_back(first, local[it.col()], it.value());
  });
}

void GramAccumulator::flush() {
  if (columns_.empty()) return;
  // Columns in increasing order: the lower triangle of D^T D maps to W's.
  const Index width = static_cast<Index>(columns_.size());
  std::vector<int> order(width);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return columns_[a] < columns_[b]; });
  std::vector<int> position(width), sorted(width);
  for (Index c = 0; c < width; ++c) {
    position[order[c]] = static_cast<int>(c);
    sorted[c] = columns_[order[c]];
  }
  Matrix D = Matrix::Zero(height_, width);
  for (const Triplet& t : entries_) D(t.row(), position[t.col()]) = t.value();
  for (int c : columns_) local_[c] = -1;
  entries_.clear();
  columns_.clear();
  height_ = filled_ = 0;
  update(D, sorted);
}

void GramAccumulator::update(const Eigen::Ref<const Matrix>& D, const std::vector<int>& columns) {
  const Index k = static_cast<Index>(columns.size());
  if (2 * k < m_) {
    // Few columns: D^T D apart (k x k), then added to W's lower triangle.
    Wb_.setZero(k, k);
    Wb_.selfadjointView<Eigen::Lower>().rankUpdate(D.transpose());
    for (Index b = 0; b < k; ++b)
      for (Index a = b; a < k; ++a) W_(columns[a], columns[b]) += Wb_(a, b);
    return;
  }
  // Most columns: W updated in place over all of them (no k x k temporary of
  // the size of W), in chunks of rows spread over W's columns, or straight
  // from D when its columns are all of W's.
  const bool all = k == m_;
  const Index step = std::max<Index>(128, kGramBlockEntries / m_);
  for (Index first = 0; first < D.rows(); first += step) {
    const Index rows = std::min(step, D.rows() - first);
    if (all) {
      W_.selfadjointView<Eigen::Lower>().rankUpdate(D.middleRows(first, rows).transpose());
      continue;
    }
    chunk_.setZero(rows, m_);
    for (Index c = 0; c < k; ++c) chunk_.col(columns[c]) = D.col(c).segment(first, rows);
    W_.selfadjointView<Eigen::Lower>().rankUpdate(chunk_.transpose());
  }
}

Matrix GramAccumulator::finish() {
  flush();
  W_.triangularView<Eigen::StrictlyUpper>() = W_.transpose();
  return std::move(W_);
}

Matrix inner_products(const SparseMatrix& Y) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> rows = Y;
  GramAccumulator W(Y.cols());
  for (Index i = 0; i < rows.rows(); ++i) W.add_row(rows, i);
  return W.finish();
}

}  // namespace nbm
