// nbm::Model: the discrete structure in unilateral contact -- mass,
// stiffness, damping, fixed dofs, contact nodes, obstacle and the treatment
// of the contact nodes' mass -- built once on the user's dofs and shared by
// the time integrator (api/solver.hpp) and every periodic tool (method.md
// §2). Building it factors nothing a time scheme needs: periodic work starts
// from it without a time step. Free of Eigen and FreeFEM, like solver.hpp.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "linalg/coo_matrix.hpp"
#include "linalg/sparse_solver.hpp"

namespace nbm {

class ContactProblem;
struct Damping;

/// A function of time, w(t) = offset + rate t + accel t^2 / 2
/// + sum_j (c_j cos(omega_j t) + s_j sin(omega_j t)); `harmonics` holds the
/// triples (omega_j, c_j, s_j).
struct TimeLawDescription {
  double offset = 0, rate = 0, accel = 0;
  std::vector<double> harmonics;
};

/// A rigid obstacle held exactly: each step enforces phi(x + u, t) >= 0 at
/// every contact node with the normal taken where the node is (method.md
/// §10). Needs mass "redistributed" (every component of the contact nodes
/// massless) and scheme "newmark".
struct ObstacleDescription {
  /// "plane", "circle" (2D), "sphere" (3D), "cylinder" (3D) or "distance" (a
  /// signed distance given as a function, `distance` below).
  std::string kind;
  /// A point of the plane, the centre, or a point of the cylinder's axis; for
  /// "distance", any point (it gives the dimension and the default pivot).
  std::vector<double> point;
  /// The plane's normal (out of the obstacle, towards the body), or the
  /// cylinder's axis; normalised.
  std::vector<double> axis;
  double radius = 0;  ///< circle, sphere, cylinder
  /// "outside" (the body outside the round obstacle) or "inside" (a casing).
  std::string side = "outside";
  /// Motion: a translation by translation(t) along `direction` (for a plane:
  /// along its normal, `direction` not used), and for round obstacles a
  /// change of radius radius_change(t).
  std::vector<double> direction;
  TimeLawDescription translation, radius_change;
  /// A rotation of the whole obstacle (its own motion included) by the angle
  /// rotation(t), radians, counter-clockwise about `rotation_axis` (3D; empty
  /// in 2D) through `pivot` (default: `point`); none if not given.
  std::optional<TimeLawDescription> rotation;
  std::vector<double> pivot, rotation_axis;
  /// kind "distance": phi(x, t) (x has point.size() coordinates), positive
  /// where the body is and zero on the obstacle's surface, a signed distance
  /// or any smooth function with the same zero set and a nonzero gradient
  /// there. Its gradient and its rate d phi / dt are central differences of
  /// steps fd_step * max(1, |x|_inf) and fd_step * max(1, |t|); `moving` says
  /// whether phi depends on t.
  std::function<double(const double* x, double t)> distance;
  bool moving = false;
  double fd_step = 1e-5;
};

/// Throws InputError naming the field if `obstacle` does not describe an
/// obstacle (unknown kind or side, wrong sizes, zero axis, non-finite or
/// negative radius, malformed time laws).
void check_obstacle(const ObstacleDescription& obstacle);
/// phi(x, t) of the obstacle: the signed distance of the point x at time t.
double obstacle_distance(const ObstacleDescription& obstacle, const std::vector<double>& x,
                         double t);

/// Contact nodes: node k owns dofs[k*d .. k*d+d-1] with normal components
/// normals[k*d ..] and gap gaps[k] (method.md §2, §7).
struct ContactDescription {
  std::vector<long> dofs;
  std::vector<double> normals;
  std::vector<double> gaps;
};

/// How the contact dofs' mass is treated (method.md §4).
enum class MassTreatment {
  kConsistent,     ///< the paper's NBM: the contact nodes keep their mass
  kRedistributed,  ///< massless boundary: their mass moved to interior dofs
};
/// The name front ends and messages use: "consistent", "redistributed".
const char* name(MassTreatment mass);

struct ModelOptions {
  /// Dirichlet dofs (held at zero; any order, repeats allowed). They are the
  /// only Dirichlet conditions the core knows: their rows and columns of M
  /// and K are ignored. A front end translates its own conventions into this
  /// list (the FreeFEM binding adds the dofs of on()'s tgv penalty,
  /// plugin/freefem/dirichlet.hpp); a huge diagonal on a dof not listed here
  /// is just a stiff (or heavy) entry.
  std::vector<long> fixed;
  /// Consistent (the paper's NBM) or redistributed (massless boundary,
  /// method.md §4: energy conserving; implicit schemes only).
  /// Redistribution needs `positions`: for every dof the d coordinates of
  /// its node, dof-major (size n_dofs * d, d = 1..3).
  MassTreatment mass = MassTreatment::kConsistent;
  std::vector<double> positions;
  /// Viscous damping (method.md §9), C = rayleigh_mass M + rayleigh_stiffness K
  /// + damping: Rayleigh coefficients (finite, >= 0; M the scheme's mass:
  /// redistributed with mass "redistributed", lumped with scheme
  /// "explicit") and a matrix assembled like M and K (n_dofs x n_dofs,
  /// symmetric, nonnegative diagonal; rows = 0: none). Scheme "explicit"
  /// takes only rayleigh_mass; with mass "redistributed" the matrix must not
  /// couple the contact dofs.
  double rayleigh_mass = 0, rayleigh_stiffness = 0;
  CooMatrix damping;
  /// The obstacle held exactly with a contact frame that follows the body
  /// (method.md §10); the contact description then gives only the contact
  /// nodes (its normals and gaps are checked but not used: the obstacle
  /// replaces them). Needs mass "redistributed".
  std::optional<ObstacleDescription> obstacle;
  /// The library that factors the sparse matrices of the time integration
  /// (the iteration matrix, the mass at a start): kCholmod in this process,
  /// or kMumps on every rank of MPI_COMM_WORLD (method.md §4). The periodic
  /// tools do not use it.
  SparseSolver solver = SparseSolver::kCholmod;

