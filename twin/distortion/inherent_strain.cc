// Inherent-strain FE solve: 8-node hexahedra, linear elasticity, Winkler substrate, layer groups activated in turn.
//
// Deviation from the dissertation: 003 sec. 6.5.2 compensates from measured scans only (no model; it calls finite
// element models too slow, ref. [191]). The twin needs a predicted distortion, so it uses the inherent-strain method
// of industrial AM simulators: each element gets the shrinkage strain eps* of its beads (heat-input dependent, see
// models/distortion/distortion_params.cc), and K du_g = f_g is solved for each activation group g on the part built
// so far (elements of groups <= g). The displacement increments add up; a group's own nodes start at zero, i.e. the
// torch lays new metal where it is programmed. Full 2x2x2 integration (no incompatible modes): thin walls a couple
// of elements thick are stiffer in bending than the metal (shear locking); the fitted strains absorb it.
#include "twin/distortion/inherent_strain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"

namespace waam::twin::internal {
namespace {

using Matrix24 = Eigen::Matrix<double, 24, 24>;
using Matrix24x6 = Eigen::Matrix<double, 24, 6>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

Matrix6 Elasticity(double e, double nu) {
  Matrix6 d = Matrix6::Zero();
  const double c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) d(i, j) = c * (i == j ? 1.0 - nu : nu);
    d(i + 3, i + 3) = c * (1.0 - 2.0 * nu) / 2.0;
  }
  return d;
}

// Stiffness K_e = int B^T D B dV and G = int B^T dV of a cube of edge h (2x2x2 Gauss points), hex8 node n at
// (n & 1, n >> 1 & 1, n >> 2 & 1). Voigt order xx, yy, zz, yz, xz, xy with engineering shears.
void CubeMatrices(double h, const Matrix6& d, Matrix24* k, Matrix24x6* g) {
  k->setZero();
  g->setZero();
  const double gp = 1.0 / std::sqrt(3.0);
  const double jac = h / 2.0;               // dx/dxi
  const double weight = jac * jac * jac;    // Gauss weights are 1
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {(q & 1 ? gp : -gp), ((q >> 1) & 1 ? gp : -gp), ((q >> 2) & 1 ? gp : -gp)};
    Eigen::Matrix<double, 6, 24> b = Eigen::Matrix<double, 6, 24>::Zero();
    for (int n = 0; n < 8; ++n) {
      const double s[3] = {(n & 1 ? 1.0 : -1.0), ((n >> 1) & 1 ? 1.0 : -1.0), ((n >> 2) & 1 ? 1.0 : -1.0)};
      double dn[3];
      for (int a = 0; a < 3; ++a) {
        dn[a] = s[a] / 8.0 / jac;
        for (int c = 0; c < 3; ++c) {
          if (c != a) dn[a] *= 1.0 + s[c] * xi[c];
        }
      }
      b(0, 3 * n) = dn[0];
      b(1, 3 * n + 1) = dn[1];
      b(2, 3 * n + 2) = dn[2];
      b(3, 3 * n + 1) = dn[2];
      b(3, 3 * n + 2) = dn[1];
      b(4, 3 * n) = dn[2];
      b(4, 3 * n + 2) = dn[0];
      b(5, 3 * n) = dn[1];
      b(5, 3 * n + 1) = dn[0];
    }
    *k += weight * b.transpose() * d * b;
    *g += weight * b.transpose();
  }
}

// Inherent strain (Voigt) of an element: contraction eps in the layer plane, ratio x eps along the build direction.
Eigen::Matrix<double, 6, 1> InherentStrain(const HexElement& e, double ratio) {
  const Eigen::Matrix3d nn = e.dir * e.dir.transpose();
  const Eigen::Matrix3d t = -e.strain * ((Eigen::Matrix3d::Identity() - nn) + ratio * nn);
  Eigen::Matrix<double, 6, 1> v;
  v << t(0, 0), t(1, 1), t(2, 2), 2.0 * t(1, 2), 2.0 * t(0, 2), 2.0 * t(0, 1);
  return v;
}

// The elements around each node, in element order: at[n] .. at[n + 1] in list.
struct NodeElements {
  std::vector<int> at;
  std::vector<int> list;
};

NodeElements ElementsAtNodes(const HexMesh& mesh) {
  const std::size_t n_nodes = mesh.node_ijk.size();
  NodeElements ne;
  ne.at.assign(n_nodes + 1, 0);
  for (const HexElement& el : mesh.elements) {
    for (int n : el.nodes) ++ne.at[n + 1];
  }
  for (std::size_t n = 0; n < n_nodes; ++n) ne.at[n + 1] += ne.at[n];
  ne.list.resize(ne.at[n_nodes]);
  std::vector<int> next(ne.at.begin(), ne.at.end() - 1);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    for (int n : mesh.elements[e].nodes) ne.list[next[n]++] = static_cast<int>(e);
  }
  return ne;
}

