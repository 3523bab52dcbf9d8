#include "linalg/mpi_ranks.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "base/errors.hpp"

namespace nbm {
namespace {

void ensure_mpi() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return;
  MPI_Init(nullptr, nullptr);
  // Ours to close: at exit, unless someone did.
  std::atexit([] {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  });
}

MPI_Comm c_comm(MpiCommunicator comm) { return MPI_Comm_f2c(comm.fortran_handle); }

MpiCommunicator handle(MPI_Comm comm) { return {static_cast<int>(MPI_Comm_c2f(comm))}; }

bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

// NBM_MPI_TIMEOUT, seconds (positive), or the default.
double timeout_seconds() {
  const char* value = std::getenv("NBM_MPI_TIMEOUT");
  if (value != nullptr) {
    char* end = nullptr;
    const double t = std::strtod(value, &end);
    if (end != value && *end == '\0' && t > 0) return t;
  }
  return 300;
}

// x <- the elementwise maximum of x over the ranks, or MPI_Abort if a rank
// does not join within the timeout (non-blocking, polled: a blocking
// reduction would wait for ever).
void max_over_ranks(MPI_Comm comm, std::vector<double>& x, const std::string& what) {
  std::vector<double> result(x.size());
  MPI_Request request;
  MPI_Iallreduce(x.data(), result.data(), static_cast<int>(x.size()), MPI_DOUBLE, MPI_MAX, comm,
                 &request);
  const auto start = std::chrono::steady_clock::now();
  const double timeout = timeout_seconds();
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - start;
    if (waited.count() > timeout) {
      int rank = 0;
      MPI_Comm_rank(comm, &rank);
      std::fprintf(stderr,
                   "nbm: MPI rank %d waited %g s for the other ranks at %s: a rank stopped "
                   "before it (see its error) or runs another script; aborting the job "
                   "(NBM_MPI_TIMEOUT sets the wait)\n",
                   rank, timeout, what.c_str());
      std::fflush(stderr);
      MPI_Abort(comm, 1);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  x.swap(result);
}

}  // namespace

void check_same_on_every_rank(MpiCommunicator comm, const std::vector<double>& fingerprint,
                              const std::string& what) {
  const MPI_Comm c = c_comm(comm);
  int size = 1, rank = 0;
  MPI_Comm_size(c, &size);
  if (size == 1) return;
  MPI_Comm_rank(c, &rank);
  // max(f) and max(-f) = -min(f) in one reduction; the ranks agree if
  // max = min for every entry (bit for bit: they compute alike).
  const std::size_t m = fingerprint.size();
  std::vector<double> bounds(2 * m);
  for (std::size_t i = 0; i < m; ++i) {
    bounds[i] = fingerprint[i];
    bounds[m + i] = -fingerprint[i];
  }
  max_over_ranks(c, bounds, what);
  bool same = true;
  for (std::size_t i = 0; i < m; ++i) same = same && bounds[i] == -bounds[m + i];
  if (same) return;
  // Which ranks differ from rank 0: rank 0's fingerprint to all, then the
  // ranks that differ (a flag per rank).
  std::vector<double> host(fingerprint);
  MPI_Bcast(host.data(), static_cast<int>(m), MPI_DOUBLE, 0, c);
  std::vector<double> differs(static_cast<std::size_t>(size), 0.0);
  differs[static_cast<std::size_t>(rank)] = host == fingerprint ? 0.0 : 1.0;
  max_over_ranks(c, differs, what);
  std::string ranks;
  int count = 0;
  for (int r = 0; r < size; ++r)
    if (differs[static_cast<std::size_t>(r)] != 0)
      ranks += (count++ == 0 ? "" : ", ") + std::to_string(r);
  throw InputError(what + " differs between MPI ranks (rank" + (count == 1 ? " " : "s ") + ranks +
                   " against rank 0): every rank must pass the same arguments");
}

MpiCommunicator mpi_self() {
  ensure_mpi();
  return handle(MPI_COMM_SELF);
}

MpiCommunicator mpi_world() {
  ensure_mpi();
  return handle(MPI_COMM_WORLD);
}

int mpi_rank(MpiCommunicator comm) {
  int rank = 0;
  MPI_Comm_rank(c_comm(comm), &rank);
  return rank;
}

int mpi_size(MpiCommunicator comm) {
  int size = 1;
  MPI_Comm_size(c_comm(comm), &size);
  return size;
}

int world_rank() { return mpi_running() ? mpi_rank(handle(MPI_COMM_WORLD)) : 0; }
int world_size() { return mpi_running() ? mpi_size(handle(MPI_COMM_WORLD)) : 1; }

}  // namespace nbm
