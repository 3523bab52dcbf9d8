#include "api/model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "api/model_data.hpp"
#include "base/errors.hpp"
#include "linalg/sparse_input.hpp"

namespace nbm {
namespace {

std::vector<Index> to_index(const std::vector<long>& v) { return {v.begin(), v.end()}; }

Vector vector_of(const std::vector<double>& x) { return Eigen::Map<const Vector>(x.data(), x.size()); }

// Checks the options that concern the model alone: the mass treatment and
// what goes with it.
void check_options(const ModelOptions& options) {
  if (options.mass == MassTreatment::kRedistributed) return;
  if (!options.positions.empty())
    throw InputError("positions: given with mass = \"consistent\"; they are used only by "
                     "mass = \"redistributed\"");
  if (options.obstacle)
    throw InputError("obstacle: needs mass = \"redistributed\" and scheme \"newmark\" (the "
                     "contact frame follows the body only with massless contact nodes)");
}

TimeLaw time_law(const TimeLawDescription& d, const std::string& who) {
  if (d.harmonics.size() % 3 != 0)
    throw InputError(who + ": " + std::to_string(d.harmonics.size()) +
                     " harmonic coefficients, expected triples (omega, cos, sin)");
  TimeLaw law;
  law.offset = d.offset, law.rate = d.rate, law.accel = d.accel;
  for (std::size_t j = 0; j < d.harmonics.size(); j += 3)
    law.harmonics.push_back({d.harmonics[j], d.harmonics[j + 1], d.harmonics[j + 2]});
  return law;
}

// A script's phi as an obstacle: its gradient and rate by central differences
// (ObstacleDescription::distance).
std::unique_ptr<RigidObstacle> distance_obstacle(const ObstacleDescription& d) {
  const int dim = static_cast<int>(d.point.size());
  if (dim < 1 || dim > 3)
    throw InputError("obstacle point: " + std::to_string(dim) +
                     " coordinates, expected 1, 2 or 3 (they give a distance's dimension)");
  if (!d.distance) throw InputError("obstacle distance: no function given for kind \"distance\"");
  if (!(std::isfinite(d.fd_step) && d.fd_step > 0 && d.fd_step < 0.1))
    throw InputError("obstacle fdStep: " + std::to_string(d.fd_step) +
                     ", expected 0 < fdStep < 0.1 (the relative step of the differences)");
  const double at_point = d.distance(d.point.data(), 0.0);
  if (!std::isfinite(at_point))
    throw InputError("obstacle distance: phi at the point given is " + std::to_string(at_point) +
                     " at t = 0, expected a finite value");
  const auto phi = d.distance;
  const double h0 = d.fd_step;
  const bool moving = d.moving;
  DistanceFunction f = [phi, h0, moving, dim](const double* x, double t) {
    ObstaclePoint p;
    p.phi = phi(x, t);
    double scale = 1;
    for (int i = 0; i < dim; ++i) scale = std::max(scale, std::abs(x[i]));
    const double h = h0 * scale;
    double y[3] = {0, 0, 0};
    for (int i = 0; i < dim; ++i) y[i] = x[i];
    for (int i = 0; i < dim; ++i) {
      y[i] = x[i] + h;
      const double plus = phi(y, t);
      y[i] = x[i] - h;
      const double minus = phi(y, t);
      y[i] = x[i];
      p.grad(i) = (plus - minus) / (2 * h);
    }
    if (moving) {
      const double tau = h0 * std::max(1.0, std::abs(t));
      p.phi_t = (phi(x, t + tau) - phi(x, t - tau)) / (2 * tau);
    }
    return p;
  };
  return make_distance_obstacle(dim, std::move(f), moving,
                                std::string("the script's signed distance") +
                                    (moving ? " (moving)" : ""));
}

// The obstacle's shape with its own motion (translation, radius change).
std::unique_ptr<RigidObstacle> shape_of(const ObstacleDescription& d) {
  Side side = Side::kOutside;
  if (d.side == "inside")
    side = Side::kInside;
  else if (d.side != "outside")
    throw InputError("obstacle side: \"" + d.side + "\", expected \"outside\" or \"inside\"");
  const TimeLaw move = time_law(d.translation, "obstacle translation");
  const TimeLaw grow = time_law(d.radius_change, "obstacle radius change");
  const bool grows = !grow.constant() || grow.offset != 0;
  if (d.kind == "distance") {
    if (grows || !move.constant() || move.offset != 0 || d.radius != 0 || !d.axis.empty() ||
        !d.direction.empty() || side == Side::kInside)
      throw InputError("obstacle distance: translation, radius, radiusChange, axis, direction or "
                       "side given with kind \"distance\", whose expression gives the shape and "
                       "the motion (time =)");
    return distance_obstacle(d);
  }
  if (d.distance)
    throw InputError("obstacle distance: a function given with kind \"" + d.kind +
                     "\" (it is used by kind \"distance\" only)");
  if (d.kind == "plane") {
    // What a plane has no use for is refused rather than ignored.
    if (grows) throw InputError("obstacle radius change: given for a plane, which has no radius");
    if (d.radius != 0) throw InputError("obstacle radius: given for a plane, which has none");
    if (side == Side::kInside)
      throw InputError("obstacle side: \"inside\" given for a plane, whose body side is where "
                       "its normal (axis) points");
    if (!d.direction.empty())
      throw InputError("obstacle direction: given for a plane, which moves along its normal");
    return make_plane(vector_of(d.point), vector_of(d.axis), move);
  }
  if ((d.kind == "circle" || d.kind == "sphere") && !d.axis.empty())
    throw InputError("obstacle axis: given for a " + d.kind + ", which has none (a cylinder's "
                     "axis, a plane's normal)");
  if (d.kind == "circle" || d.kind == "sphere") {
    const std::size_t dim = d.kind == "circle" ? 2 : 3;
    if (d.point.size() != dim)
      throw InputError("obstacle point: " + std::to_string(d.point.size()) + " coordinates, a " +
                       d.kind + " expects " + std::to_string(dim));
    return make_ball(vector_of(d.point), d.radius, side, vector_of(d.direction), move, grow);
  }
  if (d.kind == "cylinder")
    return make_cylinder(vector_of(d.point), vector_of(d.axis), d.radius, side,
                         vector_of(d.direction), move, grow);
  throw InputError("obstacle kind: \"" + d.kind +
                   "\", expected \"plane\", \"circle\", \"sphere\", \"cylinder\" or \"distance\"");
}

// The core's obstacle for the option `obstacle` (method.md §10): the shape,
// turned as a whole if it rotates.
std::shared_ptr<const RigidObstacle> make_obstacle(const ObstacleDescription& d) {
  std::unique_ptr<RigidObstacle> shape = shape_of(d);
  if (!d.rotation) {
    if (!d.pivot.empty() || !d.rotation_axis.empty())
      throw InputError(std::string("obstacle ") + (d.pivot.empty() ? "rotationAxis" : "pivot") +
                       ": given without a rotation (rotation = [theta0, omega, ...])");
    return shape;
  }
  const TimeLaw angle = time_law(*d.rotation, "obstacle rotation");
  return make_rotating(std::move(shape), vector_of(d.pivot.empty() ? d.point : d.pivot),
                       vector_of(d.rotation_axis), angle);
}

// The node coordinates of mass = "redistributed", one row per dof.
Matrix positions_of(const ModelOptions& options, Index n) {
  const long n_pos = static_cast<long>(options.positions.size());
  if (n_pos == 0 || n_pos % n != 0 || n_pos / n > 3)
    throw InputError("positions: size " + std::to_string(n_pos) +
                     ", expected 1, 2 or 3 coordinates per dof (n_dofs = " + std::to_string(n) +
                     ") with mass = \"redistributed\"");
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      options.positions.data(), n, n_pos / n);
}

// The contact problem of `contact` on the model's matrices, fixed dofs,
// positions and obstacle (data complete but for the problem).
std::unique_ptr<ContactProblem> contact_problem(const Model::Data& data,
                                                const ContactDescription& contact) {
  const Index n = data.K_user.rows();
  if (contact.gaps.empty())
    throw InputError("contact set is empty: expected at least one contact node (gaps)");
  const std::vector<Index> fixed = to_index(data.fixed);
  ContactSet contacts(n, to_index(contact.dofs), contact.normals, vector_of(contact.gaps), fixed);
  if (data.obstacle) {
    // The contact nodes (checked as given) in the user's axes: the contact
    // frame follows the body (method.md §10).
    if (data.positions.cols() != contacts.dim())
      throw InputError("positions: " + std::to_string(data.positions.cols()) +
                       " coordinates per dof, expected " + std::to_string(contacts.dim()) +
                       " (the dofs per contact node)");
    std::vector<Index> dofs;
    for (Index k = 0; k < contacts.size(); ++k)
      for (int j = 0; j < contacts.dim(); ++j) dofs.push_back(contacts.dof(k, j));
    return std::make_unique<ContactProblem>(
        data.M_user, data.K_user, ContactSet::in_user_axes(n, std::move(dofs), contacts.dim(), fixed),
        fixed);
  }
  if (data.positions.size() != 0)
    return std::make_unique<ContactProblem>(data.M_user, data.K_user, std::move(contacts), fixed,
                                            &data.positions);
  return std::make_unique<ContactProblem>(data.M_user, data.K_user, std::move(contacts), fixed);
}

// Completes `data` with the problem of `contact` and the damping in its
// coordinates.
void build_problem(Model::Data& data, const ContactDescription& contact) {
  data.problem = contact_problem(data, contact);
  data.problem->set_factorizer(SparseFactorizer(data.options.solver));
  data.damping = data.damping_user;
  if (data.damping.has_matrix() && !data.obstacle)
    data.damping.C_user = data.problem->to_internal(data.damping_user.C_user);
}

}  // namespace

