#!/usr/bin/env python3
"""Draws what the arms did in `make demo` as one SVG, from `armctl ... --trace FILE` CSVs.

    scripts/demo_picture.py OUT.svg "TITLE=TRACE.csv[@FIRST-LAST]" ...

@FIRST-LAST keeps the motion pieces that start on those lines of the path or program file
(the square without the PTP move that brings the tool to its first corner from elsewhere).

One panel per trace: the tool's path seen from above (x/y in mm, equal scales), the plan as
a line and every position read back during the motion as a dot, with the path error written
under it: how far each measured point lay from the planned tool path (the plan sampled every
20 ms, joined by straight lines), and from where the plan had the tool at that instant.
A trace that also moves up and down (a pick-and-place) gets a side view next to it.
Standard library only: it runs on any Debian python3, nothing to install.
"""
import csv
import math
import sys

PANEL_W, PANEL_H = 470, 400  # px, one view
MARGIN = dict(left=58, right=16, top=40, bottom=100)
PLAN_COLOUR, MEASURED_COLOUR = "#1f5fbf", "#d23a1e"
COLUMNS = ("kind", "line", "t_s", "planned_x_mm", "planned_y_mm", "planned_z_mm",
           "measured_x_mm", "measured_y_mm", "measured_z_mm")


class TraceError(Exception):
    pass


def read_trace(path, lines=None):
    """The plan's points (x, y, z) in order, and the read-backs as (planned, measured), of
    the pieces whose first line is within `lines` (first, last), or of all."""
    plan, reads = [], []
    try:
        with open(path, newline="") as f:
            rows = csv.reader(f)
            header = next(rows, None)
            if tuple(header or ()) != COLUMNS:
                raise TraceError(f"{path}: not an armctl --trace file (header {header})")
            for n, row in enumerate(rows, start=2):
                try:
                    if lines and not lines[0] <= int(row[1]) <= lines[1]:
                        continue
                    if row[0] == "plan":
                        plan.append(tuple(float(v) for v in row[3:6]))
                    elif row[0] == "read":
                        reads.append((tuple(float(v) for v in row[3:6]), tuple(float(v) for v in row[6:9])))
                    else:
                        raise ValueError(f"kind '{row[0]}'")
                except (ValueError, IndexError) as e:
                    raise TraceError(f"{path}:{n}: not a trace row ({e})") from None
    except OSError as e:
        raise TraceError(f"{path}: {e.strerror}") from None
    if len(plan) < 2 or not reads:
        where = f" on lines {lines[0]}-{lines[1]}" if lines else ""
        raise TraceError(f"{path}: no motion in it{where} ({len(plan)} plan rows, {len(reads)} read-backs)")
    return plan, reads


