// The thermal model's grid: which cells hold plate or deposit, switching cells on as beads are laid, and the cells
// each piece of bead heats (the uniform bead rule, or Goldak's double ellipsoid of heat_source.h).
#include <algorithm>
#include <limits>
#include <cmath>

#include "models/core/error.h"
#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

constexpr double kInsideToleranceMm = 1e-9;
// Face order of ThermalState::neighbour: -x, +x, -y, +y, -z, +z; the opposite face of f is f ^ 1.
constexpr int kFaceStep[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

bool CentreIn(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& c) {
  return (c.array() >= box.min().array() - kInsideToleranceMm).all() &&
         (c.array() <= box.max().array() + kInsideToleranceMm).all();
}

// Where a cell centre lies relative to a bead piece: inside its cross-section swept along the piece, with the
// cross-section's bottom lowered by `extra_depth_mm` (the layer under the arc).
bool InBead(const ArcPiece& piece, const Eigen::Vector3d& c, double half_width_mm, double extra_depth_mm) {
  const Eigen::Vector2d d = (piece.p1_mm - piece.p0_mm).head<2>();
  const double length2 = d.squaredNorm();
  double s = 0.0;
  double lateral = 0.0;
  double top = 0.0;
  double bottom = 0.0;
  if (length2 > 1e-18) {
    s = (c.head<2>() - piece.p0_mm.head<2>()).dot(d) / length2;
    if (s < -kInsideToleranceMm || s > 1.0 + kInsideToleranceMm) return false;
    s = std::clamp(s, 0.0, 1.0);
    lateral = (c.head<2>() - piece.p0_mm.head<2>() - s * d).norm();
    top = piece.p0_mm.z() + s * (piece.p1_mm.z() - piece.p0_mm.z());
    bottom = top - piece.height_mm;
  } else {
    // A standing arc or a vertical move: a disc column.
    lateral = (c.head<2>() - piece.p0_mm.head<2>()).norm();
    top = std::max(piece.p0_mm.z(), piece.p1_mm.z());
    bottom = std::min(piece.p0_mm.z(), piece.p1_mm.z()) - piece.height_mm;
  }
  return lateral <= half_width_mm + kInsideToleranceMm && c.z() <= top + kInsideToleranceMm &&
         c.z() >= bottom - extra_depth_mm - kInsideToleranceMm;
}

}  // namespace

Eigen::Vector3i ThermalState::CellIndex(int grid) const {
  const int i = grid % size.x();
  const int j = (grid / size.x()) % size.y();
  const int k = grid / (size.x() * size.y());
  return {i, j, k};
}

Eigen::Vector3d ThermalState::Centre(int i, int j, int k) const {
  return origin_mm + dx_mm * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
}

void ThermalState::FaceContact(int cell, int face, double* conductance_w_m2k, double* air) const {
  *conductance_w_m2k = 0.0;
  *air = 1.0;
  if ((face != 4 && face != 5) || material[cell] != kSubstrate) return;
  const std::array<int, 3>& ijk = cell_ijk[static_cast<std::size_t>(cell)];
  if (face == 4 && ijk[2] == plate_bottom_k) {
    if (contact.empty()) {
      *conductance_w_m2k = settings.table_conductance_w_m2k;
      *air = settings.table_conductance_w_m2k > 0.0 ? 0.0 : 1.0;
      return;
    }
    const ColumnContact& c = contact[static_cast<std::size_t>(ijk[0] + size.x() * ijk[1])];
    *conductance_w_m2k = c.bottom_w_m2k;
    *air = c.bottom_air;
  } else if (face == 5 && ijk[2] == plate_top_k && !contact.empty()) {
    const ColumnContact& c = contact[static_cast<std::size_t>(ijk[0] + size.x() * ijk[1])];
    *conductance_w_m2k = c.top_w_m2k;
    *air = c.top_air;
  }
}