const char* name(MassTreatment mass) {
  return mass == MassTreatment::kRedistributed ? "redistributed" : "consistent";
}

void check_obstacle(const ObstacleDescription& obstacle) { make_obstacle(obstacle); }

double obstacle_distance(const ObstacleDescription& obstacle, const std::vector<double>& x,
                         double t) {
  const auto o = make_obstacle(obstacle);
  if (static_cast<int>(x.size()) != o->dim())
    throw InputError("x: " + std::to_string(x.size()) + " coordinates, expected " +
                     std::to_string(o->dim()) + " (the obstacle's dimension)");
  return o->at(x.data(), t).phi;
}

Model::Model(const CooMatrix& M, const CooMatrix& K, const ContactDescription& contact,
             const ModelOptions& options)
    : data_(std::make_unique<Data>()) {
  check_options(options);
  Data& d = *data_;
  d.options = options;
  d.K_user = to_sparse(K, "K");
  d.M_user = to_sparse(M, "M");
  if (d.M_user.rows() != d.K_user.rows() || d.M_user.cols() != d.K_user.cols())
    throw InputError("M: size " + std::to_string(d.M_user.rows()) + "x" +
                     std::to_string(d.M_user.cols()) + " differs from the size of K, " +
                     std::to_string(d.K_user.rows()) + "x" + std::to_string(d.K_user.cols()));
  // Range errors of `fixed` are reported by ContactSet.
  d.fixed = options.fixed;
  std::sort(d.fixed.begin(), d.fixed.end());
  d.fixed.erase(std::unique(d.fixed.begin(), d.fixed.end()), d.fixed.end());
  d.damping_user.a_M = options.rayleigh_mass;
  d.damping_user.b_K = options.rayleigh_stiffness;
  if (options.damping.rows != 0 || options.damping.cols != 0 || !options.damping.value.empty())
    d.damping_user.C_user = to_sparse(options.damping, "damping matrix");
  check_damping(d.damping_user, d.K_user.rows());
  if (options.obstacle) d.obstacle = make_obstacle(*options.obstacle);
  if (options.mass == MassTreatment::kRedistributed) {
    if (contact.gaps.empty())
      throw InputError("contact set is empty: expected at least one contact node (gaps)");
    d.positions = positions_of(options, d.K_user.rows());
  }
  build_problem(d, contact);
}

