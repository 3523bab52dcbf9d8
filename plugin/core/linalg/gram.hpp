// Gram matrices W = Y^T Y of the constraint columns Y = L^-1 P B (method.md
// §4), formed from dense blocks of rows by symmetric rank-k updates (BLAS-3).
//
// The rows of Y come in elimination order: a column reaches the rows of its
// elimination-tree path, so consecutive rows (a supernode, then the
// separators above it) share most of their columns, and the top separators'
// rows are reached by nearly every column. Blocks of rows are gathered into
// runs with the columns they touch, and W gets D^T D per run instead of the
// terms of a sparse x sparse product whose sparse result is in the end dense
// (issue 14: 38-92% of the setup before).
#pragma once

#include <vector>

#include "base/types.hpp"

namespace nbm {

class GramAccumulator {
 public:
  /// W is m x m.
  explicit GramAccumulator(Index m);

  /// W += D^T D for a dense block D (r x k) whose column c is column
  /// columns[c] of Y (ascending). The block is copied into the current run,
  /// or, if it is large, applied at once.
  void add(const Eigen::Ref<const Matrix>& D, const std::vector<int>& columns);
  /// The same for row `row` of a row-major sparse Y.
  void add_row(const Eigen::SparseMatrix<double, Eigen::RowMajor, int>& Y, Index row);

  /// W, symmetric to the last bit (lower triangle computed, then mirrored).
  Matrix finish();

 private:
  // Appends `rows` rows whose entries are given by `put(run_row, local)`
  // (local: the run's column of each of Y's columns) to the run, after
  // flushing it if the new rows would leave it less than half full or make
  // it exceed kGramBlockEntries.
  template <class Columns, class Put>
  void append(Index rows, Index nonzeros, const Columns& columns, Put put);
  void flush();
  // W += D^T D for D with columns `columns` of W, in chunks of rows.
  void update(const Eigen::Ref<const Matrix>& D, const std::vector<int>& columns);

  Index m_;
  Matrix W_;
  std::vector<int> local_;    // column of Y -> column of the run, -1 if not in it
  std::vector<int> columns_;  // the run's columns, in the order met
  Index height_ = 0, filled_ = 0;
  std::vector<Triplet> entries_;  // the run's entries (row in the run, run column)
  Matrix chunk_, Wb_;
};

/// Y^T Y, dense and symmetric to the last bit.
Matrix inner_products(const SparseMatrix& Y);

}  // namespace nbm