def distance_to_segment(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    ap = [p[i] - a[i] for i in range(3)]
    length2 = sum(v * v for v in ab)
    s = 0.0 if length2 == 0 else max(0.0, min(1.0, sum(ab[i] * ap[i] for i in range(3)) / length2))
    return math.dist(p, [a[i] + s * ab[i] for i in range(3)])


def errors(plan, reads):
    """(largest, mean) distance of the measured points from the planned path, and the
    largest from the planned point of the same instant, mm."""
    to_path = [min(distance_to_segment(m, plan[k], plan[k + 1]) for k in range(len(plan) - 1)) for _, m in reads]
    to_plan = [math.dist(p, m) for p, m in reads]
    return max(to_path), sum(to_path) / len(to_path), max(to_plan)


def nice_step(span, ticks=5):
    raw = span / ticks
    e = 10 ** math.floor(math.log10(raw))
    return next(m * e for m in (1, 2, 5, 10) if m * e >= raw)


def view(x0, y0, title, plan, reads, axes, names):
    """One view of the trace, the plane of coordinates `axes` (0 = x, 1 = y, 2 = z)."""
    a, b = axes
    points = [(p[a], p[b]) for p in plan] + [(m[a], m[b]) for _, m in reads]
    lo = [min(p[i] for p in points) for i in (0, 1)]
    hi = [max(p[i] for p in points) for i in (0, 1)]
    span = max(hi[0] - lo[0], hi[1] - lo[1], 10.0) * 1.15  # equal scales, a little air
    centre = [(lo[i] + hi[i]) / 2 for i in (0, 1)]
    w = PANEL_W - MARGIN["left"] - MARGIN["right"]
    h = PANEL_H - MARGIN["top"] - MARGIN["bottom"]
    scale = min(w, h) / span
    left, top = x0 + MARGIN["left"], y0 + MARGIN["top"]
    u0, v0 = centre[0] - w / scale / 2, centre[1] - h / scale / 2

    def px(u, v):  # mm -> SVG (y up)
        return left + (u - u0) * scale, top + h - (v - v0) * scale

    out = [f'<text x="{x0 + PANEL_W / 2}" y="{y0 + 22}" class="title">{title}</text>',
           f'<rect x="{left}" y="{top}" width="{w}" height="{h}" class="frame"/>']
    step = nice_step(span)
    for i, (first, last) in enumerate(((u0, u0 + w / scale), (v0, v0 + h / scale))):
        t = math.ceil(first / step) * step
        while t <= last:
            if i == 0:
                X, _ = px(t, v0)
                out.append(f'<line x1="{X:.1f}" y1="{top}" x2="{X:.1f}" y2="{top + h}" class="grid"/>')
                out.append(f'<text x="{X:.1f}" y="{top + h + 16}" class="tick">{t:g}</text>')
            else:
                _, Y = px(u0, t)
                out.append(f'<line x1="{left}" y1="{Y:.1f}" x2="{left + w}" y2="{Y:.1f}" class="grid"/>')
                out.append(f'<text x="{left - 6}" y="{Y + 4:.1f}" class="tick" text-anchor="end">{t:g}</text>')
            t += step
    out.append(f'<text x="{left + w / 2}" y="{top + h + 34}" class="axis">{names[a]} (mm)</text>')
    out.append(f'<text x="{x0 + 14}" y="{top + h / 2}" class="axis" '
               f'transform="rotate(-90 {x0 + 14} {top + h / 2})">{names[b]} (mm)</text>')
    line = " ".join("{:.1f},{:.1f}".format(*px(p[a], p[b])) for p in plan)
    out.append(f'<polyline points="{line}" class="plan"/>')
    for _, m in reads:
        X, Y = px(m[a], m[b])
        out.append(f'<circle cx="{X:.1f}" cy="{Y:.1f}" r="2.2" class="measured"/>')
    return out


def is_3d(plan):
    """The tool moves up and down too (a pick-and-place): drawn from the side as well."""
    zs = [p[2] for p in plan]
    return max(zs) - min(zs) > 5.0


def panel(x0, y0, title, plan, reads):
    side = is_3d(plan)
    out = view(x0, y0, title + " — from above", plan, reads, (0, 1), "xyz")
    width = PANEL_W
    if side:
        # The side view across the horizontal axis the tool travels most along.
        xs, ys = [p[0] for p in plan], [p[1] for p in plan]
        along = 0 if max(xs) - min(xs) >= max(ys) - min(ys) else 1
        out += view(x0 + PANEL_W, y0, title + " — from the side", plan, reads, (along, 2), "xyz")
        width += PANEL_W
    worst_path, mean_path, worst_plan = errors(plan, reads)
    x, base = x0 + MARGIN["left"], y0 + PANEL_H - 46
    out.append(f'<text x="{x}" y="{base}" class="error">path error: largest {worst_path:.2f} mm, '
               f'mean {mean_path:.2f} mm</text>')
    out.append(f'<text x="{x}" y="{base + 16}" class="note">(the {len(reads)} measured points from the planned '
               f'path; {worst_plan:.2f} mm</text>')
    out.append(f'<text x="{x}" y="{base + 31}" class="note">at most from where the plan had the tool at that '
               f'instant)</text>')
    return out, width


def legend(x0, y0):
    return [f'<line x1="{x0}" y1="{y0}" x2="{x0 + 30}" y2="{y0}" class="plan"/>',
            f'<text x="{x0 + 38}" y="{y0 + 4}" class="note">planned tool path</text>',
            f'<circle cx="{x0 + 200}" cy="{y0}" r="3" class="measured"/>',
            f'<text x="{x0 + 210}" y="{y0 + 4}" class="note">tool measured (positions read back while it moved)</text>']


def trace_spec(text):
    """"file.csv" or "file.csv@6-9" -> (path, None or (6, 9))."""
    path, at, lines = text.rpartition("@") if "@" in text else (text, "", "")
    if not at:
        return path, None
    first, dash, last = lines.partition("-")
    if not (dash and first.isdigit() and last.isdigit() and 0 < int(first) <= int(last)):
        raise TraceError(f"'{text}': after @ the lines of the pieces to draw, FIRST-LAST (e.g. 6-9)")
    return path, (int(first), int(last))


def main(argv):
    if len(argv) < 3 or any("=" not in a for a in argv[2:]):
        sys.exit("usage: demo_picture.py OUT.svg TITLE=TRACE.csv[@FIRST-LAST] ...  (traces of armctl ... --trace FILE)")
    # Panels left to right, a new row when the next one would make a row wider than three
    # views: the demo's two arms come out one a row (square, then the program's two views).
    body, x, y, width = [], 0, 50, 0
    for spec in argv[2:]:
        title, path = spec.rsplit("=", 1)
        plan, reads = read_trace(*trace_spec(path))
        if x > 0 and x + PANEL_W * (2 if is_3d(plan) else 1) > 3 * PANEL_W:
            x, y = 0, y + PANEL_H
        out, w = panel(x, y, title.replace("&", "&amp;").replace("<", "&lt;"), plan, reads)
        body += out
        x += w
        width = max(width, x)
    y += PANEL_H
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{y}" viewBox="0 0 {width} {y}" '
           'font-family="sans-serif">',
           '<style>.title{font-size:15px;font-weight:bold;text-anchor:middle}.tick{font-size:11px;fill:#555;'
           'text-anchor:middle}.axis{font-size:12px;text-anchor:middle}.note{font-size:12px;fill:#333}'
           '.error{font-size:13px;font-weight:bold;fill:#a02010}.frame{fill:none;stroke:#999}'
           '.grid{stroke:#e4e4e4}.plan{fill:none;stroke:' + PLAN_COLOUR + ';stroke-width:1.6}'
           '.measured{fill:' + MEASURED_COLOUR + ';fill-opacity:0.75}</style>',
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="16" y="22" font-size="17" font-weight="bold">armctl make demo: what the simulated arms did</text>']
    svg += legend(20, 40) + body + ["</svg>"]
    with open(argv[1], "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    try:
        main(sys.argv)
    except TraceError as e:
        sys.exit(f"demo_picture.py: {e}")
