"""The fit report as a plain HTML page: a summary, then a table of every shape with its misfit,
cost, volume change and the parameters at a range limit, and its overlay plot.

One self-contained file beside the report (no script, no external style), so a person can open
it from the assets directory or at ``/assets/build/fit-report.html``; the plots are linked by
relative URL.
"""

from collections.abc import Callable
from html import escape

#: An RMS error (mm) above this is marked in the table: the fits' goal (docs/fitting.md).
GOAL_MM = 1.0

STYLE = """
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; }
th, td { border-bottom: 1px solid #ddd; padding: 4px 8px; text-align: left; vertical-align: top; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.miss td.rms { color: #c4452b; font-weight: bold; }
img { width: 480px; height: auto; }
"""


def _number(value, digits, sign=False) -> str:
    if value is None:
        return ""
    return f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"


def page(document: dict, href: Callable[[str], str]) -> str:
    """The page for a fit report ``document`` (``pipeline.fit_report``); ``href(name)`` is the
    URL of a shape's plot relative to the page."""
    s = document["summary"]
    lines = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
             "<title>Glasshead: mid-sagittal fits of the JD3 shapes</title>",
             f"<style>{STYLE}</style>", "</head>", "<body>",
             "<h1>Mid-sagittal fits of the JD3 shapes</h1>"]
    if s["fitted"]:
        lines.append(
            f"<p>{s['fitted']} of {s['shapes']} shapes fitted ({escape(document['method'])}, "
            f"{s['median_evaluations']} evaluations at the median): median RMS "
            f"{s['median_rms_mm']:.2f} mm, {s['within_1mm']} within {GOAL_MM:.1f} mm, worst "
            f"{escape(s['worst']['name'])} at {s['worst']['rms_mm']:.2f} mm; "
            f"{s['fit_seconds']:.1f} s of fitting, built in {document['build_seconds']:.1f} s.</p>")
    lines.append(
        "<p>Each plot: the observed outline (black), its compared part (blue), the rig's z = 0 "
        "section at the fitted pose (red) and at the start (grey, dashed), and the error "
        "vector of each ray from the origin O (green), from the observed point to where the ray "
        "crosses the fitted outline. The error is the RMS of their lengths.</p>")
    lines += ["<table>", "<thead><tr><th>shape</th><th>RMS (mm)</th><th>max (mm)</th>"
              "<th>evaluations</th><th>time (s)</th><th>volume (%)</th><th>at a limit</th>"
              "<th>plot</th></tr></thead>", "<tbody>"]
    for e in document["shapes"]:
        name = escape(e["name"])
        if e["rms_mm"] is None:
            lines.append(f'<tr id="{name}"><td><b>{name}</b><br>{escape(e["label"])}</td>'
                         f'<td colspan="7">not fitted: {escape(e.get("error", ""))}</td></tr>')
            continue
        miss = ' class="miss"' if e["rms_mm"] > GOAL_MM else ""
        url = escape(href(e["name"]), quote=True)
        lines.append(
            f'<tr id="{name}"{miss}><td><b>{name}</b><br>{escape(e["label"])}</td>'
            f'<td class="num rms">{_number(e["rms_mm"], 2)}</td>'
            f'<td class="num">{_number(e["max_error_mm"], 2)}</td>'
            f'<td class="num">{e["evaluations"]}</td>'
            f'<td class="num">{_number(e["seconds"], 2)}</td>'
            f'<td class="num">{_number(e["volume_change_pct"], 1, sign=True)}</td>'
            f'<td>{escape(", ".join(e["at_limit"]))}</td>'
            f'<td><a href="{url}"><img src="{url}" loading="lazy" '
            f'alt="{name}: observed and fitted outlines with the error vectors"></a></td></tr>')
    lines += ["</tbody>", "</table>", "</body>", "</html>"]
    return "\n".join(lines) + "\n"
