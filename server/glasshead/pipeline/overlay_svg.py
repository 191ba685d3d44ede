"""A fit's overlay plot as SVG: the observed outline against the fitted one, with the error
vectors, as in Cohen, Beskow and Massaro (1998), Figures 5 and 6.

Plain SVG text with no plotting library (as ``epg.plot``), so the fit report's page and the
workbench show it as is. Everything in the mid-sagittal plane is drawn inside one group whose
transform maps millimetres of the project frame to the picture (+y up), so the coordinates
written are the millimetres themselves: a test reads an error vector's ends back as mm. Strokes
do not scale with it (``vector-effect``); text is drawn outside the group.

The error vectors are the objective's (``objective2d``): for a compared point P on the ray from
the origin O, the vector runs from P to the ray's crossing with the fitted outline,
Q = P + e (P - O) / |P - O|, e the signed per-ray error (+: the rig lies outside).
"""

from xml.sax.saxutils import escape

import numpy as np

#: Picture scale, px per mm.
PX_PER_MM = 6.0
#: Margin round the drawing, mm; room above it for the title and below it for the legend, px.
MARGIN_MM = 6.0
TITLE_PX, LEGEND_PX = 46, 30
#: Length of the scale bar, mm.
SCALE_BAR_MM = 10.0
#: Narrowest picture, px: the legend's width.
LEGEND_WIDTH_PX = 580
COLOURS = {"observed": "#222222", "compared": "#1f5fbf", "fitted": "#c4452b",
           "start": "#888888", "error": "#2e8b57", "origin": "#8a4fb5"}


