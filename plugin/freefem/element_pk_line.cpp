// Continuous Lagrange elements of degree k on curve meshes (meshL): the
// FreeFEM plugin Element_PkL.
//
//   load "msh3"
//   load "Element_PkL"
//   meshL Th = segment(20, [x]);
//   fespace Vh(Th, P4L);          // continuous P4 on a curve
//
// Debian's FreeFEM 4.11 has P1L, P2L built in and P3L in Element_P3, but no
// continuous P4 on meshL: `fespace Vh(Th, P4)` stops with "sorry no cast to
// this curve finite element". This plugin adds P4L. If the triangle P4 is
// already known when it is loaded (`load "Element_P4"` first), `P4` on a
// meshL also means P4L, as `P3` does after `load "Element_P3"`.
//
// The element (class PkLagrangeCurve, any k >= 1): on the reference segment
// t in [0, 1] (t = barycentric coordinate of the element's second vertex)
// the nodes are equispaced, t_i = i/k, and the basis is the Lagrange basis
// of those nodes. FreeFEM orders the dofs of an element by item: first one
// dof per vertex (t = 0, then t = 1), then the k - 1 dofs of the element
// itself (t = 1/k, ..., (k-1)/k). Interior dofs belong to one element only,
// so no orientation has to be reconciled between neighbours; continuity
// comes from the shared vertex dofs.
//
// Derivatives: t is the barycentric coordinate lambda_1, so the physical
// gradient of a basis function is phi'(t) grad(lambda_1) (a vector along the
// curve, K.Gradlambda), and second derivatives are phi''(t) times products
// of its components: the curve's elements are straight.
//
// Wrong mesh types: P4L has FreeFEM's curve-element type, so
// `fespace Vh(Th2d, P4L)` on a mesh, mesh3 or meshS has no matching fespace
// constructor; FreeFEM would then print its whole table of constructors in
// mangled type names. The plugin adds those three constructors for curve
// elements, each stopping the compilation with a message saying what is
// wrong (for every meshL element, P1L to P4L), before anything runs.
#include "ff++.hpp"
#include "AddNewFE.h"


namespace Fem2D {

class PkLagrangeCurve : public GTypeOfFE<MeshL> {
 public:
  typedef MeshL::Element Element;
  typedef R1 RdHat;

  explicit PkLagrangeCurve(int degree);

  void FB(const What_d whatd, const MeshL &Th, const Element &K, const RdHat &PHat,
          RNMK_ &val) const override;

 private:
  // Dofs per item (vertex, element, face, volume) of a degree-k curve element.
  struct DofsPerItem {
    int n[4];
    explicit DofsPerItem(int k) : n{1, k - 1, 0, 0} { ffassert(k >= 1); }
    operator const int *() const { return n; }
  };

  // Reference coordinate of local dof i (vertex dofs first, see the header).
  static double NodeOf(int i, int k) { return i == 0 ? 0. : i == 1 ? 1. : double(i - 1) / k; }

  // Value and first two derivatives (in t) of basis function i at t.
  void Basis(int i, double t, double &f, double &df, double &d2f) const;