Model::Model(std::unique_ptr<Data> data) : data_(std::move(data)) {}
Model::~Model() = default;

std::shared_ptr<const Model> Model::with_contacts(const ContactDescription& contact) const {
  return rebuilt(contact, true);
}

std::shared_ptr<const Model> Model::rebuilt(const ContactDescription& contact,
                                            bool keep_obstacle) const {
  auto d = std::make_unique<Data>();
  const Data& mine = *data_;
  d->options = mine.options;
  if (!keep_obstacle) d->options.obstacle.reset();
  d->fixed = mine.fixed;
  d->M_user = mine.M_user;
  d->K_user = mine.K_user;
  d->damping_user = mine.damping_user;
  d->positions = mine.positions;
  if (keep_obstacle) d->obstacle = mine.obstacle;
  build_problem(*d, contact);
  return std::shared_ptr<const Model>(new Model(std::move(d)));
}

namespace {

// The contact nodes of a model with obstacle= and their reference
// positions x_k (the nodes' d dofs in the user's axes, contact_problem).
struct ObstacleNodes {
  std::vector<long> dofs;
  std::vector<Eigen::Vector3d> x;
  int d = 0;
};

ObstacleNodes obstacle_nodes(const Model::Data& data) {
  const ContactSet& nodes = data.problem->contacts();
  ObstacleNodes out;
  out.d = nodes.dim();
  for (Index k = 0; k < nodes.size(); ++k) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int j = 0; j < out.d; ++j) {
      out.dofs.push_back(static_cast<long>(nodes.dof(k, j)));
      x(j) = data.positions(nodes.dof(k, j), j);
    }
    out.x.push_back(x);
  }
  return out;
}

