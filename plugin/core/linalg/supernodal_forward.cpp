#include "linalg/supernodal_forward.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "base/errors.hpp"
#include "linalg/gram.hpp"

namespace nbm {
namespace {

// The supernodal structure of a CHOLMOD factor: supernode s holds the
// columns first[s] .. first[s + 1) and the rows rows[row_start[s] ..
// row_start[s + 1]) (its own columns first, then rows below them, ascending),
// its values a column-major block of that height at values + value_start[s].
struct Supernodes {
  explicit Supernodes(const cholmod_factor& L)
      : count(static_cast<int>(L.nsuper)),
        first(static_cast<const int*>(L.super)),
        row_start(static_cast<const int*>(L.pi)),
        value_start(static_cast<const int*>(L.px)),
        rows(static_cast<const int*>(L.s)),
        values(static_cast<const double*>(L.x)),
        owner(L.n),
        parent(count, -1),
        child_start(count + 1, 0),
        children(count) {
    for (int s = 0; s < count; ++s)
      for (int j = first[s]; j < first[s + 1]; ++j) owner[j] = s;
    // The parent is the supernode of the first row below the diagonal block:
    // a later one, so that visiting the supernodes in order visits children
    // before their parent.
    for (int s = 0; s < count; ++s)
      if (height(s) > width(s)) parent[s] = owner[rows[row_start[s] + width(s)]];
    for (int s = 0; s < count; ++s)
      if (parent[s] >= 0) ++child_start[parent[s] + 1];
    for (int s = 0; s < count; ++s) child_start[s + 1] += child_start[s];
    std::vector<int> next(child_start.begin(), child_start.end() - 1);
    for (int s = 0; s < count; ++s)
      if (parent[s] >= 0) children[next[parent[s]]++] = s;
  }

  int width(int s) const { return first[s + 1] - first[s]; }
  int height(int s) const { return row_start[s + 1] - row_start[s]; }