double ThermalState::InterfaceContact(int cell, int face) const {
  if (!table_body || (face != 4 && face != 5) || material[cell] != kSubstrate) return 0.0;
  const std::array<int, 3>& ijk = cell_ijk[static_cast<std::size_t>(cell)];
  if (ijk[2] != (face == 4 ? plate_bottom_k : plate_bottom_k - 1)) return 0.0;
  // The clamps' columns carry the contact under each patch (BuildColumnContacts); elsewhere it is the table's.
  if (contact.empty()) return settings.table_conductance_w_m2k;
  return contact[static_cast<std::size_t>(ijk[0] + size.x() * ijk[1])].bottom_w_m2k;
}

void BuildColumnContacts(ThermalState& s) {
  const ThermalSettings& st = s.settings;
  s.contact.clear();
  if (st.clamps.empty()) return;
  const double table = st.table_conductance_w_m2k;
  s.contact.assign(static_cast<std::size_t>(s.size.x()) * s.size.y(), ColumnContact{});
  for (int j = 0; j < s.size.y(); ++j) {
    for (int i = 0; i < s.size.x(); ++i) {
      const Eigen::Vector2d lo = s.origin_mm.head<2>() + s.dx_mm * Eigen::Vector2d(i, j);
      const Eigen::AlignedBox2d face(lo, lo + Eigen::Vector2d::Constant(s.dx_mm));
      double covered = 0.0, top = 0.0, under = 0.0, under_air = 0.0;
      for (const ClampPatch& clamp : st.clamps) {
        const Eigen::AlignedBox2d overlap = face.intersection(clamp.xy_mm);
        if (overlap.isEmpty()) continue;
        const double share = overlap.volume() / (s.dx_mm * s.dx_mm);
        covered += share;
        top += share * clamp.conductance_w_m2k;
        const double below = clamp.under_conductance_w_m2k < 0.0 ? table : clamp.under_conductance_w_m2k;
        under += share * below;
        if (below > 0.0) under_air += share;
      }
      covered = std::min(covered, 1.0);
      ColumnContact& c = s.contact[static_cast<std::size_t>(i + s.size.x() * j)];
      c.top_w_m2k = top;
      c.top_air = 1.0 - covered;
      // Outside the patches the bottom lies on the table (or, with no table contact, in the air).
      c.bottom_w_m2k = under + (1.0 - covered) * table;
      c.bottom_air = table > 0.0 ? 0.0 : 1.0 - std::min(under_air, 1.0);
    }
  }
}

int ThermalState::Activate(int grid, int material_index, double h, int born_step) {
  const int id = static_cast<int>(grid_of.size());
  grid_of.push_back(grid);
  material.push_back(static_cast<std::uint8_t>(material_index));
  born.push_back(born_step);
  latest_born = std::max(latest_born, born_step);
  enthalpy.push_back(h);
  temperature.push_back(table[material_index].Temperature(h));
  conductivity.push_back(table[material_index].Conductivity(temperature.back()));
  inflow_j.push_back(0.0);
  rate.push_back(0.0);
  heat_rate.push_back(0.0);
  rate_step_s.push_back(0.0);
  guess.push_back(0.0);
  chord.push_back(0.0);
  iterate_h.push_back(0.0);
  depth.push_back(-1);
  bound_start.push_back(0.0);
  bound_end.push_back(0.0);
  bound_level.push_back(0);
  sample_head.push_back(-1);
  active_of[grid] = id;
  std::array<int, 6> links;
  std::uint8_t bits = 0, laid = 0;
  const Eigen::Vector3i c = CellIndex(grid);
  cell_ijk.push_back({c.x(), c.y(), c.z()});
  for (int f = 0; f < 6; ++f) {
    const Eigen::Vector3i n = c + Eigen::Vector3i(kFaceStep[f][0], kFaceStep[f][1], kFaceStep[f][2]);
    links[f] = kNoCell;
    if ((n.array() < 0).any() || (n.array() >= size.array()).any()) continue;
    const int other = active_of[GridIndex(n.x(), n.y(), n.z())];
    if (other == kNoCell) continue;
    links[f] = other;
    bits |= static_cast<std::uint8_t>(1u << f);
    neighbour[other][f ^ 1] = id;
    linked[other] |= static_cast<std::uint8_t>(1u << (f ^ 1));
    if (born_step >= 0) pending[other] |= static_cast<std::uint8_t>(1u << (f ^ 1));
    if (born[other] >= 0) laid |= static_cast<std::uint8_t>(1u << f);
  }
  neighbour.push_back(links);
  linked.push_back(bits);
  pending.push_back(laid);
  return id;
}

