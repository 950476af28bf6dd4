#!/usr/bin/python3
"""FEniCSx peer of waam's thermal model: solves tools/peers/thermal_wall.json and prints probe histories as JSON.

Transient conduction rho cp dT/dt = div(k grad T) + q on the plate + wall (one hexahedral mesh of the problem's
cell size, trilinear Q1 elements), convection -k dT/dn = h (T - T_ambient) on every boundary face, backward Euler
with the problem's step (consistent mass matrix, or row-sum lumped with --lumped). The heat source q is the one waam's solver uses: in each step the arc's heat is spread
evenly over the cells whose centres lie in the bead cross-section (width x height, plus one cell below) along the
piece of path the arc covers in that step (a DG0 field, so its integral is exactly the arc's power).
Run with Debian's python3-dolfinx (0.5): /usr/bin/python3 tools/peers/thermal_fenicsx.py tools/peers/thermal_wall.json
[--lumped]
"""
import json
import sys
import time

import numpy as np
import ufl
from dolfinx import fem, geometry, mesh
from dolfinx.fem.petsc import assemble_matrix, assemble_vector
from mpi4py import MPI
from petsc4py import PETSc


def inside(box, p, tol=1e-9):
    lo, hi = np.asarray(box["min"], float), np.asarray(box["max"], float)
    return np.all(p >= lo - tol, axis=1) & np.all(p <= hi + tol, axis=1)


def build_mesh(spec):
    """The plate + wall as the cells (of the problem's size) of their bounding box whose centres lie in either."""
    h = spec["cell_mm"]
    lo = np.minimum(spec["plate_mm"]["min"], spec["wall_mm"]["min"]).astype(float)
    hi = np.maximum(spec["plate_mm"]["max"], spec["wall_mm"]["max"]).astype(float)
    n = [int(round((hi[a] - lo[a]) / h)) for a in range(3)]
    box = mesh.create_box(MPI.COMM_WORLD, [lo * 1e-3, hi * 1e-3], n, mesh.CellType.hexahedron)
    cells = np.arange(box.topology.index_map(3).size_local, dtype=np.int32)
    mid_mm = mesh.compute_midpoints(box, 3, cells) * 1e3
    keep = cells[inside(spec["plate_mm"], mid_mm) | inside(spec["wall_mm"], mid_mm)]
    box.topology.create_connectivity(3, 0)
    sub = mesh.create_submesh(box, 3, keep)[0]
    return sub


def heated_cells(spec, mid_mm, x0, x1):
    """Cells under the arc's piece from x0 to x1 (a straight path along x, as in the spec): waam's LayPiece rule."""
    h = spec["cell_mm"]
    half = 0.5 * max(spec["bead_width_mm"], h)
    y_path = spec["path_mm"][0][1]
    top = spec["path_mm"][0][2]
    bottom = top - spec["bead_height_mm"] - h
    tol = 1e-9
    return np.where((mid_mm[:, 0] >= min(x0, x1) - tol) & (mid_mm[:, 0] <= max(x0, x1) + tol)
                    & (np.abs(mid_mm[:, 1] - y_path) <= half + tol)
                    & (mid_mm[:, 2] <= top + tol) & (mid_mm[:, 2] >= bottom - tol))[0]


def probe_cells(msh, points):
    tree = geometry.BoundingBoxTree(msh, msh.topology.dim)
    candidates = geometry.compute_collisions(tree, points)
    colliding = geometry.compute_colliding_cells(msh, candidates, points)
    cells = []
    for i in range(len(points)):
        found = colliding.links(i)
        if len(found) == 0:
            sys.exit(f"thermal_fenicsx: probe {points[i] * 1e3} mm is outside the metal")
        cells.append(found[0])
    return np.asarray(cells, dtype=np.int32)


