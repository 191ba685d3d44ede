"""EPG indices over time as an SVG figure: one panel per index, one line per sequence.

Plain SVG text with no plotting library, so the API can serve it and a browser or a report can
show it as is. Time runs from each sequence's first frame, so a recording and a target line up.
"""

from dataclasses import dataclass
from xml.sax.saxutils import escape

import numpy as np

from glasshead.constants import EPG_PLOT_DEFAULT_PANELS, EPG_PLOT_PANELS

#: Panels that can be drawn: name -> (title, low, high). The value ranges are fixed, so figures
#: compare at a glance; the spec is constants.EPG_PLOT_PANELS, which the browser's plots read too.
PANELS: dict[str, tuple[str, float, float]] = {
    name: (panel["label"], float(panel["range"][0]), float(panel["range"][1]))
    for name, panel in EPG_PLOT_PANELS.items()
}
#: Panels drawn by default.
DEFAULT_PANELS = EPG_PLOT_DEFAULT_PANELS
COLOURS = ("#1f5fbf", "#c4452b", "#2e8b57", "#8a4fb5")

#: Figure geometry in SVG user units (px).
WIDTH, PANEL_HEIGHT, GAP = 760, 110, 34
LEFT, RIGHT, TOP = 64, 16, 60


@dataclass
class Track:
    """One sequence to draw: ``t_s`` (n,) seconds and ``values`` name -> (n,) float."""

    label: str
    t_s: np.ndarray
    values: dict


def panel_geometry(k: int) -> tuple[float, float]:
    """Top and bottom y of panel ``k`` (0-based)."""
    top = TOP + k * (PANEL_HEIGHT + GAP)
    return top, top + PANEL_HEIGHT


def to_xy(t: np.ndarray, v: np.ndarray, span_s: float, k: int, lo: float, hi: float):
    """Map times (relative, s) and values of panel ``k`` to SVG coordinates: two (n,) arrays."""
    top, bottom = panel_geometry(k)
    x = LEFT + (np.asarray(t) / span_s) * (WIDTH - LEFT - RIGHT)
    y = bottom - (np.clip(v, lo, hi) - lo) / (hi - lo) * (bottom - top)
    return x, y


def index_tracks_svg(tracks: list[Track], panels=DEFAULT_PANELS, title: str = "") -> str:
    """The figure as an SVG document string. Dashed lines for every track after the first."""
    if not tracks:
        raise ValueError("nothing to plot: no tracks")
    unknown = [p for p in panels if p not in PANELS]
    if unknown:
        raise ValueError(f"no panel for {unknown}; choose from {sorted(PANELS)}")
    relative = [np.asarray(tr.t_s, dtype=float) - float(tr.t_s[0]) for tr in tracks]
    span_s = max(max(float(r[-1]) for r in relative), 1e-3)
    height = TOP + len(panels) * (PANEL_HEIGHT + GAP)
    out = [(f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" '
            f'viewBox="0 0 {WIDTH} {height}" font-family="sans-serif" font-size="11">'),
           f'<rect width="{WIDTH}" height="{height}" fill="white"/>',
           f'<text x="{LEFT}" y="16" font-size="13">{escape(title)}</text>']
    for i, track in enumerate(tracks):
        x = LEFT + 220 * i
        out.append(f'<line x1="{x}" y1="32" x2="{x + 24}" y2="32" stroke="{_colour(i)}" '
                   f'stroke-width="2"{_dash(i)}/>')
        out.append(f'<text x="{x + 30}" y="36">{escape(track.label)}</text>')
    for k, name in enumerate(panels):
        label, lo, hi = PANELS[name]
        top, bottom = panel_geometry(k)
        out.append(f'<g class="panel" data-index="{name}">'
                   f'<rect x="{LEFT}" y="{top}" width="{WIDTH - LEFT - RIGHT}" '
                   f'height="{PANEL_HEIGHT}" fill="none" stroke="#999"/>'
                   f'<text x="{LEFT}" y="{top - 4}">{escape(label)}</text>'
                   f'<text x="{LEFT - 6}" y="{top + 4}" text-anchor="end">{hi:g}</text>'
                   f'<text x="{LEFT - 6}" y="{bottom}" text-anchor="end">{lo:g}</text>')
        for tick in _time_ticks(span_s):
            tx, _ = to_xy(np.array([tick]), np.array([lo]), span_s, k, lo, hi)
            out.append(f'<text x="{tx[0]:.1f}" y="{bottom + 13}" text-anchor="middle">'
                       f'{tick:g} s</text>')
        for i, (track, t) in enumerate(zip(tracks, relative, strict=True)):
            xs, ys = to_xy(t, np.asarray(track.values[name], dtype=float), span_s, k, lo, hi)
            points = " ".join(f"{x:.2f},{y:.2f}" for x, y in zip(xs, ys, strict=True))
            out.append(f'<polyline data-track="{i}" fill="none" stroke="{_colour(i)}" '
                       f'stroke-width="1.5"{_dash(i)} points="{points}"/>')
        out.append("</g>")
    out.append("</svg>")
    return "\n".join(out)


def _colour(i: int) -> str:
    return COLOURS[i % len(COLOURS)]


def _dash(i: int) -> str:
    return "" if i == 0 else ' stroke-dasharray="5 3"'


def _time_ticks(span_s: float) -> list[float]:
    """Round tick times from 0 to span_s, about five of them."""
    raw = span_s / 5
    step = 10 ** np.floor(np.log10(raw))
    step *= next(m for m in (1, 2, 5, 10) if raw <= m * step)
    return [round(float(v), 6) for v in np.arange(0.0, span_s + step * 1e-6, step)]
