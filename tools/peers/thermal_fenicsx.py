#!/usr/bin/python3
"""FEniCSx peer of waam's thermal model: solves tools/peers/thermal_wall.json and prints probe histories as JSON.

Transient conduction rho cp dT/dt = div(k grad T) + q on the plate + wall (one hexahedral mesh of the problem's
cell size, or of that size / --refine; Lagrange elements of --degree, trilinear Q1 by default), convection
-k dT/dn = h (T - T_ambient) on every boundary face, backward Euler with the problem's step (or --substeps steps in
each, the source held), consistent mass matrix (row-sum lumped with --lumped). The matrices are assembled once; a step
is b = M T_old + B q + c and one CG solve (Jacobi by default, --pc; relative tolerance --rtol). The heat source q is
the one waam's solver uses: in each step the arc's heat is spread evenly over the problem's cells whose centres lie
in the bead cross-section (width x height, plus one cell below) along the piece of path the arc covers in that step
(a field constant on each problem cell, so its integral is exactly the arc's power; a refined cell takes the density
of the problem cell that holds it). Probes are evaluated at their points.
Run with Debian's python3-dolfinx (0.5), one process:
OMP_NUM_THREADS=1 /usr/bin/python3 tools/peers/thermal_fenicsx.py tools/peers/thermal_wall.json [options]
"""
import argparse
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


def build_mesh(spec, refine):
    """The plate + wall as the cells of their bounding box (the problem's cell size / refine) whose centres lie in
    either."""
    h = spec["cell_mm"] / refine
    lo = np.minimum(spec["plate_mm"]["min"], spec["wall_mm"]["min"]).astype(float)
    hi = np.maximum(spec["plate_mm"]["max"], spec["wall_mm"]["max"]).astype(float)
    n = [int(round((hi[a] - lo[a]) / h)) for a in range(3)]
    box = mesh.create_box(MPI.COMM_WORLD, [lo * 1e-3, hi * 1e-3], n, mesh.CellType.hexahedron)
    cells = np.arange(box.topology.index_map(3).size_local, dtype=np.int32)
    mid_mm = mesh.compute_midpoints(box, 3, cells) * 1e3
    keep = cells[inside(spec["plate_mm"], mid_mm) | inside(spec["wall_mm"], mid_mm)]
    box.topology.create_connectivity(3, 0)
    sub = mesh.create_submesh(box, 3, keep)[0]
    return sub, lo


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


