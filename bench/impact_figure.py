#!/usr/bin/env python3
"""docs/figures/impact_response.svg: the clearance oscillator's response (docs/rattle.md,
"Jumps of a clearance oscillator"). Runs tests/periodic/test_impact_jumps.c with
GD_IMPACT_CURVE set (the closed-form branch and geardyn's shooting points) and draws
peak-to-peak x against Omega: the closed form as lines (solid stable, dashed unstable),
geardyn's points as markers, the jumps as arrows.
Usage: python3 bench/impact_figure.py [BUILD_DIR] [OUT.svg]"""
import cmath
import math
import os
import subprocess
import sys
import tempfile

build = sys.argv[1] if len(sys.argv) > 1 else "build"
out = sys.argv[2] if len(sys.argv) > 2 else "docs/figures/impact_response.svg"
ZETA, FM, FA = 0.05, 0.1, 0.02

with tempfile.TemporaryDirectory() as tmp:
    data = os.path.join(tmp, "curve.txt")
    exe = os.path.join(build, "test_impact_jumps")
    if not os.path.exists(exe):
        exe = os.path.join(build, "tests", "test_impact_jumps")
    subprocess.run([exe, "shooting"], check=True, env=dict(os.environ, GD_IMPACT_CURVE=data),
                   stdout=subprocess.DEVNULL)
    rows = [line.split() for line in open(data)]

branch = [(float(r[1]), float(r[2]), int(r[3])) for r in rows if r[0] == "branch"]
points = [(float(r[1]), float(r[2]), int(r[3]), int(r[4])) for r in rows if r[0] == "point"]
graz = [float(v) for v in next(r for r in rows if r[0] == "grazing")[1:]]
fold = [float(v) for v in next(r for r in rows if r[0] == "fold")[1:]]


def linear_p2p(om):
    return 2 * FA * abs(1 / (1 - om * om + 2j * ZETA * om))


X0, X1, Y0, Y1 = 0.74, 1.11, 0.0, 0.5
W, H, L, R, T, B = 760, 480, 70, 20, 40, 56


def px(x):
    return L + (x - X0) / (X1 - X0) * (W - L - R)


def py(y):
    return H - B - (y - Y0) / (Y1 - Y0) * (H - T - B)


svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
       f'viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="13">',
       f'<rect width="{W}" height="{H}" fill="white"/>',
       '<defs><marker id="arr" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" '
       'markerHeight="7" orient="auto"><path d="M0,0 L10,5 L0,10 z" fill="#c0392b"/></marker></defs>']
for i in range(8):  # grid and ticks
    x = 0.75 + 0.05 * i
    if x <= X1:
        svg.append(f'<line x1="{px(x):.1f}" y1="{T}" x2="{px(x):.1f}" y2="{H-B}" stroke="#eee"/>')
        svg.append(f'<text x="{px(x):.1f}" y="{H-B+18}" text-anchor="middle">{x:.2f}</text>')
for i in range(6):
    y = 0.1 * i
    svg.append(f'<line x1="{L}" y1="{py(y):.1f}" x2="{W-R}" y2="{py(y):.1f}" stroke="#eee"/>')
    svg.append(f'<text x="{L-8}" y="{py(y)+4:.1f}" text-anchor="end">{y:.1f}</text>')
svg.append(f'<rect x="{L}" y="{T}" width="{W-L-R}" height="{H-T-B}" fill="none" stroke="#333"/>')
svg.append(f'<text x="{(L+W-R)/2}" y="{H-14}" text-anchor="middle">Ω = ω / ω_n</text>')
svg.append(f'<text x="18" y="{(T+H-B)/2}" text-anchor="middle" '
           f'transform="rotate(-90 18 {(T+H-B)/2})">peak-to-peak of x = d / b</text>')


def path(pts, style):
    d = " ".join(f"{'M' if k == 0 else 'L'}{px(x):.1f},{py(y):.1f}" for k, (x, y) in enumerate(pts))
    return f'<path d="{d}" fill="none" {style}/>'


# linear response: valid (solid) outside the grazing points, not a solution between them
n = 400
lin = [(X0 + (X1 - X0) * k / n, linear_p2p(X0 + (X1 - X0) * k / n)) for k in range(n + 1)]
svg.append(path([p for p in lin if p[0] <= graz[0]], 'stroke="#1f4e9c" stroke-width="2"'))
svg.append(path([p for p in lin if p[0] >= graz[1]], 'stroke="#1f4e9c" stroke-width="2"'))
svg.append(path([p for p in lin if graz[0] <= p[0] <= graz[1] and p[1] <= Y1],
                'stroke="#1f4e9c" stroke-width="1" stroke-dasharray="2,4" opacity="0.6"'))
