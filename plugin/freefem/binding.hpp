// Shared pieces of the FreeFEM binding (nbm_plugin.cpp, orbit_functions.cpp):
// the script-side handle of the NBM object and the conversions and error
// handling every function uses. Only the binding sees FreeFEM headers.
#pragma once

#include <exception>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include "api/model.hpp"
#include "api/solver.hpp"
#include "periodic/user_orbit.hpp"

using namespace Fem2D;

namespace nbm_binding {

// The script-side model (NBMModel Mo(M, K, cdofs, normals, gaps, ...)): the
// structure, shared with the NBM objects built from it, the two last
// periodic orbits computed on it (continuation steps from them) and the
// orbits of its last backbone or response curve (nbmSelectOrbit). Every
// periodic call takes one; an NBM object passes as its model (a FreeFEM
// cast, nbm_plugin.cpp).
struct ModelHandle {
  using Curve = std::shared_ptr<const nbm::OrbitSequence>;
  std::shared_ptr<const nbm::Model>* model;  // null until constructed
  // The periodic tools' model of one with obstacle= (its obstacle
  // linearised: periodic_model_of), made at the first periodic call.
  std::shared_ptr<const nbm::Model>* linearised;
  nbm::OrbitReport* orbit;     // the last periodic orbit (orbit_functions.cpp)
  nbm::OrbitReport* previous;  // the one before
  Curve* curve;                // the last backbone's or response curve's orbits
  Curve* doubled;              // its period-doubled branch's (doubling = true)
  void init() {
    model = nullptr;
    linearised = nullptr;
    orbit = nullptr;
    previous = nullptr;
    curve = doubled = nullptr;
  }
  /// Drops the orbits (they refer to the model's contact problem).
  void forget_orbits() {
    delete orbit;
    delete previous;
    orbit = previous = nullptr;
    set_curve(nullptr, nullptr);
  }
  /// Makes `r` the last orbit; the last one becomes the previous one.
  void remember(nbm::OrbitReport&& r) {
    delete previous;
    previous = orbit;
    orbit = new nbm::OrbitReport(std::move(r));
  }
  /// Makes orbit k of `c` the last orbit and orbit k - 1 the previous one
  /// (none for k = 0): nbmContinueOrbit goes on along a backbone from there.
  void select(const nbm::OrbitSequence& c, std::size_t k) {
    if (k > 0) remember(c.report(k - 1));
    remember(c.report(k));
    if (k == 0) {
      delete previous;
      previous = nullptr;
    }
  }
  /// The orbits nbmSelectOrbit picks from (null: none).
  void set_curve(Curve c, Curve d) {
    delete curve;
    delete doubled;
    curve = c ? new Curve(std::move(c)) : nullptr;
    doubled = d ? new Curve(std::move(d)) : nullptr;
  }
  /// Makes `m` the model of the handle; the orbits of the last one go.
  void set_model(std::shared_ptr<const nbm::Model> m) {
    forget_orbits();
    delete linearised;
    linearised = nullptr;
    delete model;
    model = new std::shared_ptr<const nbm::Model>(std::move(m));
  }
  void destroy() {
    forget_orbits();
    delete linearised;
    delete model;
    init();
  }
};

// The script-side time integrator (NBM S(Mo, dt=...) or the shorthand
// NBM S(M, K, cdofs, normals, gaps, dt=...)): a model and its solver.
struct NbmHandle : ModelHandle {
  nbm::Solver* solver;
  // Nodes outside the contact set inside the obstacle (obstacle=): the last
  // step's count, whether a message was printed, and crossings = "error".
  long crossings;
  bool crossings_reported, crossings_fatal;
  void init() {
    ModelHandle::init();
    solver = nullptr;
    crossings = 0;
    crossings_reported = crossings_fatal = false;
  }
  void destroy() {
    ModelHandle::destroy();  // the orbits refer to the model: go first
    delete solver;
    init();
  }
};

// The script-side obstacle (NBMObstacle O(kind, point, ...)): a description
// the NBM constructor's obstacle= hands to the core (method.md §10).
struct ObstacleHandle {
  nbm::ObstacleDescription* description;
  void init() { description = nullptr; }
  void destroy() {
    delete description;
    init();
  }
};

[[noreturn]] inline void fail(const std::string& what) { ExecError("nbm: " + what); throw 0; }

// The value of a string option: the one of `choices` whose name (the core's
// nbm::name) it is; anything else fails naming the option and the choices.
// The core's options are typed: option strings exist only here.
template <class E>
E choice_of(const std::string& value, const char* function, const char* option,
            std::initializer_list<E> choices) {
  std::string expected;
  std::size_t k = 0;
  for (E c : choices) {
    if (value == nbm::name(c)) return c;
    expected += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ");
    expected += std::string("\"") + nbm::name(c) + "\"";
    ++k;
  }
  fail(std::string(function) + ": " + option + ": \"" + value + "\", expected " + expected);
}

// Runs f, turning core exceptions into ExecError with their message.
template <class F>
auto guarded(const char* function, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::exception& e) {
    fail(std::string(function) + ": " + e.what());
  }
}