// The elements active once `group` is laid (of those `final_active` keeps, held by the substrate) and their nodes
// numbered in element order: dof_of[node] (-1: none), node_of[dof block].
struct GroupNodes {
  std::vector<std::uint8_t> active;
  std::vector<int> dof_of;
  std::vector<int> node_of;
};

// False when the group adds no element (nothing to solve).
bool NumberGroupNodes(const HexMesh& mesh, const std::vector<std::uint8_t>& final_active, int group,
                      GroupNodes* out) {
  out->active.assign(mesh.elements.size(), 0);
  bool any_new = false;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    out->active[e] = final_active[e] && mesh.elements[e].group <= group;
    any_new = any_new || (out->active[e] && mesh.elements[e].group == group);
  }
  if (!any_new) return false;
  KeepConnectedToSubstrate(mesh, &out->active);
  out->dof_of.assign(mesh.node_ijk.size(), -1);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if (!out->active[e]) continue;
    for (int n : mesh.elements[e].nodes) {
      if (out->dof_of[n] < 0) {
        out->dof_of[n] = static_cast<int>(out->node_of.size());
        out->node_of.push_back(n);
      }
    }
  }
  return true;
}

// The element matrices and loads the assembly adds up.
struct ElementTerms {
  Matrix24 ke;         // stiffness of one cube
  Matrix24x6 gd;       // nodal loads per unit inherent strain (G D)
  double spring = 0.0; // Winkler spring per bottom node, N/mm
  double vertical_ratio = 1.0;
};

// K (lower triangle) and f of one group, assembled by column: node a's three columns (and its three entries of f)
// are summed only from the elements around a, in element order, the order a scatter over the elements adds them
// in. Each node writes only its own columns, so the nodes run in parallel and K and f are the same, bit for bit, on
// any number of threads. Columns hold the lower triangle (rows >= column), from the nodes sharing an element with a.
void AssembleGroup(const HexMesh& mesh, const NodeElements& around, const GroupNodes& g, int group,
                   const ElementTerms& terms, Eigen::SparseMatrix<double>* k_out, Eigen::VectorXd* f_out) {
  const int nn = static_cast<int>(g.node_of.size());
  std::vector<std::vector<int>> adjacent(nn);
  ParallelFor(nn, [&](std::size_t a) {
    const int node = g.node_of[a];
    for (int k = around.at[node]; k < around.at[node + 1]; ++k) {
      if (!g.active[around.list[k]]) continue;
      for (int b : mesh.elements[around.list[k]].nodes) {
        if (g.dof_of[b] >= static_cast<int>(a)) adjacent[a].push_back(g.dof_of[b]);
      }
    }
    std::sort(adjacent[a].begin(), adjacent[a].end());
    adjacent[a].erase(std::unique(adjacent[a].begin(), adjacent[a].end()), adjacent[a].end());
  });
  Eigen::SparseMatrix<double>& k = *k_out;
  k.resize(3 * nn, 3 * nn);
  int* outer = k.outerIndexPtr();
  outer[0] = 0;
  for (int a = 0; a < nn; ++a) {
    for (int c = 0; c < 3; ++c) outer[3 * a + c + 1] = outer[3 * a + c] + 3 * static_cast<int>(adjacent[a].size()) - c;
  }
  k.resizeNonZeros(outer[3 * nn]);
  int* inner = k.innerIndexPtr();
  double* values = k.valuePtr();
  std::fill(values, values + outer[3 * nn], 0.0);
  Eigen::VectorXd& f = *f_out;
  f = Eigen::VectorXd::Zero(3 * nn);
  ParallelFor(nn, [&](std::size_t a_index) {
    const int a = static_cast<int>(a_index);
    for (int c = 0; c < 3; ++c) {
      int at = outer[3 * a + c];
      for (int b : adjacent[a]) {
        for (int r = 0; r < 3; ++r) {
          if (3 * b + r >= 3 * a + c) inner[at++] = 3 * b + r;
        }
      }
    }
    auto entry = [&](int row, int col) -> double& {
      const int* lo = inner + outer[col];
      const int* hi = inner + outer[col + 1];
      return values[std::lower_bound(lo, hi, row) - inner];
    };
    const int node = g.node_of[a];
    for (int k_at = around.at[node]; k_at < around.at[node + 1]; ++k_at) {
      const int e = around.list[k_at];
      if (!g.active[e]) continue;
      const HexElement& el = mesh.elements[e];
      const int local = static_cast<int>(std::find(el.nodes.begin(), el.nodes.end(), node) - el.nodes.begin());
      int dofs[24];
      for (int n = 0; n < 8; ++n) {
        for (int c = 0; c < 3; ++c) dofs[3 * n + c] = 3 * g.dof_of[el.nodes[n]] + c;
      }
      for (int c = 0; c < 3; ++c) {
        const int j = 3 * local + c;
        for (int i = 0; i < 24; ++i) {
          if (dofs[i] >= dofs[j]) entry(dofs[i], dofs[j]) += terms.ke(i, j);
        }
      }
      if (el.group == group) {
        const Eigen::Matrix<double, 24, 1> fe = terms.gd * InherentStrain(el, terms.vertical_ratio);
        for (int c = 0; c < 3; ++c) f[3 * a + c] += fe[3 * local + c];
      }
      // Winkler springs on the bottom face (nodes 0-3) of a substrate element.
      if (el.ijk.z() == 0 && local < 4) {
        for (int c = 0; c < 3; ++c) entry(3 * a + c, 3 * a + c) += terms.spring;
      }
    }
  });
}

