// What the benchmark executables measure besides time: memory (peak RSS,
// heap held by solver objects) and which BLAS the process loaded.
#pragma once

#include <string>

namespace nbm_bench {

/// A field of /proc/self/status in MB (VmHWM: peak resident size).
double status_mb(const std::string& field);

/// Heap in use (glibc: small blocks and mmapped ones), in MB. Freed memory is
/// reused without a change of the resident size, so the heap, not the RSS,
/// measures what solver objects hold.
double heap_mb();

/// The BLAS/LAPACK libraries mapped into this process (CHOLMOD's, resolved by
/// Debian's libblas.so.3 / liblapack.so.3 alternatives: scripts/install-deps.sh),
/// OpenBLAS's thread count when it is one of them, and OPENBLAS_NUM_THREADS.
std::string blas_description();

/// Handles `--blas` (prints blas_description() and returns true); otherwise
/// adds it to Google Benchmark's context.
bool blas_flag(int argc, char** argv);

}  // namespace nbm_bench
