#!/usr/bin/python3
"""A 2-D steady section of a wall on a plate, solved with the cell-centred 5-point finite volumes of waam's thermal
model, with and without the re-entrant face factor (docs/THERMAL.md, "Re-entrant edges"), to show the grid order at
the wall's foot: a 4 mm wall 10 mm tall on a 40 x 12 mm plate, a unit flux into the wall's top, the plate's bottom
held at 0, every other face insulated. Prints the temperature at (y, z) = (1, 1), (1, 5), (1, -1) and (5, -1) mm
(bilinear in the cell centres) on 1, 0.5, 0.25 and 0.125 mm cells and the ratios of successive steps (4: second
order, 2.52: order 4/3). Needs Debian's python3-scipy: /usr/bin/python3 tools/peers/thermal_section_2d.py
"""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sl
from scipy.interpolate import RegularGridInterpolator

FACTOR = 1.2626829  # twin/thermal/thermal_state.h, kReentrantFaceFactor
PROBES = [(1, 1), (1, 5), (1, -1), (5, -1)]


def solve(h, factor):
    ny, nz = int(40 / h), int(22 / h)
    yc, zc = -20 + (np.arange(ny) + 0.5) * h, -12 + (np.arange(nz) + 0.5) * h
    y, z = np.meshgrid(yc, zc, indexing="ij")
    metal = (z < 0) | ((np.abs(y) < 2) & (z < 10))
    index = -np.ones((ny, nz), int)
    index[metal] = np.arange(metal.sum())

    def present(i, j):
        return 0 <= i < ny and 0 <= j < nz and metal[i, j]

    def face_factor(i, j, i2, j2):
        # One factor per edge of the face where exactly one of the two cells beyond it is metal.
        f = 1.0
        for d in (-1, 1):
            a, b = ((i + d, j), (i + d, j2)) if i == i2 else ((i, j + d), (i2, j + d))
            if present(*a) != present(*b):
                f *= factor
        return f

    rows, cols, vals, b = [], [], [], np.zeros(metal.sum())
    for i in range(ny):
        for j in range(nz):
            if not metal[i, j]:
                continue
            p = index[i, j]
            for i2, j2 in ((i + 1, j), (i, j + 1)):
                if present(i2, j2):
                    q, g = index[i2, j2], face_factor(i, j, i2, j2)
                    rows += [p, q, p, q]
                    cols += [q, p, p, q]
                    vals += [-g, -g, g, g]
            if j == 0:
                rows.append(p)
                cols.append(p)
                vals.append(2.0)  # T = 0 on the bottom face, half a cell away
            if abs(zc[j] + h / 2 - 10) < 1e-9:
                b[p] += h  # unit flux through the wall's top
    t = sl.spsolve(sp.csc_matrix((vals, (rows, cols)), shape=(len(b), len(b))), b)
    field = np.full((ny, nz), np.nan)
    field[metal] = t
    return RegularGridInterpolator((yc, zc), field)(PROBES)


for factor in (1.0, FACTOR):
    runs = np.array([solve(h, factor) for h in (1.0, 0.5, 0.25, 0.125)])
    steps = np.diff(runs, axis=0)
    print(f"face factor {factor}: probes {PROBES}")
    print(np.round(runs, 5))
    print("ratios of successive steps", np.round(steps[:-1] / steps[1:], 2))
