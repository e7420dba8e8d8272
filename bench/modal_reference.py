#!/usr/bin/python3
"""A direct reference for each frequency of `geardyn modal --json` (issue 35 item 3):
for every elastic mode geardyn reports, shift-invert at that mode's own eigenvalue
lambda_j (scipy's ARPACK, one eigenvalue, tolerance 1e-14, SuperLU of the complex
A - lambda_j B of the first-order pencil from `geardyn matrices`): the mode is then by
far the dominant eigenvalue of the operator, so the reference converges to rounding
whatever the mesh. Prints, per mode, geardyn's frequency, the reference's, their
relative difference and geardyn's reported residual; then the largest difference.
Also the reference's own spread: the same solve at lambda_j (1 + 1e-6), another
factorisation, so the difference is meaningful only above it.

usage: modal_reference.py MATRICES_DIR SPEED_RAD_S GEARDYN_JSON
"""
import json
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def main():
    d, w, js = sys.argv[1], float(sys.argv[2]), sys.argv[3]
    M = scipy.io.mmread(d + "/M.mtx").tocsc()
    K = scipy.io.mmread(d + "/K.mtx").tocsc()
    C = scipy.io.mmread(d + "/C.mtx").tocsc()
    G = scipy.io.mmread(d + "/G.mtx").tocsc()
    n = M.shape[0]
    I = sp.identity(n, format="csc")
    Z = sp.csc_matrix((n, n))
    res = json.load(open(js))
    damped = res["damped"]
    D = (C + w * G).tocsc() if damped else Z
    # complex matrices: a complex shift of real ones would take only a real part of the
    # operator (scipy's OPpart)
    A = sp.bmat([[Z, I], [-K, -D]], format="csc").astype(complex)
    B = sp.bmat([[I, Z], [Z, M]], format="csc").astype(complex)
    worst = spread = 0.0
    for m in res["modes"]:
        if m["rigid_body"]:
            continue
        lam = complex(m["eigenvalue_real"], m["eigenvalue_imag"])
        got = []
        for sig in (lam, lam * (1 + 1e-6)):
            v = spla.eigs(A, k=1, M=B, sigma=sig, which="LM", tol=1e-14,
                          return_eigenvectors=False)
            got.append(abs(v[0]))
        ref = got[0]
        rel = abs(m["omega_n_rad_s"] - ref) / ref
        worst, spread = max(worst, rel), max(spread, abs(got[1] - got[0]) / ref)
        print(f"mode {m['mode']:3d}  {m['frequency_hz']:.12g} Hz  reference {ref / 2 / np.pi:.12g} Hz"
              f"  rel. diff {rel:.1e}  geardyn residual {m['residual']:.1e}")
    print(f"largest relative difference {worst:.2e} (reference spread {spread:.1e})")


main()