for s in range(3):
    seg = [(o, a) for o, a, g in branch if g == s]
    style = ('stroke="#1f4e9c" stroke-width="2"' if s != 1 else
             'stroke="#1f4e9c" stroke-width="2" stroke-dasharray="7,5"')
    svg.append(path(seg, style))
for o, a, s, st in points:
    fill = "#e67e22" if st else "white"
    svg.append(f'<circle cx="{px(o):.1f}" cy="{py(a):.1f}" r="4.5" fill="{fill}" '
               f'stroke="#e67e22" stroke-width="2"/>')


def amp_at(om, seg):
    best = min((abs(o - om), a) for o, a, g in branch if g == seg)
    return best[1]


# the jumps: up at the first fold (lower branch to the upper), down at the second
up0, up1 = amp_at(fold[0], 0), amp_at(fold[0], 2)
dn0, dn1 = amp_at(fold[1], 2), linear_p2p(fold[1])
svg.append(f'<line x1="{px(fold[0]):.1f}" y1="{py(up0)-4:.1f}" x2="{px(fold[0]):.1f}" '
           f'y2="{py(up1)+6:.1f}" stroke="#c0392b" stroke-width="1.5" marker-end="url(#arr)"/>')
svg.append(f'<line x1="{px(fold[1]):.1f}" y1="{py(dn0)+6:.1f}" x2="{px(fold[1]):.1f}" '
           f'y2="{py(dn1)-6:.1f}" stroke="#c0392b" stroke-width="1.5" marker-end="url(#arr)"/>')
for x, y, lines in ((fold[0], 0.265, ["jump up (sweep up)", f"Ω = {fold[0]:.5f}"]),
                   (fold[1], 0.175, ["jump down (sweep down)", f"Ω = {fold[1]:.5f}"])):
    for k, line in enumerate(lines):
        svg.append(f'<text x="{px(x)+7:.1f}" y="{py(y)+16*k:.1f}" fill="#c0392b">{line}</text>')
for g in graz:
    svg.append(f'<circle cx="{px(g):.1f}" cy="{py(2*FM):.1f}" r="3" fill="#1f4e9c"/>')
svg.append(f'<text x="{px(graz[1])+6:.1f}" y="{py(2*FM)-6:.1f}" fill="#1f4e9c">grazing</text>')
svg.append(f'<text x="{px(graz[0])+6:.1f}" y="{py(2*FM)+16:.1f}" fill="#1f4e9c">grazing '
           f'{graz[0]:.5f}</text>')
lx, ly = px(0.925), py(0.15)  # legend
legend = [('<line x1="0" y1="0" x2="26" y2="0" stroke="#1f4e9c" stroke-width="2"/>',
           "closed form, stable (Eqs. R1, R8)"),
          ('<line x1="0" y1="0" x2="26" y2="0" stroke="#1f4e9c" stroke-width="2" '
           'stroke-dasharray="7,5"/>', "closed form, unstable (between the folds)"),
          ('<circle cx="13" cy="0" r="4.5" fill="#e67e22" stroke="#e67e22" stroke-width="2"/>',
           "geardyn periodic --method shooting, stable"),
          ('<circle cx="13" cy="0" r="4.5" fill="white" stroke="#e67e22" stroke-width="2"/>',
           "geardyn, unstable"),
          ('<line x1="0" y1="0" x2="26" y2="0" stroke="#1f4e9c" stroke-dasharray="2,4"/>',
           "linear response past grazing (no solution)")]
for k, (mark, text) in enumerate(legend):
    svg.append(f'<g transform="translate({lx:.1f},{ly + 20*k:.1f})">{mark}'
               f'<text x="34" y="4">{text}</text></g>')
svg.append(f'<text x="{L}" y="24" font-weight="bold">Clearance oscillator, ζ = {ZETA}, '
           f'F_m = {FM}, F_a = {FA} (examples/impact_oscillator.yaml)</text>')
svg.append("</svg>")
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
with open(out, "w") as f:
    f.write("\n".join(svg) + "\n")
print(out)