// The obstacle at time t at each node: the unit normal -grad phi / |grad phi|
// (into `normals`, if given) and the gap phi / |grad phi| along it.
std::vector<double> obstacle_gaps(const RigidObstacle& o, const ObstacleNodes& nodes, double t,
                                  std::vector<double>* normals) {
  std::vector<double> gaps;
  for (std::size_t k = 0; k < nodes.x.size(); ++k) {
    const ObstaclePoint p = o.at(nodes.x[k].data(), t);
    const double g = p.grad.norm();
    if (!(g > 0) || !std::isfinite(p.phi))
      throw InputError("obstacle: no normal at contact node " + std::to_string(k) +
                       " (zero or non-finite gradient of " + o.describe() + ")");
    if (normals)
      for (int j = 0; j < nodes.d; ++j) normals->push_back(-p.grad(j) / g);
    gaps.push_back(p.phi / g);
  }
  return gaps;
}

// Signals sampled at N equidistant times of a period (a row per sample, a
// column per signal): their mean and harmonics h = 1..H by the discrete
// Fourier sums (exact for h < N / 2), H the highest harmonic above the
// round-off of the sums (1e-13 of the samples' size); rows h - 1 of cos, sin.
struct FourierSums {
  Vector mean;
  Matrix cos, sin;
  /// Signal k's series at the phase a = omega t.
  double at(Index k, double a) const {
    double value = mean(k);
    for (Index h = 1; h <= cos.rows(); ++h)
      value += cos(h - 1, k) * std::cos(h * a) + sin(h - 1, k) * std::sin(h * a);
    return value;
  }
};

FourierSums fourier_sums(const Matrix& g) {
  const Index N = g.rows(), H = N / 2 - 1;
  FourierSums f;
  f.mean = g.colwise().mean().transpose();
  Matrix c = Matrix::Zero(H, g.cols()), s = Matrix::Zero(H, g.cols());
  const double pi = std::acos(-1.0);
  for (Index h = 1; h <= H; ++h)
    for (Index j = 0; j < N; ++j) {
      const double a = 2 * pi * h * j / N;
      c.row(h - 1) += (2.0 / N) * std::cos(a) * g.row(j);
      s.row(h - 1) += (2.0 / N) * std::sin(a) * g.row(j);
    }
  const double scale = std::max(g.cwiseAbs().maxCoeff(), 1e-300);
  Index last = 0;
  for (Index h = 1; h <= H; ++h)
    if (c.row(h - 1).cwiseAbs().maxCoeff() > 1e-13 * scale ||
        s.row(h - 1).cwiseAbs().maxCoeff() > 1e-13 * scale)
      last = h;
  f.cos = c.topRows(last);
  f.sin = s.topRows(last);
  return f;
}

}  // namespace