namespace {

// The table body's cells: round(thickness / cell) layers (at least one) under the plate's lowest cells, every column
// whose centre lies in the table's footprint, at the table's temperature.
void AddTableBody(ThermalState& s, const Eigen::AlignedBox3d& table_mm) {
  const int layers = std::max(1, static_cast<int>(std::lround(s.settings.table_thickness_mm / s.dx_mm)));
  s.table_bottom_k = s.plate_bottom_k - layers;
  WAAM_DEMAND(s.table_bottom_k >= 0);
  const double h = s.table[kSubstrate].Enthalpy(s.settings.table_c);
  const Eigen::AlignedBox2d footprint(table_mm.min().head<2>(), table_mm.max().head<2>());
  for (int k = s.table_bottom_k; k < s.plate_bottom_k; ++k) {
    for (int j = 0; j < s.size.y(); ++j) {
      for (int i = 0; i < s.size.x(); ++i) {
        if (!footprint.contains(s.Centre(i, j, k).head<2>())) continue;
        const int g = s.GridIndex(i, j, k);
        s.kind[g] = CellKind::kPlate;
        s.Activate(g, kSubstrate, h, -1);
        s.start_enthalpy_j += h * s.CellVolume();
      }
    }
  }
}

}  // namespace

void InitialiseThermalState(ThermalState& s) {
  const ThermalSettings& st = s.settings;
  s.dx_mm = st.cell_mm;
  s.dx_m = st.cell_mm * 1e-3;
  Eigen::AlignedBox3d all = st.substrate_box_mm;
  all.extend(st.deposit_box_mm);
  const Eigen::AlignedBox3d table_mm = TableBoxMm(st);
  s.table_body = !table_mm.isEmpty();
  if (s.table_body) {
    all.extend(table_mm);
    all.extend(Eigen::Vector3d(table_mm.min().x(), table_mm.min().y(), table_mm.min().z() - 2.0 * s.dx_mm));
  }
  // The grid is shifted so that the plate's lowest x and y corner and its top are cell faces: the plate's cells
  // then do not depend on how far the table body or the deposit reach beyond it (a table margin that is not a
  // multiple of the cell would otherwise move the plate's edges by up to half a cell).
  const Eigen::Vector3d plate_corner(st.substrate_box_mm.min().x(), st.substrate_box_mm.min().y(),
                                     st.substrate_box_mm.max().z());
  for (int a = 0; a < 3; ++a) {
    s.origin_mm[a] = plate_corner[a] - std::ceil((plate_corner[a] - all.min()[a]) / s.dx_mm - 1e-9) * s.dx_mm;
  }
  for (int a = 0; a < 3; ++a) {
    s.size[a] = std::max(1, static_cast<int>(std::ceil((all.max()[a] - s.origin_mm[a]) / s.dx_mm - 1e-9)));
  }
  const std::size_t count = static_cast<std::size_t>(s.size.x()) * s.size.y() * s.size.z();
  s.kind.assign(count, CellKind::kEmpty);
  s.active_of.assign(count, kNoCell);
  s.plate_bottom_k = s.size.z();
  s.plate_top_k = -1;
  for (int k = 0; k < s.size.z(); ++k) {
    for (int j = 0; j < s.size.y(); ++j) {
      for (int i = 0; i < s.size.x(); ++i) {
        const Eigen::Vector3d c = s.Centre(i, j, k);
        CellKind& kind = s.kind[s.GridIndex(i, j, k)];
        if (CentreIn(st.substrate_box_mm, c)) {
          kind = CellKind::kPlate;
          s.plate_bottom_k = std::min(s.plate_bottom_k, k);
          s.plate_top_k = std::max(s.plate_top_k, k);
        } else if (CentreIn(st.deposit_box_mm, c)) {
          kind = CellKind::kDeposit;
        }
      }
    }
  }
  // The plate starts at the initial temperature, everywhere.
  const double h0 = s.table[kSubstrate].Enthalpy(st.initial_c);
  for (std::size_t g = 0; g < count; ++g) {
    if (s.kind[g] == CellKind::kPlate) s.Activate(static_cast<int>(g), kSubstrate, h0, -1);
  }
  WAAM_THROW_UNLESS(!s.grid_of.empty(), "thermal substrate box holds no cell centre at cell_mm = "
                                            << st.cell_mm << ": the plate must be at least one cell thick");
  if (s.table_body) AddTableBody(s, table_mm);
  BuildColumnContacts(s);
}

