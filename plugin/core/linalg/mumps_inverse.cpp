#include "linalg/mumps_inverse.hpp"

#include <dmumps_c.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/errors.hpp"
#include "linalg/dense_cholesky.hpp"

namespace nbm {
namespace {

// MUMPS's parameter arrays are 1-based in its user guide.
int& icntl(DMUMPS_STRUC_C& id, int i) { return id.icntl[i - 1]; }
int infog(const DMUMPS_STRUC_C& id, int i) { return id.infog[i - 1]; }

// INFOG(1) < 0 is MUMPS's error, known to every rank.
void check(const DMUMPS_STRUC_C& id, const std::string& what) {
  if (infog(id, 1) < 0)
    throw NumericalError("MUMPS failed in " + what + ": INFOG(1) = " + std::to_string(infog(id, 1)) +
                         ", INFOG(2) = " + std::to_string(infog(id, 2)) +
                         " (INFOG in the MUMPS user guide)");
}

// One MUMPS instance, released when its owner goes, also when the owner's
// constructor throws.
struct MumpsInstance {
  MumpsInstance(MpiCommunicator comm) {
    id.comm_fortran = comm.fortran_handle;
    id.par = 1;  // the host works too
    id.sym = 1;  // symmetric positive definite: LDL^T without pivoting
    id.job = -1;
    dmumps_c(&id);
    check(id, "initialization");
    for (int stream = 1; stream <= 3; ++stream) icntl(id, stream) = -1;  // silent
    icntl(id, 4) = 0;
  }
  ~MumpsInstance() {
    // Collective, like every MUMPS call; after MPI_Finalize (an inverse that
    // outlives a front end's MPI session) the memory goes with the process.
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (finalized) return;
    id.job = -2;
    dmumps_c(&id);
  }
  MumpsInstance(const MumpsInstance&) = delete;
  MumpsInstance& operator=(const MumpsInstance&) = delete;
  DMUMPS_STRUC_C id{};
};

// The pivot order MUMPS is given (1-based positions: perm[v] is the place
// of variable v): CHOLMOD's fill-reducing order of the interior, then the
// Schur variables, which MUMPS eliminates last. With a Schur complement
// MUMPS's own choice is the minimum degree alone, whose factor of a 3D
// elasticity matrix is several times larger than nested dissection's
// (bench/RESULTS-mumps.md); without one, the same order keeps the two
// libraries' factors alike.
std::vector<int> pivot_positions(const SparseMatrix& X, const std::vector<Index>& schur) {
  const Index n = X.rows();
  std::vector<Index> interior_index(static_cast<std::size_t>(n), 0), interior;
  for (Index v : schur) interior_index[static_cast<std::size_t>(v)] = -1;
  for (Index v = 0; v < n; ++v)
    if (interior_index[static_cast<std::size_t>(v)] == 0) {
      interior_index[static_cast<std::size_t>(v)] = static_cast<Index>(interior.size());
      interior.push_back(v);
    }
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(X.nonZeros()));
  for (Index j = 0; j < X.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(X, j); it; ++it) {
      const Index r = interior_index[static_cast<std::size_t>(it.row())];
      const Index c = interior_index[static_cast<std::size_t>(j)];
      if (r >= 0 && c >= 0) entries.emplace_back(r, c, it.value());
    }
  const Index ni = static_cast<Index>(interior.size());
  SparseMatrix X_II(ni, ni);
  X_II.setFromTriplets(entries.begin(), entries.end());
  std::vector<int> perm(static_cast<std::size_t>(n));
  int position = 0;
  for (Index k : fill_reducing_order(X_II))
    perm[static_cast<std::size_t>(interior[static_cast<std::size_t>(k)])] = ++position;
  for (Index v : schur) perm[static_cast<std::size_t>(v)] = ++position;
  return perm;
}

// The input MUMPS reads: the lower triangle of X, 1-based; on the host
// (rank 0) the pivot order and the Schur variables. With several ranks each
// gives MUMPS the entries of its share of the columns (distributed input,
// ICNTL(18) = 3): every rank holds X already, and the host neither
// gathers the whole triangle nor sends it out (bench/RESULTS-mumps.md).
// MUMPS reads the input while it analyses and factors, so it lives in the
// caller's scope.
struct MumpsInput {
  MumpsInput(DMUMPS_STRUC_C& id, int rank, int ranks, const SparseMatrix& X,
             const std::vector<Index>& schur,
             MumpsOrdering ordering = MumpsOrdering::kFillReducing) {
    const bool distributed = ranks > 1;
    if (rank == 0) {
      id.n = static_cast<int>(X.rows());
      if (ordering == MumpsOrdering::kFillReducing) {
        perm = pivot_positions(X, schur);
        id.perm_in = perm.data();
        icntl(id, 7) = 1;  // the order given in perm_in
      }
    }
    if (distributed || rank == 0) {
      const Index first = distributed ? X.outerSize() * rank / ranks : 0;
      const Index last = distributed ? X.outerSize() * (rank + 1) / ranks : X.outerSize();
      for (Index j = first; j < last; ++j)
        for (SparseMatrix::InnerIterator it(X, j); it; ++it)
          if (it.row() >= j) {
            rows.push_back(static_cast<int>(it.row() + 1));
            cols.push_back(static_cast<int>(j + 1));
            values.push_back(it.value());
          }
    }
    if (distributed) {
      icntl(id, 18) = 3;  // the entries distributed by the user
      id.nnz_loc = static_cast<int64_t>(values.size());
      id.irn_loc = rows.data();
      id.jcn_loc = cols.data();
      id.a_loc = values.data();
    } else if (rank == 0) {
      id.nnz = static_cast<int64_t>(values.size());
      id.irn = rows.data();
      id.jcn = cols.data();
      id.a = values.data();
    }
    if (!schur.empty()) {
      icntl(id, 19) = 1;  // the Schur complement, centralised on the host
      id.size_schur = static_cast<int>(schur.size());
      for (Index v : schur) schur_list.push_back(static_cast<int>(v + 1));
      id.listvar_schur = schur_list.data();
    }
  }
  std::vector<int> rows, cols, schur_list, perm;
  std::vector<double> values;
};

// MUMPS's counts: a negative INFOG is in millions.
double count(int value) { return value >= 0 ? value : -1e6 * static_cast<double>(value); }

// A fingerprint of column-major doubles for check_same_on_every_rank: two
// weighted sums that a changed, moved or swapped entry changes.
std::vector<double> fingerprint(const double* x, Index count) {
  double a = 0, b = 0;
  for (Index i = 0; i < count; ++i) {
    a += x[i] * (1.0 + 0.25 * static_cast<double>(i % 7));
    b += std::abs(x[i]) * (1.0 + 0.5 * static_cast<double>(i % 3));
  }
  return {static_cast<double>(count), a, b};
}

class MumpsInverse final : public CholeskyInverse {
 public:
  MumpsInverse(const SparseMatrix& X, const std::string& what, std::vector<Index> schur,
               MpiCommunicator comm)
      : n_(X.rows()),
        what_(what),
        schur_(std::move(schur)),
        ranks_(comm),
        comm_(MPI_Comm_f2c(comm.fortran_handle)),
        position_(n_, -1),
        mumps_(comm),
        id_(mumps_.id) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_count_);
    const Index m = static_cast<Index>(schur_.size());
    for (Index k = 0; k < m; ++k) position_[schur_[k]] = k;