def _points(value, what):
    points = np.asarray(value, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 2:
        raise ValueError(f"{what} must be (n, 2) mid-sagittal points with n >= 2, got shape "
                         f"{points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError(f"{what} has non-finite coordinates")
    return points


def crossings(origin, compared, errors) -> np.ndarray:
    """Q (m, 2): where each ray from ``origin`` (2,) through ``compared`` (m, 2) crosses the
    fitted outline, given the signed per-ray errors (m,), mm."""
    origin = np.asarray(origin, dtype=np.float64)
    offset = compared - origin
    direction = offset / np.linalg.norm(offset, axis=1)[:, None]
    return compared + np.asarray(errors, dtype=np.float64)[:, None] * direction


def _path(points, closed=False) -> str:
    text = " ".join(f"{x:.3f},{y:.3f}" for x, y in points)
    return f"M{text}{' Z' if closed else ''}"


def svg_overlay(*, observed, compared, errors, origin, fitted, start=None, title="",
                subtitle="") -> str:
    """The overlay plot as an SVG document string.

    observed: (n, 2) the observed outline, mm; compared: (m, 2) its compared points, one per ray;
    errors: (m,) signed per-ray errors, mm; origin: (2,) the rays' origin; fitted: (k, 2) the
    fitted outline (closed); start: (k, 2) the starting outline (closed, drawn dashed) or None.
    Each error vector is a ``line`` of class ``error`` in the group ``errors``, from P (x1, y1)
    to Q (x2, y2), in mm.
    """
    observed = _points(observed, "observed outline")
    compared = _points(compared, "compared points")
    fitted = _points(fitted, "fitted outline")
    start = None if start is None else _points(start, "starting outline")
    errors = np.asarray(errors, dtype=np.float64)
    if errors.shape != (len(compared),) or not np.all(np.isfinite(errors)):
        raise ValueError(f"errors must be ({len(compared)},) finite values, one per compared "
                         f"point; got shape {errors.shape}")
    origin = np.asarray(origin, dtype=np.float64)
    if origin.shape != (2,):
        raise ValueError(f"origin must be (2,), got shape {origin.shape}")
    ends = crossings(origin, compared, errors)

    drawn = [observed, compared, fitted, ends, origin[None]] + ([start] if start is not None
                                                                 else [])
    every = np.vstack(drawn)
    low = every.min(axis=0) - MARGIN_MM
    high = every.max(axis=0) + MARGIN_MM
    width = max(round(float(high[0] - low[0]) * PX_PER_MM), LEGEND_WIDTH_PX)
    height = round(float(high[1] - low[1]) * PX_PER_MM) + TITLE_PX + LEGEND_PX
    # mm -> px: x' = (x - low_x) s, y' = TITLE_PX + (high_y - y) s.
    transform = (f"translate({-low[0] * PX_PER_MM:.3f} {TITLE_PX + high[1] * PX_PER_MM:.3f}) "
                 f"scale({PX_PER_MM:g} {-PX_PER_MM:g})")
    thin = 'vector-effect="non-scaling-stroke" fill="none"'
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
           f"<title>{escape(title)}</title>",
           f'<rect width="{width}" height="{height}" fill="#ffffff"/>',
           f'<text x="8" y="18" font-size="14" font-weight="bold">{escape(title)}</text>',
           f'<text x="8" y="36" fill="#555555">{escape(subtitle)}</text>',
           f'<g id="mm" transform="{transform}">']
    if start is not None:
        out.append(f'<path id="start" d="{_path(start, True)}" stroke="{COLOURS["start"]}" '
                   f'stroke-width="1" stroke-dasharray="4 3" {thin}/>')
    out.append(f'<path id="fitted" d="{_path(fitted, True)}" stroke="{COLOURS["fitted"]}" '
               f'stroke-width="1.5" {thin}/>')
    out.append(f'<path id="observed" d="{_path(observed)}" stroke="{COLOURS["observed"]}" '
               f'stroke-width="1" {thin}/>')
    out.append(f'<path id="compared" d="{_path(compared)}" stroke="{COLOURS["compared"]}" '
               f'stroke-width="2" {thin}/>')
    out.append(f'<g id="errors" stroke="{COLOURS["error"]}" stroke-width="1">')
    for (x1, y1), (x2, y2) in zip(compared, ends, strict=True):
        out.append(f'<line class="error" x1="{x1:.4f}" y1="{y1:.4f}" x2="{x2:.4f}" '
                   f'y2="{y2:.4f}" vector-effect="non-scaling-stroke"/>')
    out.append("</g>")
    r = 3.0 / PX_PER_MM
    ox, oy = origin
    out.append(f'<g id="origin" stroke="{COLOURS["origin"]}" stroke-width="1.5">'
               f'<line x1="{ox - r:.3f}" y1="{oy:.3f}" x2="{ox + r:.3f}" y2="{oy:.3f}" '
               f'vector-effect="non-scaling-stroke"/><line x1="{ox:.3f}" y1="{oy - r:.3f}" '
               f'x2="{ox:.3f}" y2="{oy + r:.3f}" vector-effect="non-scaling-stroke"/></g>')
    bar_x, bar_y = float(high[0] - MARGIN_MM / 2 - SCALE_BAR_MM), float(low[1] + MARGIN_MM / 2)
    out.append(f'<line id="scale-bar" x1="{bar_x:.3f}" y1="{bar_y:.3f}" '
               f'x2="{bar_x + SCALE_BAR_MM:.3f}" y2="{bar_y:.3f}" stroke="#000000" '
               f'stroke-width="2" vector-effect="non-scaling-stroke"/>')
    out.append("</g>")

    def px(x, y):
        return (x - low[0]) * PX_PER_MM, TITLE_PX + (high[1] - y) * PX_PER_MM

    label_x, label_y = px(ox, oy)
    out.append(f'<text x="{label_x + 5:.1f}" y="{label_y - 5:.1f}" '
               f'fill="{COLOURS["origin"]}">O</text>')
    left, bottom = px(bar_x, bar_y)
    out.append(f'<text x="{left:.1f}" y="{bottom - 6:.1f}">{SCALE_BAR_MM:g} mm</text>')
    legend = [("observed", "observed outline"), ("compared", "compared part"),
              ("fitted", "fitted (z = 0 section)"), ("start", "start"),
              ("error", "error vectors")]
    y = height - 10
    x = 8.0
    for key, text in legend:
        dash = ' stroke-dasharray="4 3"' if key == "start" else ""
        out.append(f'<line x1="{x:.1f}" y1="{y - 4}" x2="{x + 18:.1f}" y2="{y - 4}" '
                   f'stroke="{COLOURS[key]}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{x + 22:.1f}" y="{y}">{escape(text)}</text>')
        x += 30 + 6 * len(text)
    out.append("</svg>")
    return "\n".join(out) + "\n"
