#include "measure.hpp"

#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

namespace nbm_bench {

double status_mb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == field + ":") {
      double kb;
      status >> kb;
      return kb / 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0;
}

double heap_mb() {
  const struct mallinfo2 mi = mallinfo2();
  return static_cast<double>(mi.uordblks + mi.hblkhd) / (1024.0 * 1024.0);
}

std::string blas_description() {
  std::set<std::string> libs;
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const size_t slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    const std::string name = path.substr(path.rfind('/') + 1);
    if (name.find("blas") != std::string::npos || name.find("lapack") != std::string::npos)
      libs.insert(path);
  }
  std::string text;
  for (const std::string& lib : libs) text += (text.empty() ? "" : ", ") + lib;
  if (text.empty()) text = "no BLAS library mapped";
  // OpenBLAS's own entry points, when it is the library loaded.
  using Count = int (*)();
  using Config = char* (*)();
  if (auto threads = reinterpret_cast<Count>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"))) {
    text += "; OpenBLAS threads: " + std::to_string(threads());
    if (auto config = reinterpret_cast<Config>(dlsym(RTLD_DEFAULT, "openblas_get_config")))
      text += std::string(" (") + config() + ")";
  } else {
    text += "; not OpenBLAS (single-threaded reference BLAS)";
  }
  const char* env = std::getenv("OPENBLAS_NUM_THREADS");
  text += std::string("; OPENBLAS_NUM_THREADS=") + (env ? env : "unset");
  return text;
}

bool blas_flag(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--blas") == 0) {
      std::printf("%s\n", blas_description().c_str());
      return true;
    }
  benchmark::AddCustomContext("blas", blas_description());
  return false;
}

}  // namespace nbm_bench