def solve(spec, lumped):
    t_start, cpu_start = time.perf_counter(), time.process_time()
    msh = build_mesh(spec)
    V = fem.FunctionSpace(msh, ("Lagrange", 1))
    Q = fem.FunctionSpace(msh, ("DG", 0))
    dt = spec["step_s"]
    k, rc = spec["conductivity_w_mk"], spec["density_kg_m3"] * spec["specific_heat_j_kgk"]
    hconv, t_amb = spec["convection_w_m2k"], spec["ambient_c"]

    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    T_old = fem.Function(V)
    T_old.x.array[:] = spec["initial_c"]
    T = fem.Function(V)
    q = fem.Function(Q)
    stiffness = k * ufl.dot(ufl.grad(u), ufl.grad(v)) * ufl.dx + hconv * u * v * ufl.ds
    if lumped:
        # Row-sum lumped heat capacity (a diagonal mass matrix, as a finite-volume scheme has).
        A = assemble_matrix(fem.form(stiffness))
        A.assemble()
        mass = fem.petsc.create_vector(fem.form(rc / dt * v * ufl.dx))
        assemble_vector(mass, fem.form(rc / dt * v * ufl.dx))
        mass.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        diagonal = A.getDiagonal()
        diagonal.axpy(1.0, mass)
        A.setDiagonal(diagonal)
        L = fem.form(q * v * ufl.dx + hconv * t_amb * v * ufl.ds)
    else:
        A = assemble_matrix(fem.form(rc / dt * u * v * ufl.dx + stiffness))
        A.assemble()
        L = fem.form(rc / dt * T_old * v * ufl.dx + q * v * ufl.dx + hconv * t_amb * v * ufl.ds)
    b = fem.petsc.create_vector(L)
    ksp = PETSc.KSP().create(msh.comm)
    ksp.setOperators(A)
    ksp.setType("cg")
    ksp.getPC().setType("hypre")
    ksp.setTolerances(rtol=1e-10)

    cells = np.arange(msh.topology.index_map(3).size_local, dtype=np.int32)
    mid_mm = mesh.compute_midpoints(msh, 3, cells) * 1e3
    cell_m3 = (spec["cell_mm"] * 1e-3) ** 3
    names = list(spec["probes_mm"])
    points = np.asarray([spec["probes_mm"][n] for n in names], float) * 1e-3
    pcells = probe_cells(msh, points)

    ksp.setUp()
    setup_s = time.perf_counter() - t_start
    (x0, y0, z0), (x1, _, _) = spec["path_mm"]
    length = abs(x1 - x0)
    weld_steps = int(round(length / (spec["speed_mm_s"] * dt)))
    cool_steps = int(round(spec["cool_s"] / dt))
    step_mm = (x1 - x0) / weld_steps
    times, history, iterations = [], {n: [] for n in names}, 0
    for step in range(weld_steps + cool_steps):
        q.x.array[:] = 0.0
        if step < weld_steps:
            hot = heated_cells(spec, mid_mm, x0 + step * step_mm, x0 + (step + 1) * step_mm)
            q.x.array[hot] = spec["heat_w"] / (len(hot) * cell_m3)
        if lumped:
            b.pointwiseMult(mass, T_old.vector)  # M_lumped T_old, then the assembled terms are added to it
        else:
            with b.localForm() as local:
                local.set(0.0)
        assemble_vector(b, L)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        ksp.solve(b, T.vector)
        iterations += ksp.getIterationNumber()
        T.x.scatter_forward()
        T_old.x.array[:] = T.x.array
        values = T.eval(points, pcells)
        times.append(round((step + 1) * dt, 9))
        for i, n in enumerate(names):
            history[n].append(float(values[i][0]))
    wall_s, cpu_s = time.perf_counter() - t_start, time.process_time() - cpu_start
    # setup_s includes FFCx's just-in-time compile of the forms (cached in ~/.cache/fenics after the first run).
    return {"peer": "fenicsx", "mass": "lumped" if lumped else "consistent", "wall_s": wall_s, "cpu_s": cpu_s, "setup_s": setup_s,
            "cells": int(len(cells)), "dofs": int(V.dofmap.index_map.size_global),
            "steps": weld_steps + cool_steps, "iterations": iterations, "time_s": times, "probes_c": history}


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--lumped"):
        sys.exit("usage: thermal_fenicsx.py <problem.json> [--lumped]")
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    print(json.dumps(solve(spec, len(sys.argv) == 3)))


if __name__ == "__main__":
    main()
