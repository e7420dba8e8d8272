"""plotly figures of the results (`result.plot()`), and what every result shows in a
notebook (`_repr_html_`), in the shell (`__repr__`) and to tab completion (`__dir__`).
plotly is imported when a figure is asked for (Debian: python3-plotly); the library's own
figures (SVG, HTML, PNG, PDF) are geardyn's C plots (docs/plots.md)."""
import math

import numpy as np

_WHIRL_COLORS = {"forward": "#1f77b4", "backward": "#d62728", "mixed": "#9467bd",
                 "none": "#7f7f7f"}


def _go():
    try:
        import plotly.graph_objects as go
        from plotly.subplots import make_subplots
    except ImportError as e:  # pragma: no cover - depends on the machine
        raise ImportError("result.plot() needs plotly (Debian: python3-plotly, "
                          "pip: plotly)") from e
    return go, make_subplots


def _layout(fig, title):
    # the title at the left and the toolbar upright at the right: they never overlap
    fig.update_layout(title={"text": title, "x": 0, "xanchor": "left"},
                      modebar={"orientation": "v"}, hovermode="closest",
                      template="plotly_white")
    fig.update_xaxes(exponentformat="power")
    fig.update_yaxes(exponentformat="power")
    return fig


def modal(r):
    go, _ = _go()
    f = np.asarray(r.frequency_hz)
    whirl = list(r.whirl)
    fig = go.Figure()
    for w in _WHIRL_COLORS:
        idx = [i for i in range(len(f)) if whirl[i] == w]
        if not idx:
            continue
        fig.add_scatter(x=[i + 1 for i in idx], y=f[idx], mode="markers", name="whirl: " + w,
                        marker={"color": _WHIRL_COLORS[w], "size": 10},
                        text=["mode %d: %.6g Hz, zeta %s, %s" % (
                            i + 1, f[i], _zeta(r.damping_ratio[i]),
                            r.dominant_motion_names[i]) for i in idx],
                        hovertemplate="%{text}<extra></extra>")
    fig.update_xaxes(title="mode", dtick=1)
    fig.update_yaxes(title="natural frequency (Hz)")
    return _layout(fig, "modes at %.6g rpm" % (r.speed * 30 / math.pi))


def _zeta(z):
    return "0" if abs(z) < 1e-9 else "%.3g" % z


def campbell(r, max_frequency=None):
    go, _ = _go()
    rpm = r.speeds_rpm
    f = r.frequency_hz
    fig = go.Figure()
    for t, tr in enumerate(r.tracks):
        if max_frequency and np.nanmin(f[t]) > max_frequency:
            continue
        fig.add_scatter(x=rpm, y=f[t], mode="lines+markers",
                        name="mode %d (%s, %s)" % (tr["id"], tr["whirl"], tr["dominant_motion"]),
                        line={"color": _WHIRL_COLORS.get(tr["whirl"], "#7f7f7f")})
    top = max_frequency or 1.1 * np.nanmax(f)
    for o in r.orders:
        w1 = min(r.speeds[-1], top * 2 * math.pi / o["order"]) if o["order"] > 0 else r.speeds[-1]
        x = [rpm[0], w1 * 30 / math.pi]
        y = [o["order"] * r.speeds[0] / (2 * math.pi), o["order"] * w1 / (2 * math.pi)]
        fig.add_scatter(x=x, y=y, mode="lines+text", name=o["label"], text=["", o["label"]],
                        textposition="top left", line={"dash": "dash",
                                                       "color": "#2ca02c" if o["kind"] == "mesh"
                                                       else "#555"})
    cs = [c for c in r.critical_speeds if not max_frequency or c["frequency_hz"] <= max_frequency]
    if cs:
        fig.add_scatter(x=[c["speed_rpm"] for c in cs], y=[c["frequency_hz"] for c in cs],
                        mode="markers", name="critical speeds",
                        marker={"symbol": "diamond", "size": 10, "color": "black"},
                        text=["mode %d meets %s" % (c["mode"], c["order"]) for c in cs])
    fig.update_xaxes(title="reference speed (rpm)", range=[rpm[0], rpm[-1]])
    fig.update_yaxes(title="damped natural frequency (Hz)", range=[0, top])
    return _layout(fig, "Campbell diagram")