    const MumpsInput input(id_, rank_, ranks_count_, X, schur_);
    Matrix S;
    if (m > 0) {
      S = Matrix::Zero(m, m);
      if (rank_ == 0) id_.schur = S.data();
    }
    id_.job = 4;  // analysis and factorization
    dmumps_c(&id_);
    if (infog(id_, 1) == -10 || infog(id_, 12) > 0)
      throw NumericalError(what + " is not positive definite (MUMPS factorization)");
    check(id_, what + " factorization");
    factor_entries_ = count(infog(id_, 29));
    id_.irn = id_.jcn = id_.irn_loc = id_.jcn_loc = nullptr;
    id_.a = id_.a_loc = nullptr;
    id_.listvar_schur = nullptr;
    id_.perm_in = nullptr;
    id_.schur = nullptr;
    if (m == 0) return;

    // MUMPS fills one triangle of the symmetric S_X (its guide: the lower one
    // by rows, i.e. our upper one by columns); mirror it for the Cholesky
    // factor, which reads the lower one.
    broadcast(S.data(), S.size());
    for (Index j = 0; j < m; ++j)
      for (Index i = j + 1; i < m; ++i) S(i, j) = S(j, i);
    factor_entries_ += 0.5 * static_cast<double>(m) * static_cast<double>(m + 1);
    schur_factor_ = DenseCholesky(std::move(S));
    if (!schur_factor_.positive_definite())
      throw NumericalError(what + " is not positive definite (its Schur complement on the " +
                           std::to_string(m) + " contact variables)");
  }

  Index size() const override { return n_; }

  void solve_in_place(Vector& x) const override {
    forward_in_place(x);
    backward_in_place(x);
  }
  void solve_in_place(Matrix& x) const override {
    forward(x.data(), x.cols());
    backward(x.data(), x.cols());
  }

  void forward_in_place(Vector& x) const override {
    check_size(x.size());
    forward(x.data(), 1);
  }
  void backward_in_place(Vector& x) const override {
    check_size(x.size());
    backward(x.data(), 1);
  }

  using CholeskyInverse::forward;
  // Y = L^-1 P B = [0; L_S^-1 B_S]: dense on the Schur rows.
  SparseMatrix forward(const SparseMatrix& B, Matrix* gram) const override {
    Matrix Y_S = schur_rows(B);
    schur_factor_.matrixL().solveInPlace(Y_S);
    if (gram != nullptr) *gram = Y_S.transpose() * Y_S;
    std::vector<Triplet> entries;
    entries.reserve(static_cast<std::size_t>(Y_S.size()));
    for (Index j = 0; j < Y_S.cols(); ++j)
      for (Index k = 0; k < Y_S.rows(); ++k)
        if (Y_S(k, j) != 0) entries.emplace_back(schur_[k], j, Y_S(k, j));
    SparseMatrix Y(n_, B.cols());
    Y.setFromTriplets(entries.begin(), entries.end());
    return Y;
  }

  Matrix gram(const SparseMatrix& B) const override {
    Matrix W;
    forward(B, &W);
    return W;
  }

  double forward_entries(const SparseMatrix& B) const override {
    check_rows(B);
    return static_cast<double>(schur_.size()) * static_cast<double>(B.cols());
  }
  double factor_entries() const override { return factor_entries_; }

 private:
  // x (n x cols, column-major, the same on every rank) <- the forward half.
  void forward(double* x, Index cols) const {
    const Index m = static_cast<Index>(schur_.size());
    // MUMPS reads rank 0's right-hand side: one computed from other data on
    // another rank (a load, a state that differs) is an error, not ignored.
    if (ranks_count_ > 1)
      check_same_on_every_rank(ranks_, fingerprint(x, n_ * cols),
                               "the right-hand side of a solve with " + what_);
    reduced_columns_ = cols;
    if (m == 0) return;  // L = I: backward does the whole solve
    reduced_.resize(m * cols);
    run_solve(x, cols, 1);  // reduction: r_S into reduced_
    broadcast(reduced_.data(), reduced_.size());
    Eigen::Map<Matrix> r(reduced_.data(), m, cols);
    schur_factor_.matrixL().solveInPlace(r);
    Eigen::Map<Matrix> y(x, n_, cols);
    y.setZero();
    for (Index k = 0; k < m; ++k) y.row(schur_[k]) = r.row(k);
  }

  // x <- the backward half, continuing the last forward of as many columns.
  void backward(double* x, Index cols) const {
    if (reduced_columns_ != cols)
      throw std::logic_error("MumpsInverse: backward without the forward it continues");
    reduced_columns_ = 0;
    const Index m = static_cast<Index>(schur_.size());
    if (m > 0) {
      Eigen::Map<Matrix> z(reduced_.data(), m, cols);
      Eigen::Map<const Matrix> y(x, n_, cols);
      for (Index k = 0; k < m; ++k) z.row(k) = y.row(schur_[k]);
      schur_factor_.matrixU().solveInPlace(z);  // x_S
    }
    run_solve(x, cols, m > 0 ? 2 : 0);  // expansion, or a whole solve
    broadcast(x, n_ * cols);
  }

  // MUMPS's solve phase on the host's x with ICNTL(26) = `phase` (0 whole
  // solve, 1 reduction into reduced_, 2 expansion from reduced_).
  void run_solve(double* x, Index cols, int phase) const {
    id_.nrhs = static_cast<int>(cols);
    id_.lrhs = static_cast<int>(n_);
    id_.rhs = rank_ == 0 ? x : nullptr;
    if (phase != 0) {
      id_.redrhs = rank_ == 0 ? reduced_.data() : nullptr;
      id_.lredrhs = static_cast<int>(schur_.size());
    }
    icntl(id_, 26) = phase;
    id_.job = 3;
    dmumps_c(&id_);
    check(id_, "solve");
  }

  // B's rows on the Schur variables, dense; every entry of B must lie there.
  Matrix schur_rows(const SparseMatrix& B) const {
    check_rows(B);
    Matrix B_S = Matrix::Zero(static_cast<Index>(schur_.size()), B.cols());
    for (Index j = 0; j < B.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(B, j); it; ++it) {
        if (it.value() == 0) continue;
        if (position_[it.row()] < 0)
          throw std::logic_error("MumpsInverse::forward: row " + std::to_string(it.row()) +
                                 " of the constraint basis is not a Schur variable");
        B_S(position_[it.row()], j) = it.value();
      }
    return B_S;
  }

  void broadcast(double* data, Index count) const {
    if (count > 0) MPI_Bcast(data, static_cast<int>(count), MPI_DOUBLE, 0, comm_);
  }

  void check_rows(const SparseMatrix& B) const {
    if (B.rows() != n_)
      throw InputError("forward: a matrix with " + std::to_string(B.rows()) + " rows, expected " +
                       std::to_string(n_));
  }
  void check_size(Index size) const {
    if (size != n_)
      throw InputError("solve: a vector of size " + std::to_string(size) + ", expected " +
                       std::to_string(n_));
  }

  Index n_;
  std::string what_;
  std::vector<Index> schur_;     // S, ascending
  MpiCommunicator ranks_;
  MPI_Comm comm_;                // ranks_
  int rank_ = 0, ranks_count_ = 1;
  std::vector<Index> position_;  // of each variable in S, -1 outside
  mutable MumpsInstance mumps_;
  DMUMPS_STRUC_C& id_;           // mumps_.id; the solve phases write their statistics in it
  DenseCholesky schur_factor_;   // L_S
  double factor_entries_ = 0;
  mutable std::vector<double> reduced_;  // r_S, then x_S (m x columns)
  mutable Index reduced_columns_ = 0;    // of the forward backward continues
};