  bool damped() const { return rayleigh_mass != 0 || rayleigh_stiffness != 0 || damping.rows != 0; }
};

struct ObstacleHarmonics;

class Model {
 public:
  /// Validates everything (throws InputError naming the faulty argument) and
  /// builds the contact problem in internal coordinates (method.md §2, §7):
  /// fixed dofs removed, contact nodes rotated, the mass redistributed for
  /// mass "redistributed" (§4).
  Model(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
        const ModelOptions& options);
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  long n_dofs() const;
  long n_contact() const;
  const ModelOptions& options() const;
  /// Fixed dofs: the `fixed` option, sorted, without repeats.
  const std::vector<long>& fixed_dofs() const;
  bool massless_boundary() const;
  /// The contact problem in internal coordinates (time steppers and
  /// periodic-orbit solvers).
  const ContactProblem& problem() const;
  /// The same structure with another contact description (re-linearisation,
  /// Solver::replace_contacts), built from the matrices as given, so that a
  /// model built from scratch with that description is the same bit for bit.
  std::shared_ptr<const Model> with_contacts(const ContactDescription& contact) const;
  /// The model of the periodic tools for a model with the option `obstacle`:
  /// the same contact nodes with the obstacle linearised at the reference
  /// configuration (method.md §8), normal n_k = -grad phi / |grad phi| at x_k
  /// and gap phi(x_k) / |grad phi| along it, and the option dropped (their
  /// exact flow needs fixed normals; exact for a plane). Throws InputError
  /// if the model has no obstacle, or one that moves.
  std::shared_ptr<const Model> with_obstacle_linearised() const;
  /// True if the option `obstacle` moves by its own law.
  bool obstacle_moves() const;
  /// The same for a forced orbit at the excitation frequency omega with an
  /// obstacle that moves: the normals at t = 0, the model's gaps the mean of
  /// g_k(t) = phi(x_k, t) / |grad phi(x_k, t)| over the period 2 pi / omega
  /// and its harmonics k omega (method.md §9's gap harmonics). Throws
  /// InputError if the model has no obstacle or its gaps are not periodic
  /// with that period (to 1e-9 of their size, within 63 harmonics).
  ObstacleHarmonics with_obstacle_harmonics(double omega) const;

  struct Data;  ///< api/model_data.hpp: what the time integrator reads
  const Data& data() const { return *data_; }

 private:
  explicit Model(std::unique_ptr<Data> data);
  /// A copy with the contact description `contact`, built from the
  /// matrices as given, with or without the option obstacle.
  std::shared_ptr<const Model> rebuilt(const ContactDescription& contact, bool keep_obstacle) const;
  std::unique_ptr<Data> data_;
};

/// A model whose moving obstacle is linearised for a forced orbit
/// (Model::with_obstacle_harmonics): gap_cos[k], gap_sin[k] hold harmonic
/// k + 1 of every contact node's gap, as ForcedOrbitOptions' gap_cos, gap_sin.
struct ObstacleHarmonics {
  std::shared_ptr<const Model> model;
  std::vector<std::vector<double>> gap_cos, gap_sin;
};

}  // namespace nbm