inline nbm::Solver& solver_of(NbmHandle* h, const char* function) {
  if (!h || !h->solver)
    fail(std::string(function) + ": the NBM object was not constructed (declare it as "
         "NBM S(Mo, dt=...) on an NBMModel Mo, or NBM S(M, K, cdofs, normals, gaps, dt=...))");
  return *h->solver;
}

inline const nbm::Model& model_of(ModelHandle* h, const char* function) {
  if (!h || !h->model)
    fail(std::string(function) + ": the model was not constructed (an NBMModel or NBM "
         "declared without arguments; construct it as NBMModel Mo(M, K, cdofs, normals, gaps, "
         "...) or NBM S(...))");
  return **h->model;
}

/// The model of a periodic call: one whose contact nodes have fixed normals
/// and gaps. A model with obstacle= gives its obstacle linearised at the
/// reference configuration (Model::with_obstacle_linearised, which refuses
/// one that moves), made once and kept with the handle, whose orbits refer
/// to it.
inline const nbm::Model& periodic_model_of(ModelHandle* h, const char* function) {
  const nbm::Model& m = model_of(h, function);
  if (!m.options().obstacle) return m;
  // One that moves is refused here (the handle may hold the linearisation
  // of a forced orbit's, made for its frequency: orbit_functions.cpp).
  if (!h->linearised || m.obstacle_moves())
    h->linearised = new std::shared_ptr<const nbm::Model>(
        guarded(function, [&] { return m.with_obstacle_linearised(); }));
  return **h->linearised;
}

inline nbm::CooMatrix coo_of(Matrice_Creuse<double>* A, const char* function, const char* name) {
  if (!A || !A->pHM())
    fail(std::string(function) + ": matrix " + name +
         " is empty or not an assembled sparse matrix");
  const HashMatrix<int, double>& H = *A->pHM();
  nbm::CooMatrix coo;
  coo.rows = H.n;
  coo.cols = H.m;
  coo.lower_half = H.half != 0;
  coo.i.resize(H.nnz);
  coo.j.resize(H.nnz);
  coo.value.resize(H.nnz);
  const int base = H.fortran;
  for (size_t k = 0; k < H.nnz; ++k) {
    coo.i[k] = H.i[k] - base;
    coo.j[k] = H.j[k] - base;
    coo.value[k] = H.aij[k];
  }
  return coo;
}

template <class T, class K>
std::vector<T> vector_of(KN<K>* x, const char* function, const char* name) {
  if (!x) fail(std::string(function) + ": array " + name + " is missing");
  std::vector<T> v(x->N());
  for (long i = 0; i < x->N(); ++i) v[i] = static_cast<T>((*x)[i]);
  return v;
}

template <class K, class T>
void assign(KN<K>* x, const std::vector<T>& v) {
  if (x->N() != static_cast<long>(v.size())) x->resize(v.size());
  for (long i = 0; i < static_cast<long>(v.size()); ++i) (*x)[i] = static_cast<K>(v[i]);
}

/// Registers the periodic-orbit functions (orbit_functions.cpp).
void load_orbit_functions();
/// Registers nbmBackbone (backbone_functions.cpp).
void load_backbone_functions();
/// Registers the NBMObstacle type (obstacle_functions.cpp).
void load_obstacle_functions();

}  // namespace nbm_binding