bool Model::obstacle_moves() const { return data_->obstacle && !data_->obstacle->fixed(); }

std::shared_ptr<const Model> Model::with_obstacle_linearised() const {
  const Data& mine = *data_;
  if (!mine.obstacle) throw InputError("obstacle: the model has none to linearise (no obstacle=)");
  const RigidObstacle& o = *mine.obstacle;
  if (!o.fixed())
    throw InputError("obstacle: " + o.describe() +
                     " moves by its own law, which the periodic tools take only in a forced "
                     "orbit (nbmForcedOrbit) whose excitation period is the law's; elsewhere give "
                     "its motion as the gap harmonics gapCos, gapSin on a model without obstacle=");
  const ObstacleNodes nodes = obstacle_nodes(mine);
  ContactDescription linear;
  linear.dofs = nodes.dofs;
  linear.gaps = obstacle_gaps(o, nodes, 0.0, &linear.normals);
  return rebuilt(linear, false);
}

ObstacleHarmonics Model::with_obstacle_harmonics(double omega) const {
  const Data& mine = *data_;
  if (!mine.obstacle) throw InputError("obstacle: the model has none to linearise (no obstacle=)");
  if (!(std::isfinite(omega) && omega > 0))
    throw InputError("omega: " + std::to_string(omega) + ", expected a finite omega > 0");
  const RigidObstacle& o = *mine.obstacle;
  const ObstacleNodes nodes = obstacle_nodes(mine);
  ContactDescription linear;
  linear.dofs = nodes.dofs;
  obstacle_gaps(o, nodes, 0.0, &linear.normals);  // the normals at t = 0
  // The gaps sampled over one period, their Fourier sums, and the series
  // checked between the samples: a law that is not periodic with 2 pi / omega,
  // or has harmonics beyond N / 2, does not pass.
  const int N = 128;
  const double T = 2 * std::acos(-1.0) / omega;
  const Index n_c = static_cast<Index>(nodes.x.size());
  Matrix g(N, n_c);
  for (int s = 0; s < N; ++s) {
    const std::vector<double> gs = obstacle_gaps(o, nodes, s * T / N, nullptr);
    for (Index k = 0; k < n_c; ++k) g(s, k) = gs[k];
  }
  const FourierSums f = fourier_sums(g);
  const double scale = std::max(g.cwiseAbs().maxCoeff(), 1e-300);
  for (int s = 0; s < N; ++s) {
    const double t = (s + 0.5) * T / N;
    const std::vector<double> gs = obstacle_gaps(o, nodes, t, nullptr);
    for (Index k = 0; k < n_c; ++k) {
      const double off = std::abs(f.at(k, omega * t) - gs[k]);
      if (!(off <= 1e-9 * scale))
        throw InputError("obstacle: " + o.describe() + ": the gap of contact node " +
                         std::to_string(k) + " is not periodic with the excitation's period 2 pi / "
                         "omega = " + std::to_string(T) + " (off by " + std::to_string(off) +
                         " at t = " + std::to_string(t) +
                         "): the obstacle's law must be a sum of harmonics of omega");
    }
  }
  linear.gaps.assign(f.mean.data(), f.mean.data() + n_c);
  ObstacleHarmonics out;
  out.model = rebuilt(linear, false);
  for (Index h = 0; h < f.cos.rows(); ++h) {  // (rows of column-major matrices: copied by entry)
    const Vector ch = f.cos.row(h).transpose(), sh = f.sin.row(h).transpose();
    out.gap_cos.emplace_back(ch.data(), ch.data() + n_c);
    out.gap_sin.emplace_back(sh.data(), sh.data() + n_c);
  }
  return out;
}

long Model::n_dofs() const { return data_->problem->n_dofs(); }
long Model::n_contact() const { return data_->problem->n_contact(); }
const ModelOptions& Model::options() const { return data_->options; }
const std::vector<long>& Model::fixed_dofs() const { return data_->fixed; }
bool Model::massless_boundary() const { return data_->problem->massless_boundary(); }
const ContactProblem& Model::problem() const { return *data_->problem; }

}  // namespace nbm
