// The MPI ranks the core's parallel parts run on (MUMPS, mumps_inverse.hpp),
// without mpi.h in the core's headers.
#pragma once

#include <string>
#include <vector>

namespace nbm {

/// An MPI communicator as MUMPS takes it: its Fortran handle.
struct MpiCommunicator {
  int fortran_handle;
};
/// MPI_COMM_SELF and MPI_COMM_WORLD. Both start MPI if no one has yet (a
/// plain FreeFem++ run: a singleton MPI process), and close it at exit.
MpiCommunicator mpi_self();
MpiCommunicator mpi_world();
/// This rank and the number of ranks of `comm`.
int mpi_rank(MpiCommunicator comm);
int mpi_size(MpiCommunicator comm);
/// This process's rank in MPI_COMM_WORLD and their number: 0 and 1 if MPI
/// was not started (nothing is started here).
int world_rank();
int world_size();

/// Collective: every rank of `comm` brings a fingerprint of what it is about
/// to hand to a parallel computation (`what`: its name in messages), and
/// learns whether all ranks brought the same; throws InputError on every
/// rank, naming `what` and the ranks that differ, if they did not. Waits for
/// the other ranks at most NBM_MPI_TIMEOUT seconds (environment; default
/// 300): a rank that never comes stopped on an error of its own (or runs
/// another script), and the waiting ranks would hang in the computation, so
/// they print why and abort the job (MPI_Abort). Free with one rank.
void check_same_on_every_rank(MpiCommunicator comm, const std::vector<double>& fingerprint,
                              const std::string& what);

}  // namespace nbm
