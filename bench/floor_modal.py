#!/usr/bin/python3
"""The floor for `geardyn modal --modes N`: scipy's ARPACK (eigs, shift-invert with
SuperLU) and LAPACK dgeev (scipy.linalg.eig) on the same first-order matrices, read
from `geardyn matrices --format mtx`. Prints best-of-R CPU times (the machine may be
shared; one thread: OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1) and the lowest
frequencies; asserts nothing.

The shift is geardyn's automatic one (src/modal/sparse_modes.c, gd_sparse_shift_auto),
so both sides invert the same operator. --tol T sets ARPACK's tolerance (default 1e-9,
geardyn's); --sigma-scale F multiplies the shift by F (the floor's own stability: the
same problem through another factorisation); --freqs prints the lowest frequencies to 12 digits on a line of its own.

--speeds A:B:N (rad/s) times one solve at each of N speeds from A to B instead (the
floor of a Campbell diagram, per speed; K, M, C as exported, D = C + speed G).

usage: floor_modal.py DIR SPEED_RAD_S NMODES [REPEATS] [--no-dense] [--tol T] [--freqs]
                      [--speeds A:B:N] [--sigma-scale F]
"""
import sys
import time

import numpy as np
import scipy.io
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def best(f, reps):
    t = 1e30
    out = None
    for _ in range(reps):
        t0 = time.process_time()
        out = f()
        t = min(t, time.process_time() - t0)
    return t, out


def geardyn_shift(d, K, M):
    """sigma = -s of gd_sparse_shift_auto: a tenth of the lowest Rayleigh quotient of the
    uniform motions of each DOF type, clamped to [1e-6, 1e-3] sqrt(min K_ii / M_ii)."""
    kd, md = K.diagonal(), M.diagonal()
    ok = (kd > 0) & (md > 0)
    g = np.sqrt(np.min(kd[ok] / md[ok])) if ok.any() else 1e3
    s = 1e-3 * g
    with open(d + "/dofs.csv") as f:
        types = [line.split(",")[2] for line in f.read().splitlines()[1:]]
    wrq = np.inf
    for t in sorted(set(types)):
        e = np.array([1.0 if x == t else 0.0 for x in types])
        num, den, kdiag = e @ (K @ e), e @ (M @ e), np.abs(kd) @ e
        if den > 0 and num > 1e-9 * kdiag:
            wrq = min(wrq, np.sqrt(num / den))
    if np.isfinite(wrq):
        s = max(min(0.1 * wrq, s), 1e-6 * g)
    return -s


def main():
    d, w, nm = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    reps = int(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[4][0] != "-" else 3
    tol = float(sys.argv[sys.argv.index("--tol") + 1]) if "--tol" in sys.argv else 1e-9
    M = scipy.io.mmread(d + "/M.mtx").tocsc()
    K = scipy.io.mmread(d + "/K.mtx").tocsc()
    C = scipy.io.mmread(d + "/C.mtx").tocsc()
    G = scipy.io.mmread(d + "/G.mtx").tocsc()
    D = (C + w * G).tocsc()
    n = M.shape[0]
    sigma = geardyn_shift(d, K, M)
    if "--sigma-scale" in sys.argv:
        sigma *= float(sys.argv[sys.argv.index("--sigma-scale") + 1])
    I = sp.identity(n, format="csc")
    Z = sp.csc_matrix((n, n))
    # A z = lambda B z, z = [u; lambda u]: A = [0 I; -K -D], B = [I 0; 0 M]
    A = sp.bmat([[Z, I], [-K, -D]], format="csc")
    B = sp.bmat([[I, Z], [Z, M]], format="csc")

    def arpack():
        # shift-invert about sigma: SuperLU of (A - sigma B); the tolerance geardyn uses
        return spla.eigs(A, k=min(2 * nm, 2 * n - 2), M=B, sigma=sigma, which="LM",
                         tol=tol, return_eigenvectors=True)

    if "--speeds" in sys.argv:
        a, b, ns = sys.argv[sys.argv.index("--speeds") + 1].split(":")
        speeds = np.linspace(float(a), float(b), int(ns))
        total = 0.0
        for sp_w in speeds:
            Aw = sp.bmat([[Z, I], [-K, -(C + sp_w * G)]], format="csc")
            t, _ = best(lambda: spla.eigs(Aw, k=min(2 * nm, 2 * n - 2), M=B, sigma=sigma,
                                          which="LM", tol=tol, return_eigenvectors=True), reps)
            total += t
        print(f"floor ARPACK+SuperLU per speed: n={n} modes={nm} speeds={len(speeds)} "
              f"time {total / len(speeds):.6f} s")
        return
    t_ar, (lam, _) = best(arpack, reps)
    lam = lam[np.argsort(np.abs(lam))]
    f = sorted(set(round(abs(x) / (2 * np.pi), 6) for x in lam))
    print(f"floor ARPACK+SuperLU: n={n} modes={nm} time {t_ar:.6f} s; "
          f"lowest |lambda|/2pi (Hz): {' '.join(f'{x:.6g}' for x in f[:6])}")
    if "--freqs" in sys.argv:
        # one per mode (conjugate pairs once), ascending
        fr = np.sort(np.abs(lam[lam.imag >= 0]) / (2 * np.pi))[:nm]
        print("freqs " + " ".join(f"{x:.12g}" for x in fr))
    if "--no-dense" not in sys.argv:
        Ad, Bd = A.toarray(), B.toarray()
        Minv = np.linalg.inv(Bd[n:, n:])
        Ad[n:, :] = Minv @ Ad[n:, :]
        t_de, _ = best(lambda: scipy.linalg.eig(Ad, right=True, left=False,
                                                overwrite_a=False, check_finite=False), reps)
        print(f"floor LAPACK dgeev (2n = {2 * n}): time {t_de:.6f} s")


main()
