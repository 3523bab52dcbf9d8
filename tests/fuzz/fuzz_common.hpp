// Helpers shared by the libFuzzer targets of the nbm core (tests/fuzz).
//
// Policy of every target: the core may reject an input only by throwing
// nbm::InputError or nbm::NumericalError; any other exception, a sanitizer
// report, a hang (libFuzzer -timeout) or a violated property is a failure,
// reported by abort() so that libFuzzer saves the input as a crash artifact.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <limits>
#include <typeinfo>
#include <vector>

#include "base/errors.hpp"

namespace nbm_fuzz {

/// Set by a target to print its input (matrices, vectors) before a failure.
inline std::function<void()>& on_fail() {
  static std::function<void()> f;
  return f;
}

[[noreturn]] inline void fail(const char* fmt, ...) {
  if (on_fail()) on_fail()();
  std::va_list args;
  va_start(args, fmt);
  std::fputs("nbm fuzz: property violated: ", stderr);
  std::vfprintf(stderr, fmt, args);
  std::fputc('\n', stderr);
  va_end(args);
  std::abort();
}

/// Runs f(); the two nbm exception types are accepted (returns false), any
/// other exception aborts. Returns true when f() completed.
template <class F>
bool accepted(F&& f) {
  try {
    f();
    return true;
  } catch (const nbm::InputError&) {
    return false;
  } catch (const nbm::NumericalError&) {
    return false;
  } catch (const std::exception& e) {
    fail("unexpected exception %s: %s", typeid(e).name(), e.what());
  } catch (...) {
    fail("unexpected non-standard exception");
  }
}

/// 10^x with x uniform in [lo, hi] (log-uniform scales).
inline double pow10_in(FuzzedDataProvider& fdp, double lo, double hi) {
  return std::pow(10.0, fdp.ConsumeFloatingPointInRange<double>(lo, hi));
}

/// Uniform in [lo, hi].
inline double uniform(FuzzedDataProvider& fdp, double lo, double hi) {
  return fdp.ConsumeFloatingPointInRange<double>(lo, hi);
}

/// A value that breaks finiteness or scale assumptions.
inline double special(FuzzedDataProvider& fdp) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  static const double values[] = {std::numeric_limits<double>::quiet_NaN(),
                                  kInf,
                                  -kInf,
                                  0.0,
                                  -0.0,
                                  std::numeric_limits<double>::denorm_min(),
                                  std::numeric_limits<double>::min(),
                                  std::numeric_limits<double>::max(),
                                  -std::numeric_limits<double>::max(),
                                  1e300,
                                  -1e300,
                                  1e-300};
  return values[fdp.ConsumeIntegralInRange<std::size_t>(0, std::size(values) - 1)];
}

}  // namespace nbm_fuzz
