#!/usr/bin/python3
"""The floor for `geardyn modal --modes N`: scipy's ARPACK (eigs, shift-invert with
SuperLU) and LAPACK dgeev (scipy.linalg.eig) on the same first-order matrices, read
from `geardyn matrices --format mtx`. Prints best-of-R CPU times (the machine may be
shared; one thread: OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1) and the lowest
frequencies; asserts nothing.

usage: floor_modal.py DIR SPEED_RAD_S NMODES [REPEATS] [--no-dense]
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


def main():
    d, w, nm = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    reps = int(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[4][0] != "-" else 3
    M = scipy.io.mmread(d + "/M.mtx").tocsc()
    K = scipy.io.mmread(d + "/K.mtx").tocsc()
    C = scipy.io.mmread(d + "/C.mtx").tocsc()
    G = scipy.io.mmread(d + "/G.mtx").tocsc()
    D = (C + w * G).tocsc()
    n = M.shape[0]
    # the same shift as geardyn's: sigma = -1e-3 sqrt(min K_ii / M_ii)
    kd, md = K.diagonal(), M.diagonal()
    ok = (kd > 0) & (md > 0)
    g = np.sqrt(np.min(kd[ok] / md[ok])) if ok.any() else 1e3
    sigma = -1e-3 * g
    I = sp.identity(n, format="csc")
    Z = sp.csc_matrix((n, n))
    # A z = lambda B z, z = [u; lambda u]: A = [0 I; -K -D], B = [I 0; 0 M]
    A = sp.bmat([[Z, I], [-K, -D]], format="csc")
    B = sp.bmat([[I, Z], [Z, M]], format="csc")

    def arpack():
        # shift-invert about sigma: SuperLU of (A - sigma B); the tolerance geardyn uses
        return spla.eigs(A, k=min(2 * nm, 2 * n - 2), M=B, sigma=sigma, which="LM",
                         tol=1e-9, return_eigenvectors=True)

    t_ar, (lam, _) = best(arpack, reps)
    lam = lam[np.argsort(np.abs(lam))]
    f = sorted(set(round(abs(x) / (2 * np.pi), 6) for x in lam))
    print(f"floor ARPACK+SuperLU: n={n} modes={nm} time {t_ar:.6f} s; "
          f"lowest |lambda|/2pi (Hz): {' '.join(f'{x:.6g}' for x in f[:6])}")
    if "--no-dense" not in sys.argv:
        Ad, Bd = A.toarray(), B.toarray()
        Minv = np.linalg.inv(Bd[n:, n:])
        Ad[n:, :] = Minv @ Ad[n:, :]
        t_de, _ = best(lambda: scipy.linalg.eig(Ad, right=True, left=False,
                                                overwrite_a=False, check_finite=False), reps)
        print(f"floor LAPACK dgeev (2n = {2 * n}): time {t_de:.6f} s")


main()
