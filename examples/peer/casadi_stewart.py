"""Eq. 19 of Gao & Wu built with CasADi, exported as C: F, its sparse Jacobian and a
`fast_newton` rootfinder. Used by compare.sh; the same system as `stewart equations`."""

import sys

import casadi as ca
import numpy as np

BASE = np.array([[200.764, 53.795, 0], [169.706, 0, 0], [0, 0, 0], [-31.058, 53.795, 0],
                 [53.795, 200.764, 0], [115.911, 200.764, 0]], dtype=float)
PLATFORM = np.array([[122.475, 122.475, 0], [51.764, 0, 0], [0, 0, 0], [-70.711, 122.475, 0],
                     [-44.829, 167.303, 0], [96.593, 167.303, 0]], dtype=float)


def constants():
    """E1..E9 (Eq. 17) and E10..E12 (Eq. 18)."""
    frame = PLATFORM[[0, 2, 4]].T + 1.0   # [G1' G3' G5'] + M
    rest = PLATFORM[[1, 3, 5]].T + 1.0    # [G2' G4' G6'] + M
    e = np.linalg.solve(frame, rest)      # columns: coefficients of G2, G4, G6
    dist = [np.linalg.norm(PLATFORM[0] - PLATFORM[2]), np.linalg.norm(PLATFORM[2] - PLATFORM[4]),
            np.linalg.norm(PLATFORM[4] - PLATFORM[0])]
    return e, dist


def system():
    v = ca.SX.sym("v", 18)
    legs = ca.SX.sym("L", 6)
    px = lambda i: v[i]
    py = lambda i: v[6 + i]
    pz = lambda i: v[12 + i]
    e, dist = constants()
    f = []
    for i in range(6):
        f.append((px(i) - BASE[i, 0]) ** 2 + (py(i) - BASE[i, 1]) ** 2 + (pz(i) - BASE[i, 2]) ** 2 - legs[i] ** 2)
    for col, g in enumerate([1, 3, 5]):
        for coord in (px, py, pz):
            f.append(e[0, col] * coord(0) + e[1, col] * coord(2) + e[2, col] * coord(4) - coord(g))
    for (a, b), d in zip([(0, 2), (2, 4), (4, 0)], dist):
        f.append((px(a) - px(b)) ** 2 + (py(a) - py(b)) ** 2 + (pz(a) - pz(b)) ** 2 - d ** 2)
    return v, legs, ca.vertcat(*f)


def main(out_dir):
    v, legs, f = system()
    residual = ca.Function("stewart_f", [v, legs], [f])
    jac = ca.Function("stewart_jac", [v, legs], [ca.jacobian(f, v)])
    g = ca.Function("g", [v, legs], [f])
    rf = ca.rootfinder("stewart_rf", "fast_newton", g,
                       {"abstol": 1e-10, "abstolStep": 1e-10, "max_iter": 50})
    gen = ca.CodeGenerator("stewart_casadi.c", {"with_header": True})
    for fun in (residual, jac, rf):
        gen.add(fun)
    gen.generate(out_dir + "/")
    print("nonzeros of the Jacobian:", jac.sparsity_out(0).nnz(), file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