// The input both MUMPS calls take: X square, the Schur variables distinct
// rows in ascending order with at least one row left to factor, and the
// same X and Schur variables on every rank.
void check_input(const SparseMatrix& X, const std::string& what,
                 const std::vector<Index>& schur_variables, MpiCommunicator comm) {
  if (X.rows() != X.cols())
    throw InputError(what + ": " + std::to_string(X.rows()) + " x " + std::to_string(X.cols()) +
                     ", expected a square matrix");
  if (!std::is_sorted(schur_variables.begin(), schur_variables.end()) ||
      std::adjacent_find(schur_variables.begin(), schur_variables.end()) !=
          schur_variables.end() ||
      (!schur_variables.empty() &&
       (schur_variables.front() < 0 || schur_variables.back() >= X.rows())))
    throw InputError(what + ": Schur variables must be distinct rows in ascending order");
  if (static_cast<Index>(schur_variables.size()) == X.rows() && X.rows() > 0)
    throw InputError(what + ": every variable is a Schur variable (nothing for MUMPS to factor)");
  // The ranks must bring the same matrix and Schur variables before the
  // first collective MUMPS call (which would hang, or factor rank 0's alone).
  if (mpi_size(comm) > 1) {
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(X.nonZeros()));
    for (Index j = 0; j < X.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(X, j); it; ++it) values.push_back(it.value());
    std::vector<double> same(fingerprint(values.data(), static_cast<Index>(values.size())));
    same.push_back(static_cast<double>(X.rows()));
    for (Index v : schur_variables) same[1] += static_cast<double>(v);
    same.push_back(static_cast<double>(schur_variables.size()));
    check_same_on_every_rank(comm, same, what);
  }
}

}  // namespace

