// Reduced distortion model: layer-wise shrinkage and a bending of the central axis, the picture of 003 sec. 6.5.2
// (residual stresses form a bending moment that bends the central axis, each layer contributing locally, Fig. 71).
//
// Each layer i (elements of that layer) has a centroid c_i, build direction n_i, mean bead height h_i and an
// inherent strain that varies across it, eps(r) ~ a_i + g_i . r (least squares over its elements, r in the layer
// plane). The layer shrinks towards c_i in its plane by a_i; along n_i its slice shortens by ratio a_i h_i and
// becomes a wedge of rotation theta_i = ratio h_i (n_i x g_i) (the hotter side shrinks more). A point of layer j is
// carried by the wedges and shortenings of all layers below it: u = sum_{i<j} [theta_i x (x - c_i) - ratio a_i h_i
// n_i] - a_j (x - c_j)_perp. Deviation from the FE mode: no substrate compliance and no restraint between layers.
#include <cmath>
#include <map>

#include <Eigen/Dense>

#include "twin/distortion/inherent_strain.h"

namespace waam::twin::internal {

std::vector<Eigen::Vector3d> SolveReduced(const HexMesh& mesh, const DepositHistory& history,
                                          const models::DistortionParams& params) {
  struct Layer {
    double w = 0.0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    double a = 0.0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
  };
  std::map<int, Layer> layers;
  auto layer_of = [](const HexElement& e) { return static_cast<int>(std::lround(e.layer)); };
  for (const HexElement& e : mesh.elements) {
    Layer& l = layers[layer_of(e)];
    l.w += 1.0;
    l.c += e.center;
    l.n += e.dir;
    l.a += e.strain;
  }
  for (auto& [index, l] : layers) {
    l.c /= l.w;
    l.a /= l.w;
    l.n = l.n.norm() > 0 ? Eigen::Vector3d(l.n.normalized()) : Eigen::Vector3d::UnitZ();
  }
  // Strain gradient in each layer plane: 2x2 least squares in a basis (t1, t2) of the plane.
  std::map<int, std::pair<Eigen::Matrix2d, Eigen::Vector2d>> normal_eq;
  for (const HexElement& e : mesh.elements) {
    const Layer& l = layers[layer_of(e)];
    const Eigen::Vector3d t1 = l.n.unitOrthogonal();
    const Eigen::Vector3d t2 = l.n.cross(t1);
    const Eigen::Vector3d r = e.center - l.c;
    const Eigen::Vector2d x(r.dot(t1), r.dot(t2));
    auto& [m, b] = normal_eq.try_emplace(layer_of(e), Eigen::Matrix2d::Zero(), Eigen::Vector2d::Zero()).first->second;
    m += x * x.transpose();
    b += x * (e.strain - l.a);
  }
  for (auto& [index, l] : layers) {
    const auto& [m, b] = normal_eq[index];
    if (std::abs(m.determinant()) < 1e-9 * std::max(1.0, m.squaredNorm())) continue;
    const Eigen::Vector2d g2 = m.ldlt().solve(b);
    const Eigen::Vector3d t1 = l.n.unitOrthogonal();
    l.g = g2.x() * t1 + g2.y() * l.n.cross(t1);
  }
  // Prefix sums over the layers below: Theta_j = sum theta_i, W_j = sum (theta_i x c_i + ratio a_i h_i n_i).
  std::map<int, std::pair<Eigen::Vector3d, Eigen::Vector3d>> below;
  Eigen::Vector3d theta_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_sum = Eigen::Vector3d::Zero();
  for (const auto& [index, l] : layers) {
    below[index] = {theta_sum, w_sum};
    const double h = index < history.layers() ? history.LayerHeight(index) : 0.0;
    const Eigen::Vector3d theta = params.vertical_ratio * h * l.n.cross(l.g);
    theta_sum += theta;
    w_sum += theta.cross(l.c) + params.vertical_ratio * l.a * h * l.n;
  }
  std::vector<Eigen::Vector3d> u(mesh.node_ijk.size(), Eigen::Vector3d::Zero());
  std::vector<int> node_layer(mesh.node_ijk.size(), -1);
  for (const HexElement& e : mesh.elements) {
    for (int n : e.nodes) {
      if (node_layer[n] < 0 || layer_of(e) < node_layer[n]) node_layer[n] = layer_of(e);
    }
  }
  for (std::size_t n = 0; n < u.size(); ++n) {
    if (node_layer[n] < 0) continue;
    const Eigen::Vector3d x = mesh.node_ijk[n].cast<double>() * mesh.h_mm;
    const Layer& l = layers[node_layer[n]];
    const auto& [theta, w] = below[node_layer[n]];
    Eigen::Vector3d r = x - l.c;
    r -= r.dot(l.n) * l.n;
    u[n] = theta.cross(x) - w - l.a * r;
  }
  return u;
}

}  // namespace waam::twin::internal