  int count;
  const int *first, *row_start, *value_start, *rows;
  const double* values;
  std::vector<int> owner;   // column -> its supernode
  std::vector<int> parent;  // supernode -> its parent, -1 for a root
  std::vector<int> child_start, children;  // children of s: children[child_start[s] ..)
};

// The entries of B by supernode of their permuted row: B's entry (i, j)
// lands in row inverse[i] of P B, which the supernode owning that column
// solves for.
struct EntriesBySupernode {
  EntriesBySupernode(const Supernodes& S, const SparseMatrix& B, const int* perm)
      : start(S.count + 1, 0) {
    std::vector<int> inverse(S.owner.size());
    for (std::size_t k = 0; k < inverse.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
    for (int j = 0; j < B.cols(); ++j)
      for (SparseMatrix::InnerIterator it(B, j); it; ++it)
        ++start[S.owner[inverse[it.row()]] + 1];
    for (int s = 0; s < S.count; ++s) start[s + 1] += start[s];
    column.resize(start.back());
    row.resize(start.back());
    value.resize(start.back());
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int j = 0; j < B.cols(); ++j)
      for (SparseMatrix::InnerIterator it(B, j); it; ++it) {
        const int p = inverse[it.row()], e = next[S.owner[p]]++;
        column[e] = j;
        row[e] = p;
        value[e] = it.value();
      }
  }
  std::vector<int> start, column, row;
  std::vector<double> value;
};

// The columns of B (ascending) that reach each supernode: those with entries
// in it and those reaching its children.
std::vector<std::vector<int>> reach(const Supernodes& S, const EntriesBySupernode& E, int m) {
  std::vector<std::vector<int>> columns(S.count);
  std::vector<int> mark(m, -1);
  for (int s = 0; s < S.count; ++s) {
    auto& mine = columns[s];
    auto take = [&](int j) {
      if (mark[j] == s) return;
      mark[j] = s;
      mine.push_back(j);
    };
    for (int e = E.start[s]; e < E.start[s + 1]; ++e) take(E.column[e]);
    for (int c = S.child_start[s]; c < S.child_start[s + 1]; ++c)
      for (int j : columns[S.children[c]]) take(j);
    std::sort(mine.begin(), mine.end());
  }
  return columns;
}

}  // namespace

void supernodal_forward(const cholmod_factor& L, const SparseMatrix& B, SparseMatrix* Y_out,
                        Matrix* gram) {
  const Supernodes S(L);
  const int n = static_cast<int>(L.n), m = static_cast<int>(B.cols());
  const EntriesBySupernode E(S, B, static_cast<const int*>(L.Perm));
  const std::vector<std::vector<int>> columns = reach(S, E, m);

  // Y in compressed columns, each column sized for every row of the
  // supernodes it reaches (exact zeros are dropped below).
  SparseMatrix Y(n, m);
  std::vector<Index> bound(m + 1, 0);
  if (Y_out != nullptr) {
    for (int s = 0; s < S.count; ++s)
      for (int j : columns[s]) bound[j + 1] += S.width(s);
    for (int j = 0; j < m; ++j) bound[j + 1] += bound[j];
    if (bound[m] > std::numeric_limits<int>::max())
      throw NumericalError("forward substitutions: more than 2^31 entries in L^-1 P B");
    Y.resizeNonZeros(bound[m]);
  }
  int* inner = Y.innerIndexPtr();
  double* value = Y.valuePtr();
  std::vector<Index> end(bound.begin(), bound.end() - 1);  // next free entry of each column

  GramAccumulator W(gram != nullptr ? m : 0);
  std::vector<int> local_row(n, -1), local_column(m, -1);
  std::vector<std::vector<double>> update(S.count);  // a child's rows below it, for its parent
  for (int s = 0; s < S.count; ++s) {
    const std::vector<int>& cols = columns[s];
    const int k = static_cast<int>(cols.size()), h = S.height(s), w = S.width(s);
    if (k == 0) continue;
    const int* rows = S.rows + S.row_start[s];
    for (int a = 0; a < k; ++a) local_column[cols[a]] = a;
    for (int t = 0; t < h; ++t) local_row[rows[t]] = t;

    // The front: B's entries in the supernode and the children's updates.
    std::vector<double> front(static_cast<std::size_t>(h) * k, 0.0);
    auto at = [&](int row, int column) -> double& {
      return front[static_cast<std::size_t>(column) * h + local_row[row]];
    };
    for (int e = E.start[s]; e < E.start[s + 1]; ++e)
      at(E.row[e], local_column[E.column[e]]) += E.value[e];
    for (int c = S.child_start[s]; c < S.child_start[s + 1]; ++c) {
      const int child = S.children[c];
      if (update[child].empty()) continue;
      const int hc = S.height(child), wc = S.width(child);
      const int* child_rows = S.rows + S.row_start[child];
      const double* u = update[child].data();
      for (int j : columns[child]) {
        const int a = local_column[j];
        for (int t = wc; t < hc; ++t) at(child_rows[t], a) += u[t - wc];
        u += hc - wc;
      }
      std::vector<double>().swap(update[child]);
    }

    // Solve with the diagonal block, update the rows below.
    Eigen::Map<Matrix> F(front.data(), h, k);
    const Eigen::Map<const Matrix, 0, Eigen::OuterStride<>> Ls(S.values + S.value_start[s], h, w,
                                                               Eigen::OuterStride<>(h));
    Ls.topRows(w).triangularView<Eigen::Lower>().solveInPlace(F.topRows(w));
    if (h > w) F.bottomRows(h - w).noalias() -= Ls.bottomRows(h - w) * F.topRows(w);

    for (int a = 0; a < k && Y_out != nullptr; ++a) {
      const int j = cols[a];
      for (int t = 0; t < w; ++t)
        if (const double v = F(t, a); v != 0.0) {
          inner[end[j]] = S.first[s] + t;
          value[end[j]++] = v;
        }
    }
    if (gram != nullptr) W.add(F.topRows(w), cols);
    if (S.parent[s] >= 0) {
      update[s].resize(static_cast<std::size_t>(h - w) * k);
      Eigen::Map<Matrix>(update[s].data(), h - w, k) = F.bottomRows(h - w);
    }
    for (int j : cols) local_column[j] = -1;
    for (int t = 0; t < h; ++t) local_row[rows[t]] = -1;
  }

  if (gram != nullptr) *gram = W.finish();
  if (Y_out == nullptr) return;
  // Close the gaps left by the dropped zeros (columns move down, in order).
  int* outer = Y.outerIndexPtr();
  Index filled = 0;
  for (int j = 0; j < m; ++j) {
    const Index begin = bound[j], count = end[j] - begin;
    std::copy(inner + begin, inner + begin + count, inner + filled);
    std::copy(value + begin, value + begin + count, value + filled);
    outer[j] = static_cast<int>(filled);
    filled += count;
  }
  outer[m] = static_cast<int>(filled);
  Y.data().resize(filled);
  Y.data().squeeze();
  *Y_out = std::move(Y);
}

}  // namespace nbm