def _bode(x, series, xtitle, title):
    """Magnitude (log) and phase over x, and the polar (Nyquist) plot, of named complex
    series."""
    go, make_subplots = _go()
    fig = make_subplots(rows=2, cols=2, specs=[[{}, {"rowspan": 2}], [{}, None]],
                        subplot_titles=("magnitude", "Nyquist (polar)", "phase"))
    colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
              "#7f7f7f", "#bcbd22", "#17becf"]
    for k, (name, z) in enumerate(series):
        c = {"color": colors[k % len(colors)]}
        fig.add_scatter(x=x, y=np.abs(z), name=name, line=c, legendgroup=name, row=1, col=1)
        fig.add_scatter(x=x, y=np.degrees(np.angle(z)), name=name, line=c, legendgroup=name,
                        showlegend=False, row=2, col=1)
        fig.add_scatter(x=z.real, y=z.imag, name=name, line=c, legendgroup=name,
                        showlegend=False, mode="lines+markers", marker={"size": 4}, row=1, col=2)
    fig.update_yaxes(type="log", title="magnitude", row=1, col=1)
    fig.update_yaxes(title="phase (deg)", row=2, col=1)
    fig.update_xaxes(title=xtitle, row=2, col=1)
    fig.update_xaxes(title="real part", row=1, col=2)
    fig.update_yaxes(title="imaginary part", row=1, col=2)
    fig.update_layout(height=620)
    return _layout(fig, title)


def frf(r):
    hz = r.freqs / (2 * math.pi)
    if r.directional:
        series = []
        for o, name in enumerate(r.outputs):
            series += [(name + " forward", r.forward[o]), (name + " backward", r.backward[o])]
    else:
        H = r.H
        series = [(name, H[o, 0]) for o, name in enumerate(r.outputs)]
    return _bode(hz, series, "frequency (Hz)", "frequency response to %s" % r.input)


def unbalance(r, harmonic=0):
    rpm = r.speeds * 30 / math.pi
    R = r.response
    series = [(name, R[harmonic, o]) for o, name in enumerate(r.outputs)]
    return _bode(rpm, series, "reference speed (rpm)",
                 "unbalance response, harmonic %g x speed" % r.harmonics[harmonic]["order"])


def mesh_stiffness(r):
    go, _ = _go()
    deg = np.degrees(r.angle_rad)
    fig = go.Figure()
    pairs = np.asarray(r.pairs_in_contact)
    lo, hi = r.min - 0.12 * (r.max - r.min or r.max), r.max + 0.12 * (r.max - r.min or r.max)
    for n in sorted(set(pairs.tolist())):
        on = np.where(pairs == n, hi, np.nan)
        fig.add_scatter(x=deg, y=on, fill="tozeroy", mode="none", opacity=0.2,
                        name="%d pair%s in contact" % (n, "" if n == 1 else "s"))
    fig.add_scatter(x=deg, y=r.stiffness, name="k (normal plane)", line={"color": "black"})
    fig.update_xaxes(title="driver angle (deg)")
    fig.update_yaxes(title="mesh stiffness k (N/m)", range=[lo, hi])
    return _layout(fig, "time-varying mesh stiffness" + (" of " + r.mesh if r.mesh else ""))


def contact_analysis(r):
    go, _ = _go()
    deg = np.degrees(r.angle_rad)
    fig = go.Figure()
    fig.add_scatter(x=deg, y=np.asarray(r.ste) * 1e6, name="loaded TE")
    fig.add_scatter(x=deg, y=np.asarray(r.ste_unloaded) * 1e6, name="no-load TE",
                    line={"dash": "dot"})
    fig.update_xaxes(title="driver angle (deg)")
    fig.update_yaxes(title="transmission error along the contact normal (um)")
    return _layout(fig, "loaded transmission error at %g N m" % r.torque
                   + (" of " + r.mesh if r.mesh else ""))


def harris_map(r):
    go, _ = _go()
    fig = go.Figure()
    fig.add_scatter(x=r.torque, y=np.asarray(r.ste_peak_to_peak) * 1e6, mode="lines+markers",
                    name="peak-to-peak TE")
    fig.update_xaxes(title="driver torque (N m)")
    fig.update_yaxes(title="peak-to-peak transmission error (um)")
    return _layout(fig, "Harris map" + (" of " + r.mesh if r.mesh else ""))


def transient(r):
    go, _ = _go()
    fig = go.Figure()
    for k, name in enumerate(r.names):
        fig.add_scatter(x=r.t, y=r.values[k], name="%s (%s)" % (name, r.units[k]))
    fig.update_xaxes(title="time (s)")
    fig.update_yaxes(title="value (unit in the legend)")
    return _layout(fig, "time history")


