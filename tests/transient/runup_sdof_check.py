#!/usr/bin/env python3
"""Independent check of the run-up acceptance (tests/transient/test_runup.c,
run_up_peak_at_the_critical_speed), not run by ctest: the first forward mode of
tests/transient/runup_rotor.yaml alone (campbell: 110.83 Hz, log decrement 0.116) as a
complex one-DOF whirl under the same rotating unbalance, swept through the same ramps
and order-tracked the same way, with numpy/scipy only. Its 1x peaks fall in the same
blocks as geardyn's (6771.1 rpm at 1250 rpm/s, 6726.8 rpm at 625 rpm/s): the shift from
the 6649.8 rpm critical speed is the sweep's, not the integrator's.
usage: python3 tests/transient/runup_sdof_check.py   (about a minute)"""
# Independent check of the sweep shift: one forward-whirl mode (110.83 Hz, log decrement
# 0.116 -> zeta 0.0185) as a complex SDOF z'' + 2 zeta w z' + w^2 z = (rotating unbalance)
# ~ (W^2 - i W') e^{i phi}, swept 5500 -> 7800 rpm in T s; the 1x order amplitude by
# the same order tracking (8 turns, Hann, 50 % overlap) as geardyn.
import numpy as np
from scipy.integrate import solve_ivp
wn = 2*np.pi*110.83; zeta = 0.116/(2*np.pi)
def run(rate_rpm_s):
    w0, w1 = 5500*np.pi/30, 7800*np.pi/30
    T = (7800-5500)/rate_rpm_s; a = (w1-w0)/T
    def f(t, y):
        z = y[0]+1j*y[1]; v = y[2]+1j*y[3]
        W = w0+a*t; phi = w0*t+0.5*a*t*t
        F = (W*W - 1j*a)*np.exp(1j*phi)
        acc = F - 2*zeta*wn*v - wn*wn*z
        return [v.real, v.imag, acc.real, acc.imag]
    t = np.arange(0, T, 1e-4)
    sol = solve_ivp(f, (0, T), [0,0,0,0], t_eval=t, rtol=1e-9, atol=1e-12, method='DOP853')
    x = sol.y[0]; phi = w0*t+0.5*a*t*t
    S, R = 32, 8; N = S*R
    hop = R*0.5*2*np.pi; out = []
    a0 = 0.0
    while a0 + 2*np.pi*R <= phi[-1]:
        th = a0 + 2*np.pi*np.arange(N)/S
        xs = np.interp(th, phi, x); ts = np.interp([a0, a0+2*np.pi*R], phi, t)
        wdw = 0.5*(1-np.cos(2*np.pi*np.arange(N)/N)); xs = xs - xs.mean()
        X = np.fft.rfft(xs*wdw); amp = 2*np.abs(X)/wdw.sum()
        out.append((2*np.pi*R/(ts[1]-ts[0])*30/np.pi, amp[R-1:R+2].max()))
        a0 += hop
    out = np.array(out); i = out[:,1].argmax()
    return out[i,0]
crit = 110.83*60
for r in (1250, 625):
    p = run(r); print(r, "rpm/s: SDOF peak", round(p,1), "rpm, shift", round(p-crit,1))