def solve(spec, lumped, refine, degree, substeps, rtol, pc):
    t_start, cpu_start = time.perf_counter(), time.process_time()
    msh, lo = build_mesh(spec, refine)
    V = fem.FunctionSpace(msh, ("Lagrange", degree))
    Q = fem.FunctionSpace(msh, ("DG", 0))
    dt = spec["step_s"] / substeps
    k, rc = spec["conductivity_w_mk"], spec["density_kg_m3"] * spec["specific_heat_j_kgk"]
    hconv, t_amb = spec["convection_w_m2k"], spec["ambient_c"]

    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    T_old = fem.Function(V)
    T_old.x.array[:] = spec["initial_c"]
    T = fem.Function(V)
    T.x.array[:] = spec["initial_c"]
    q = fem.Function(Q)
    stiffness = k * ufl.dot(ufl.grad(u), ufl.grad(v)) * ufl.dx + hconv * u * v * ufl.ds
    # Everything is assembled once; a step is b = M T_old + B q + c (matrix-vector products) and one CG solve.
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
    else:
        A = assemble_matrix(fem.form(rc / dt * u * v * ufl.dx + stiffness))
        A.assemble()
        M = assemble_matrix(fem.form(rc / dt * u * v * ufl.dx))
        M.assemble()
    B = assemble_matrix(fem.form(ufl.TrialFunction(Q) * v * ufl.dx))  # the cell-wise source's load on the nodes
    B.assemble()
    c = fem.petsc.create_vector(fem.form(hconv * t_amb * v * ufl.ds))
    assemble_vector(c, fem.form(hconv * t_amb * v * ufl.ds))
    c.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    b, load = A.createVecRight(), A.createVecRight()
    ksp = PETSc.KSP().create(msh.comm)
    ksp.setOperators(A)
    ksp.setType("cg")
    ksp.getPC().setType(pc)
    ksp.setTolerances(rtol=rtol)
    ksp.setInitialGuessNonzero(True)  # from the last step's field

    # The source lives on the problem's cells: a refined cell takes the density of the problem cell holding it.
    cells = np.arange(msh.topology.index_map(3).size_local, dtype=np.int32)
    h = spec["cell_mm"]
    parent_mm = lo + (np.floor((mesh.compute_midpoints(msh, 3, cells) * 1e3 - lo) / h) + 0.5) * h
    names = list(spec["probes_mm"])
    points = np.asarray([spec["probes_mm"][n] for n in names], float) * 1e-3
    pcells = probe_cells(msh, points)

    ksp.setUp()
    setup_s, setup_cpu_s = time.perf_counter() - t_start, time.process_time() - cpu_start
    (x0, y0, z0), (x1, _, _) = spec["path_mm"]
    length = abs(x1 - x0)
    weld_steps = int(round(length / (spec["speed_mm_s"] * spec["step_s"])))
    cool_steps = int(round(spec["cool_s"] / spec["step_s"]))
    step_mm = (x1 - x0) / weld_steps
    times, history, iterations = [], {n: [] for n in names}, 0
    for step in range(weld_steps + cool_steps):
        q.x.array[:] = 0.0
        if step < weld_steps:
            hot = heated_cells(spec, parent_mm, x0 + step * step_mm, x0 + (step + 1) * step_mm)
            q.x.array[hot] = spec["heat_w"] * refine ** 3 / (len(hot) * (h * 1e-3) ** 3)
        for _ in range(substeps):
            if lumped:
                b.pointwiseMult(mass, T_old.vector)
            else:
                M.mult(T_old.vector, b)
            B.mult(q.vector, load)
            b.axpy(1.0, load)
            b.axpy(1.0, c)
            ksp.solve(b, T.vector)
            iterations += ksp.getIterationNumber()
            T.x.scatter_forward()
            T_old.x.array[:] = T.x.array
        values = T.eval(points, pcells)
        times.append(round((step + 1) * spec["step_s"], 9))
        for i, n in enumerate(names):
            history[n].append(float(values[i][0]))
    wall_s, cpu_s = time.perf_counter() - t_start, time.process_time() - cpu_start
    # setup_s includes FFCx's just-in-time compile of the forms (cached in ~/.cache/fenics after the first run).
    return {"peer": "fenicsx", "mass": "lumped" if lumped else "consistent", "refine": refine, "degree": degree,
            "substeps": substeps, "rtol": rtol, "pc": pc, "wall_s": wall_s, "cpu_s": cpu_s, "setup_s": setup_s, "setup_cpu_s": setup_cpu_s,
            "cells": int(len(cells)), "dofs": int(V.dofmap.index_map.size_global),
            "steps": (weld_steps + cool_steps) * substeps, "iterations": iterations, "time_s": times,
            "probes_c": history}


def main():
    parser = argparse.ArgumentParser(description="FEniCSx peer of waam's thermal model (tools/peers.sh)")
    parser.add_argument("problem", help="the problem's JSON (tools/peers/thermal_wall.json)")
    parser.add_argument("--lumped", action="store_true", help="row-sum lumped heat capacity")
    parser.add_argument("--refine", type=int, default=1, help="elements per problem cell along each axis")
    parser.add_argument("--degree", type=int, default=1, help="Lagrange degree (1: trilinear Q1, 2: Q2)")
    parser.add_argument("--substeps", type=int, default=1, help="time steps per problem step (same source)")
    parser.add_argument("--rtol", type=float, default=1e-8, help="CG relative tolerance")
    parser.add_argument("--pc", default="jacobi",
                        help="PETSc preconditioner of the CG (jacobi, the fastest here; hypre: BoomerAMG; sor)")
    args = parser.parse_args()
    with open(args.problem) as f:
        spec = json.load(f)
    print(json.dumps(solve(spec, args.lumped, args.refine, args.degree, args.substeps, args.rtol, args.pc)))


if __name__ == "__main__":
    main()