def waterfall(w, unit=""):
    """A run-up waterfall: the spectra as a colour map over speed and frequency with the
    order lines (top), and the order cuts, each order's amplitude against speed
    (bottom); the C plot's two main panels (docs/plots.md)."""
    go, make_subplots = _go()
    fig = make_subplots(rows=2, cols=1, vertical_spacing=0.12,
                        subplot_titles=("spectra over speed", "order cuts"))
    rpm = np.asarray(w.speeds_rpm)
    fmax = max((float(f[-1]) for f in w.frequencies if len(f)), default=0.0)
    if len(w.orders) and len(rpm):  # up to 3x the highest order line, where it is drawn
        fmax = min(fmax, 3.0 * float(np.max(np.abs(w.orders))) * float(np.max(rpm)) / 60.0)
    grid = np.linspace(0.0, fmax, 400) if fmax > 0 else np.zeros(1)
    z = np.array([np.interp(grid, f, a, left=np.nan, right=np.nan) if len(f) else
                  np.full(grid.shape, np.nan) for f, a in zip(w.frequencies, w.amplitudes)])
    # in dB of the largest amplitude, 80 dB deep: the order lines and the resonances
    # show together (a linear scale shows only the highest peak)
    top = np.nanmax(z) if np.isfinite(z).any() else 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        db = np.maximum(20.0 * np.log10(z / top), -80.0)
    fig.add_heatmap(x=rpm, y=grid, z=db.T, customdata=z.T, colorscale="Viridis", zmin=-80,
                    zmax=0, row=1, col=1,
                    colorbar={"title": "dB re %.3g %s" % (top, unit), "len": 0.45,
                              "y": 0.78},
                    hovertemplate="%{x:.1f} rpm, %{y:.1f} Hz: %{customdata:.3g} "
                    + unit + " (%{z:.1f} dB)<extra></extra>")
    for k, label in enumerate(w.order_labels):
        f_line = w.orders[k] * rpm / 60.0
        fig.add_scatter(x=rpm, y=f_line, mode="lines", line={"color": "white", "width": 1},
                        name=label, showlegend=False, row=1, col=1)
        fig.add_scatter(x=rpm, y=w.order_amplitude[k], mode="lines+markers", name=label,
                        row=2, col=1)
    fig.update_xaxes(title="reference speed (rpm)", row=2, col=1)
    fig.update_yaxes(title="frequency (Hz)", range=[0, fmax], row=1, col=1)
    fig.update_yaxes(title="amplitude" + (" (%s)" % unit if unit else ""), row=2, col=1)
    fig = _layout(fig, "run-up waterfall (%g turns a block)" % w.revs_per_block)
    # the legend (the orders) under the plots, clear of the colour bar
    fig.update_layout(legend={"orientation": "h", "y": -0.12, "x": 0})
    return fig


def periodic(r):
    go, _ = _go()
    fig = go.Figure()
    x = r.speed * 30 / math.pi
    for k, name in enumerate(r.names):
        fig.add_scatter(x=x, y=r.peak_to_peak[:, k], mode="lines+markers",
                        name="%s (%s)" % (name, r.units[k]))
    fig.update_xaxes(title="reference speed (rpm)")
    fig.update_yaxes(title="peak-to-peak (unit in the legend)")
    return _layout(fig, "periodic steady state")


def summary(r):
    """One line on what a result holds (its class, sizes and the names it offers)."""
    sizes = []
    for k in ("nmodes", "ntracks", "nspeeds", "nfreq", "noutputs", "nrecords", "nout",
              "npoints", "nloads", "n"):
        v = r.__dict__.get(k)
        if isinstance(v, int):
            sizes.append("%s=%d" % (k, v))
    return "<geardyn.%s %s; %s>" % (type(r).__name__, " ".join(sizes),
                                    ", ".join(public_names(r)))


def public_names(r):
    """What a result offers: its attributes, properties and methods, and the per-record
    fields its __getattr__ serves (a subclass names their dtype in _FIELDS_DTYPE)."""
    names = set(k for k in r.__dict__ if not k.startswith("_"))
    for cls in type(r).__mro__:
        names.update(k for k in vars(cls) if not k.startswith("_"))
    dt = getattr(type(r), "_FIELDS_DTYPE", None)
    if dt is not None:
        names.update(n for n in dt.names if not n.startswith("_"))
    return sorted(names)