std::vector<int> LayPiece(ThermalState& s, const ArcPiece& piece, int step) {
  // Beads narrower than a cell still lay the cells their path crosses.
  const double half_width = 0.5 * std::max(piece.width_mm, s.dx_mm);
  const double below = s.dx_mm;  // the layer under the arc is heated too
  Eigen::AlignedBox3d box(piece.p0_mm);
  box.extend(piece.p1_mm);
  box.min() -= Eigen::Vector3d(half_width, half_width, piece.height_mm + below);
  box.max() += Eigen::Vector3d(half_width, half_width, 0.0);
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, static_cast<int>(std::floor((box.min()[a] - s.origin_mm[a]) / s.dx_mm - 0.5)));
    hi[a] = std::min(s.size[a] - 1, static_cast<int>(std::ceil((box.max()[a] - s.origin_mm[a]) / s.dx_mm - 0.5)));
  }
  std::vector<int> heated;
  for (int k = lo.z(); k <= hi.z(); ++k) {
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const int g = s.GridIndex(i, j, k);
        if (s.kind[g] == CellKind::kEmpty) continue;
        const Eigen::Vector3d c = s.Centre(i, j, k);
        if (!InBead(piece, c, half_width, below)) continue;
        int id = s.active_of[g];
        if (id == kNoCell && s.kind[g] == CellKind::kDeposit && InBead(piece, c, half_width, 0.0)) {
          id = s.Activate(g, kDeposit, s.reference_h[kDeposit], step);
        }
        if (id != kNoCell) heated.push_back(id);
      }
    }
  }
  if (!heated.empty()) return heated;
  // No metal in or under the bead's cross-section: the first metal straight below the arc takes the heat.
  const Eigen::Vector3d mid = 0.5 * (piece.p0_mm + piece.p1_mm);
  const int i = static_cast<int>(std::floor((mid.x() - s.origin_mm.x()) / s.dx_mm));
  const int j = static_cast<int>(std::floor((mid.y() - s.origin_mm.y()) / s.dx_mm));
  if (i < 0 || j < 0 || i >= s.size.x() || j >= s.size.y()) return heated;
  int k = std::min(s.size.z() - 1, static_cast<int>(std::floor((mid.z() - s.origin_mm.z()) / s.dx_mm)));
  for (; k >= 0; --k) {
    const int id = s.active_of[s.GridIndex(i, j, k)];
    if (id != kNoCell) {
      heated.push_back(id);
      break;
    }
  }
  return heated;
}