std::unique_ptr<CholeskyInverse> make_mumps_inverse(const SparseMatrix& X, const std::string& what,
                                                    std::vector<Index> schur_variables,
                                                    MpiCommunicator comm) {
  check_input(X, what, schur_variables, comm);
  return std::make_unique<MumpsInverse>(X, what, std::move(schur_variables), comm);
}

MumpsEstimate estimate_mumps_factorization(const SparseMatrix& X, const std::string& what,
                                           const std::vector<Index>& schur_variables,
                                           MpiCommunicator comm, MumpsOrdering ordering) {
  check_input(X, what, schur_variables, comm);
  MumpsInstance mumps(comm);
  DMUMPS_STRUC_C& id = mumps.id;
  const MumpsInput input(id, mpi_rank(comm), mpi_size(comm), X, schur_variables, ordering);
  id.job = 1;  // analysis
  dmumps_c(&id);
  check(id, what + " analysis");
  return {count(infog(id, 3)), id.rinfog[0], static_cast<double>(infog(id, 16)),
          static_cast<double>(infog(id, 17))};
}

std::vector<Index> touched_rows(const SparseMatrix& constraints) {
  std::vector<char> touched(static_cast<std::size_t>(constraints.rows()), 0);
  for (Index j = 0; j < constraints.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(constraints, j); it; ++it)
      if (it.value() != 0) touched[static_cast<std::size_t>(it.row())] = 1;
  std::vector<Index> rows;
  for (Index i = 0; i < constraints.rows(); ++i)
    if (touched[static_cast<std::size_t>(i)]) rows.push_back(i);
  return rows;
}

}  // namespace nbm