// K du = f for one group with the solver `options` name. Throws InputError when it fails.
Eigen::VectorXd SolveGroup(const Eigen::SparseMatrix<double>& k, const Eigen::VectorXd& f,
                           const DistortionOptions& options, int group) {
  if (options.solver == FeSolver::kCg) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::IncompleteCholesky<double>> cg;
    cg.setTolerance(1e-8);
    cg.setMaxIterations(20000);
    cg.compute(k);
    Eigen::VectorXd du = cg.solve(f);
    WAAM_THROW_UNLESS(cg.info() == Eigen::Success,
                      "distortion: conjugate gradient did not converge in " << cg.iterations()
                      << " iterations (error " << cg.error() << "); use distortion solver ldlt");
    return du;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(k);
  WAAM_THROW_UNLESS(ldlt.info() == Eigen::Success,
                    "distortion: the stiffness matrix of group " << group << " is singular (part not held by the "
                    "substrate?); raise models distortion substrate_stiffness_n_mm3");
  return ldlt.solve(f);
}

}  // namespace

std::vector<Eigen::Vector3d> SolveInherentStrain(const HexMesh& mesh, const models::DistortionParams& params,
                                                 const DistortionOptions& options, DistortionStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const Matrix6 d = Elasticity(params.youngs_modulus_mpa, params.poisson);
  ElementTerms terms;
  Matrix24x6 ge;
  CubeMatrices(mesh.h_mm, d, &terms.ke, &ge);
  terms.gd = ge * d;
  // Winkler substrate: each bottom face (z = 0) spreads k_s h^2 over its four nodes in all three directions.
  terms.spring = params.substrate_stiffness_n_mm3 * mesh.h_mm * mesh.h_mm / 4.0;
  terms.vertical_ratio = params.vertical_ratio;

  std::vector<Eigen::Vector3d> u(mesh.node_ijk.size(), Eigen::Vector3d::Zero());
  std::vector<std::uint8_t> final_active(mesh.elements.size(), 1);
  const std::size_t dropped = KeepConnectedToSubstrate(mesh, &final_active);
  if (stats != nullptr) stats->dropped_elements = dropped;
  const NodeElements around = ElementsAtNodes(mesh);

  // Each group's increment du_g = K_g^-1 f_g depends only on the elements active then and the group's own strains,
  // not on the other increments: the groups are solved in parallel, each into its own slot, and their increments
  // added in group order afterwards (the same sums as one after the other). Up to min(threads, groups)
  // factorisations are held at once.
  struct GroupSolution {
    std::vector<int> node_of;  // dof block -> node
    Eigen::VectorXd du;
    std::size_t nonzeros = 0;
  };
  std::vector<GroupSolution> solutions(mesh.groups);
  ParallelFor(solutions.size(), [&](std::size_t group_index) {
    const int group = static_cast<int>(group_index);
    CheckInterrupt();
    GroupNodes g;
    if (!NumberGroupNodes(mesh, final_active, group, &g) || g.node_of.empty()) return;
    Eigen::SparseMatrix<double> k;
    Eigen::VectorXd f;
    AssembleGroup(mesh, around, g, group, terms, &k, &f);
    solutions[group_index].du = SolveGroup(k, f, options, group);
    solutions[group_index].nonzeros = static_cast<std::size_t>(k.nonZeros());
    solutions[group_index].node_of = std::move(g.node_of);
  });
  for (const GroupSolution& solution : solutions) {
    if (solution.node_of.empty()) continue;
    const std::vector<int>& node_of = solution.node_of;
    for (std::size_t a = 0; a < node_of.size(); ++a) u[node_of[a]] += solution.du.segment<3>(3 * a);
    if (stats != nullptr) {
      stats->solves += 1;
      stats->dofs = std::max<std::size_t>(stats->dofs, 3 * node_of.size());
      stats->nonzeros = std::max<std::size_t>(stats->nonzeros, solution.nonzeros);
    }
  }
  if (stats != nullptr) {
    stats->solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return u;
}

}  // namespace waam::twin::internal