  const int k_;
  KN<double> node_;   // t_i, i = 0..k
  KN<double> scale_;  // 1 / prod_{j != i} (t_i - t_j)
};

PkLagrangeCurve::PkLagrangeCurve(int degree)
    // One component, k subdivisions for plots, interpolation matrix the same
    // on every element, continuous.
    : GTypeOfFE<MeshL>(DofsPerItem(degree), 1, degree, true, false),
      k_(degree),
      node_(degree + 1),
      scale_(degree + 1) {
  ffassert(this->NbDoF == k_ + 1);
  for (int i = 0; i <= k_; ++i) node_[i] = NodeOf(i, k_);
  for (int i = 0; i <= k_; ++i) {
    double p = 1.;
    for (int j = 0; j <= k_; ++j)
      if (j != i) p *= node_[i] - node_[j];
    scale_[i] = 1. / p;
  }
  // Lagrange interpolation: dof i is the value at node i.
  for (int i = 0; i <= k_; ++i) {
    this->PtInterpolation[i] = R1(node_[i]);
    this->pInterpolation[i] = i;
    this->cInterpolation[i] = 0;
    this->dofInterpolation[i] = i;
    this->coefInterpolation[i] = 1.;
  }
}

// phi_i(t) = scale_i prod_{j != i} (t - t_j). The derivatives are sums of the
// same product with one (first) or two (second) factors left out; k is small,
// so the O(k^3) loops cost nothing next to the quadrature.
void PkLagrangeCurve::Basis(int i, double t, double &f, double &df, double &d2f) const {
  f = 1., df = 0., d2f = 0.;
  for (int j = 0; j <= k_; ++j) {
    if (j == i) continue;
    f *= t - node_[j];
    double pj = 1.;  // product without factors i, j
    for (int m = 0; m <= k_; ++m)
      if (m != i && m != j) pj *= t - node_[m];
    df += pj;
    for (int l = 0; l <= k_; ++l) {
      if (l == i || l == j) continue;
      double pjl = 1.;  // without i, j, l (ordered pairs j != l: each term twice, as it should)
      for (int m = 0; m <= k_; ++m)
        if (m != i && m != j && m != l) pjl *= t - node_[m];
      d2f += pjl;
    }
  }
  f *= scale_[i], df *= scale_[i], d2f *= scale_[i];
}

void PkLagrangeCurve::FB(const What_d whatd, const MeshL &, const Element &K, const RdHat &PHat,
                         RNMK_ &val) const {
  ffassert(val.N() >= this->NbDoF && val.M() == 1);
  val = 0.;
  R3 G[2];
  K.Gradlambda(G);
  const R3 &g = G[1];  // grad t
  const double t = PHat.x;
  RN_ f0(val('.', 0, op_id));
  for (int i = 0; i <= k_; ++i) {
    double f, df, d2f;
    Basis(i, t, f, df, d2f);
    if (whatd & Fop_D0) f0[i] = f;
    if (whatd & Fop_dx) val(i, 0, op_dx) = df * g.x;
    if (whatd & Fop_dy) val(i, 0, op_dy) = df * g.y;
    if (whatd & Fop_dz) val(i, 0, op_dz) = df * g.z;
    if (whatd & Fop_dxx) val(i, 0, op_dxx) = d2f * g.x * g.x;
    if (whatd & Fop_dyy) val(i, 0, op_dyy) = d2f * g.y * g.y;
    if (whatd & Fop_dzz) val(i, 0, op_dzz) = d2f * g.z * g.z;
    if (whatd & Fop_dxy) val(i, 0, op_dxy) = d2f * g.x * g.y;
    if (whatd & Fop_dxz) val(i, 0, op_dxz) = d2f * g.x * g.z;
    if (whatd & Fop_dyz) val(i, 0, op_dyz) = d2f * g.y * g.z;
  }
}

// The triangle element that the script language calls `name`, or null.
// Debian's Element_P4 does not add P4 to ListOfTFE (so FindFE2("P4") would
// stop the script): look the name up in the language's global table.
static TypeOfFE *FindTriangleElement(const char *name) {
  TableOfIdentifier::const_iterator e = Global.m.find(name);
  if (e == Global.m.end() || e->second.first != atype<TypeOfFE *>() || !e->second.second)
    return nullptr;
  return GetAny<TypeOfFE *>((*e->second.second)(NullStack));
}

// `fespace Vh(Th, <curve element>)` with Th a PMesh (mesh, mesh3, meshS):
// a compile error that names the mistake instead of FreeFEM's list of the
// constructors that do exist.
template <class PFes, class PMesh>
class CurveElementOnOtherMesh : public OneOperator {
 public:
  explicit CurveElementOnOtherMesh(const char *meshType)
      : OneOperator(atype<PFes *>(), atype<PFes *>(), atype<PMesh *>(), atype<TypeOfFEL *>()),
        meshType_(meshType) {}
  E_F0 *code(const basicAC_F0 &) const override {
    CompileError(std::string("fespace: a finite element of curve meshes (P1L ... P4L) on a ") + meshType_ +
                 "; these elements need a meshL");
    return nullptr;
  }

 private:
  const char *meshType_;
};

static PkLagrangeCurve P4Curve(4);

static void Init() {
  // P3 on meshL is Debian's P3L (Element_P3); only P4 is missing.
  AddNewFEL("P4L", &P4Curve);
  if (TypeOfFE *p4 = FindTriangleElement("P4")) TEF2dtoL[p4] = &P4Curve;
  TheOperators->Add("<-", new CurveElementOnOtherMesh<pfes, pmesh>("mesh (2d)"),
                    new CurveElementOnOtherMesh<pfes3, pmesh3>("mesh3"),
                    new CurveElementOnOtherMesh<pfesS, pmeshS>("meshS"));
}

}  // namespace Fem2D

LOADFUNC(Fem2D::Init)