std::vector<std::pair<int, double>> HeatPiece(ThermalState& s, const ArcPiece& piece, int step,
                                              Eigen::AlignedBox3d* heated_mm) {
  const std::vector<int> bead = LayPiece(s, piece, step);
  std::vector<std::pair<int, double>> shares;
  if (bead.empty()) return shares;
  const ThermalSettings& st = s.settings;
  if (st.heat_source == HeatSourceShape::kDoubleEllipsoid) {
    // Goldak's double ellipsoid at the piece's midpoint, travelling along it (a standing arc: as told), each active
    // cell of its support taking its exact integral, renormalised over the metal there (the part of the ellipsoid
    // in air or in metal not laid yet goes to the metal), so the cells take exactly the power.
    const double floor_mm = 0.25 * s.dx_mm;  // a bead of no width or height still heats a pool
    DoubleEllipsoid pool;
    pool.half_width_mm = 0.5 * std::max(piece.width_mm, 2.0 * floor_mm);
    pool.depth_mm = st.pool_depth_beads * std::max(piece.height_mm, floor_mm);
    pool.front_mm = st.pool_front_widths * std::max(piece.width_mm, 2.0 * floor_mm);
    pool.rear_mm = st.pool_rear_widths * std::max(piece.width_mm, 2.0 * floor_mm);
    const Eigen::Vector3d arc = 0.5 * (piece.p0_mm + piece.p1_mm);
    Eigen::Vector2d travel = (piece.p1_mm - piece.p0_mm).head<2>();
    if (travel.norm() <= 1e-9) travel = piece.travel;
    const Eigen::AlignedBox3d support = DoubleEllipsoidSupport(pool, arc, travel);
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0, static_cast<int>(std::floor((support.min()[a] - s.origin_mm[a]) / s.dx_mm)));
      hi[a] = std::min(s.size[a] - 1, static_cast<int>(std::floor((support.max()[a] - s.origin_mm[a]) / s.dx_mm)));
    }
    double sum = 0.0;
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * s.dx_mm);
    for (int k = lo.z(); k <= hi.z(); ++k) {
      for (int j = lo.y(); j <= hi.y(); ++j) {
        for (int i = lo.x(); i <= hi.x(); ++i) {
          const int id = s.active_of[s.GridIndex(i, j, k)];
          if (id == kNoCell) continue;
          const Eigen::Vector3d c = s.Centre(i, j, k);
          const double share = DoubleEllipsoidCellShare(pool, arc, travel, Eigen::AlignedBox3d(c - half, c + half));
          if (!(share > 0.0)) continue;
          shares.emplace_back(id, share);
          sum += share;
          heated_mm->extend(Eigen::AlignedBox3d(c - half, c + half));
        }
      }
    }
    // A pool whose support holds no metal (a bead far narrower than a cell off the cell centres): the bead rule.
    if (sum > 1e-12) {
      for (auto& [id, share] : shares) share /= sum;
      return shares;
    }
    shares.clear();
  }
  const double each = 1.0 / static_cast<double>(bead.size());
  for (int id : bead) {
    shares.emplace_back(id, each);
    const Eigen::Vector3i g = s.CellIndex(s.grid_of[id]);
    const Eigen::Vector3d c = s.Centre(g.x(), g.y(), g.z());
    heated_mm->extend(Eigen::AlignedBox3d(c - Eigen::Vector3d::Constant(0.5 * s.dx_mm),
                                          c + Eigen::Vector3d::Constant(0.5 * s.dx_mm)));
  }
  return shares;
}

int ProbeCell(const ThermalState& s, const Eigen::Vector3d& p_mm, int boundary) {
  const Eigen::Vector3d x = (p_mm - s.origin_mm) / s.dx_mm;
  if (!x.allFinite()) return kNoCell;
  const Eigen::Vector3i cell = x.array().floor().cast<int>();
  // The cell holding the point, else (a point of a box edge whose cell's centre lies outside the box) the metal
  // cell of the 3 x 3 x 3 around it whose centre is nearest.
  double best = std::numeric_limits<double>::infinity();
  int found = kNoCell;
  for (int r = 0; r < 27; ++r) {
    const Eigen::Vector3i c = cell + Eigen::Vector3i(r % 3 - 1, (r / 3) % 3 - 1, r / 9 - 1);
    if ((c.array() < 0).any() || (c.array() >= s.size.array()).any()) continue;
    const int id = s.active_of[s.GridIndex(c.x(), c.y(), c.z())];
    if (id == kNoCell || s.born[id] >= boundary) continue;
    const double d = (s.Centre(c.x(), c.y(), c.z()) - p_mm).squaredNorm() + (r == 13 ? -1e300 : 0.0);
    if (d < best) {
      best = d;
      found = id;
    }
  }
  return found;
}

}  // namespace waam::twin::internal
