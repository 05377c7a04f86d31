"""The Bokeh document of the explorer page (:mod:`sawdrift.report.explore` prepares its data).

Every panel's cells are one ``ColumnDataSource`` shared by its regime view and its drift view,
so hovering, tapping and selection agree between the two; all phase views share one pair of
ranges (zoom and pan together). Two CustomJS callbacks run in the page: one recomputes the
disagreement layer when the set of compared panels changes, one decodes the tapped cell's trace
(zlib via the browser's ``DecompressionStream``, then the 8-bit levels of
:func:`sawdrift.study.traces.pack_traces`) into the trace panel's source.
"""

from __future__ import annotations

import html
from typing import TYPE_CHECKING, Any

import numpy as np

from .diagrams import COLOURS
from .marks import device_unit

if TYPE_CHECKING:
    from bokeh.document import Document


NO_TRACES = ("Traces were not stored with this table, so a click cannot show a cell's last "
             "periods. Store them by running the sweep again with <code>--traces</code> "
             "(<code>sawdrift sweep ... --traces -o TABLE.parquet</code>: the cells already in the "
             "table are run once more, for their traces) and build this page again.")

_NUM = """return Number.isFinite(value) ? String(Number(value.toPrecision(4))) : "n/a";"""
_PERIOD = """if (!Number.isFinite(value)) return "n/a";
return value > 0 ? value + (value == 1 ? " period" : " periods") : "none";"""

# disagreement layer: a cell is marked where the compared panels' regimes (c<q> columns) differ;
# a panel is compared with the ticked panels of its own group (the models at its values of the
# other swept columns)
_DISAGREE_JS = """
const S = compare.active;
const show = toggle.active.length > 0;
let compared = 0;
for (let p = 0; p < sources.length; p++) {
  const d = sources[p].data;
  const n = d.regime.length;
  const marked = [];
  const G = S.filter((q) => groups[q] === groups[p]);
  if (G.length > 1) {
    compared += 1;
    for (let i = 0; i < n; i++) {
      const first = d["c" + G[0]][i];
      let known = first >= 0, differ = false;
      for (const q of G) {
        const c = d["c" + q][i];
        if (c < 0) known = false;
        if (c !== first) differ = true;
      }
      if (known && differ) marked.push(i);
    }
  }
  overlays[p].view.filter.indices = marked;
  overlays[p].visible = show;
  titles[p].text = base[p] + (G.length > 1 ? ` (disagree: ${marked.length} of ${n})` : "");
}
summary.text = compared ? `${S.length} panels compared${within}` :
  (columns ? `tick two or more panels of one ${columns} to compare` :
   "select two or more panels to compare");
"""

# click: the tapped cell's header line, then its trace decoded from the page's blob
_TAP_JS = """
const p = sources.findIndex((s) => s.selected === cb_obj);
if (p < 0 || cb_obj.indices.length === 0) return;
const i = cb_obj.indices[0];
for (let q = 0; q < sources.length; q++)
  if (q !== p && sources[q].selected.indices.length) sources[q].selected.indices = [];
const d = sources[p].data;
const fmt = (v) => Number.isFinite(v) ? String(Number(v.toPrecision(4))) : "n/a";
const head = `<b>${labels[p]}</b>: ${xlabel} = ${fmt(d.xv[i])}, ${ylabel} = ${fmt(d.yv[i])}: ` +
  `<b>${d.regime[i]}</b>${d.chaos_mark[i]}, drift ratio ${fmt(d.drift_ratio[i])}` +
  (d.se_text[i] ? ` ${d.se_text[i]}` : "") +
  (d.warnings && d.warnings[i] !== "none" ? `<br>warnings: ${d.warnings[i]}` : "");
const empty = {t: []};
for (const f of fields) empty[f] = [];
if (!blob) { trace.data = empty; info.text = head + "<br>" + no_traces; return; }
const row = d.trace_row[i];
if (row < 0) {
  trace.data = empty;
  info.text = head + "<br>This cell has no stored trace (it failed, or was computed without --traces).";
  return;
}
async function load() {
  const bytes = Uint8Array.from(atob(blob), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
  return await new Response(stream).arrayBuffer();
}
window.__sawdrift_traces = window.__sawdrift_traces || load();
window.__sawdrift_traces.then((buf) => {
  const width = 2 + 2 * fields.length;
  const count = buf.byteLength / (4 * width + fields.length * m);
  const h = new Float32Array(buf, 4 * width * row, width);
  const codes = new Uint8Array(buf, 4 * width * count);
  const data = {t: Array.from({length: m}, (_, k) => h[0] + (h[1] - h[0]) * k / (m - 1))};
  fields.forEach((f, j) => {
    const lo = h[2 + 2 * j], hi = h[3 + 2 * j], at = (row * fields.length + j) * m;
    const v = new Array(m);
    let level = 0;
    for (let k = 0; k < m; k++) {
      level = (level + codes[at + k]) & 255;
      v[k] = lo + (hi - lo) * level / 255;
    }
    data[f] = v;
  });
  const fit = (r, v) => {
    const lo = Math.min(...v), hi = Math.max(...v);
    const flat = hi - lo <= 1e-9 * Math.max(1, Math.abs(lo), Math.abs(hi));  // e.g. N* = 0 in flight
    const pad = flat ? 0.5 * Math.max(1, Math.abs(lo)) : 0.05 * (hi - lo);
    r.setv({start: lo - pad, end: hi + pad, reset_start: lo - pad, reset_end: hi + pad});
  };
  fit(t_range, [data.t[0], data.t[m - 1]]);
  fields.forEach((f, j) => fit(y_ranges[j], data[f]));
  trace.data = data;
  info.text = head + `<br>the last ${fmt(h[1] - h[0])} periods, t* = ${fmt(h[0])} to ${fmt(h[1])}`;
}).catch((e) => { info.text = head + "<br>the stored traces could not be read: " + e; });
"""


#: characters of a title line: a 13 px bold title fits a 360 px figure (the regimes; 44 in the
#: 430 px drift figure) with room to spare
TITLE_CHARS, DRIFT_TITLE_CHARS = 36, 44

# tick labels of a device axis (SI values): engineering prefixes, e.g. 1e-8 m -> "10 nm"
_ENG_JS = """
if (tick === 0) return "0";
const e = Math.max(-12, Math.min(9, 3 * Math.floor(Math.log10(Math.abs(tick)) / 3)));
const prefix = {"-12": "p", "-9": "n", "-6": "\u00b5", "-3": "m", "0": "", "3": "k", "6": "M", "9": "G"}[e];
return String(Number((tick / 10 ** e).toPrecision(3))) + " " + prefix + unit;
"""


def wrap_title(label: str, width: int = TITLE_CHARS) -> str:
    """``label`` broken into lines of at most ``width`` characters: between its ", "-separated
    parts (a panel's model and fixed columns) where it can, else at spaces."""
    import textwrap

    lines: list[str] = []
    for part in label.split(", "):
        if lines and len(lines[-1]) + 2 + len(part) <= width:
            lines[-1] += ", " + part
        else:
            if lines:
                lines[-1] += ","
            lines += textwrap.wrap(part, width, break_on_hyphens=False) or [part]
    return "\n".join(lines)


def _device_axes(fig: Any, xa: Any, ya: Any) -> None:
    """Engineering tick labels (with the unit) and fewer ticks on the device axes of ``fig``."""
    from bokeh.models import CustomJSTickFormatter

    for axis, spec in ((fig.xaxis, xa), (fig.yaxis, ya)):
        unit = device_unit(spec.column)
        if unit:
            axis.formatter = CustomJSTickFormatter(args={"unit": unit}, code=_ENG_JS)
            axis.ticker.desired_num_ticks = 4


def _swatches() -> str:
    items = [f'<span style="display:inline-block;width:12px;height:12px;background:{c};'
             f'border:1px solid #888;margin:0 4px 0 10px"></span>{html.escape(r)}'
             for r, c in COLOURS.items()]
    items.append('<span style="display:inline-block;width:8px;height:8px;border-radius:50%;'
                 'background:white;border:1px solid black;margin:0 4px 0 14px"></span>'
                 "creep: drift with no gross slip")
    return "".join(items)


def _tooltip(label: str, xa: Any, ya: Any, info: dict[str, Any]) -> str:
    # xa, ya: sawdrift.report.explore.Axis (not imported: explore imports this module)
    safe = html.escape(label).replace("@", "&#64;").replace("$", "&#36;")
    lines = [f"<b>@regime</b>@chaos_mark &mdash; {safe}",
             f"{html.escape(xa.label)} = @xv{{custom}}, {html.escape(ya.label)} = @yv{{custom}}"]
    if {xa.column, ya.column} != {"m_star", "amplitude"}:
        lines.append("m* = @m_star{custom}, A* = @amplitude{custom}")
    lines += ["drift ratio: @drift_ratio{custom} @se_text",
              "drift velocity x*': @drift_velocity{custom}"]
    if info["device"]:
        lines.append("drift speed: @speed{custom} m/s")
    lines.append("settled: @settled (after @settle_periods{custom} periods)")
    lines.append("orbit period: @orbit_period{period}" if info["has_orbit_period"]
                 else "orbit period: not stored in this table")
    lines += ["hop period: @hop_period{period}", "Lyapunov exponent: @lyapunov_text",
              "gross-slip fraction: @gross_slip{custom}",
              "creep (drift with no gross slip): @creep", "lift-offs per period: @liftoffs{custom}",
              "model version: @version"]
    if info["has_warnings"]:
        lines.append("warnings: @warnings")
    if info["has_errors"]:
        lines.append("error: @error")
    lines.append('<span style="color:#777">cell @cell_id</span>')
    body = "<br>".join(lines)
    return f'<div class="sd-tip" style="font-size:12px;line-height:1.35;max-width:340px">{body}</div>'


def _drift_palette() -> list[str]:
    import matplotlib
    from matplotlib.colors import to_hex

    cmap = matplotlib.colormaps["RdBu_r"]
    return [to_hex(cmap(k / 255.0)) for k in range(256)]


def _compare_controls(labels: list[str], cds: list, overlays: list, titles: list,
                      base: list[str], marks: list, info: dict[str, Any]) -> Any:
    """The compare check boxes, the layer's toggle and the summary, wired to the disagreement
    layer; every panel ticked, each compared with the ticked panels of its own group
    (``info["groups"]``: the models within each value of the other swept columns)."""
    from bokeh.layouts import column
    from bokeh.models import CheckboxGroup, CustomJS, Div

    groups, n = [int(g) for g in info["groups"]], len(labels)
    columns = " and ".join(info["within"])
    within = f", the models within each value of {columns}" if columns else ""
    compare = CheckboxGroup(labels=labels, active=list(range(n)), inline=True, name="compare")
    toggle = CheckboxGroup(labels=["hatch (x) the cells where the compared panels disagree in regime"],
                           active=[0], name="layer")
    paired = [groups.count(g) > 1 for g in groups]
    summary = Div(text=f"{n} panels compared{within}" if any(paired) else
                  "one panel: nothing to compare", name="summary")
    again = CustomJS(args={"sources": cds, "overlays": overlays, "titles": titles, "base": base,
                           "compare": compare, "toggle": toggle, "summary": summary,
                           "groups": groups, "within": within, "columns": columns},
                     code=_DISAGREE_JS)
    compare.js_on_change("active", again)
    toggle.js_on_change("active", again)
    for k, mark in enumerate(marks):
        if paired[k]:
            titles[k].text = f"{base[k]} (disagree: {int(np.sum(mark))} of {len(mark)})"
    head = "<b>Compare</b> (the hatched layer)" + (
        f": each panel with the ticked panels of its own {html.escape(columns)}" if columns else "")
    return column(Div(text=head + ":"), compare, toggle, summary)


def _trace_panel(fields: list[str], info: dict[str, Any]) -> tuple[Any, Any, list, list, Any]:
    """The click panel: its source (filled by the click), its time range and value ranges, its
    figures (one per packed field) and its text line."""
    from bokeh.models import ColumnDataSource, Div, Range1d
    from bokeh.plotting import figure

    trace = ColumnDataSource({"t": [], **{f: [] for f in fields}}, name="trace-source")
    # explicit ranges, set by the click (an empty source leaves a data range nothing to fit)
    t_range = Range1d(0, 1)
    y_ranges = [Range1d(0, 1) for _ in fields]
    trace_figs = []
    names = {"x": "x*", "a": "a*", "N": "N*", "T": "T*"}
    for j, f in enumerate(fields):
        fig = figure(width=430, height=150 if j < len(fields) - 1 else 175, x_range=t_range,
                     y_range=y_ranges[j], tools="pan,wheel_zoom,box_zoom,reset,save", name=f"trace-{f}")
        fig.toolbar.logo, fig.toolbar.autohide = None, True
        fig.line("t", f, source=trace, line_width=1.4, color="#1f4e9c")
        fig.yaxis.axis_label = names.get(f, f)
        fig.min_border_left = 60
        if j == len(fields) - 1:
            fig.xaxis.axis_label = "t* (wave periods)"
        trace_figs.append(fig)
    first = ("Click a cell to draw its last periods here." if info["stored"]
             else NO_TRACES)
    trace_info = Div(text=first, width=430, name="trace-info", styles={"font-size": "13px"})
    return trace, t_range, y_ranges, trace_figs, trace_info


def _regime_marks(fig: Any, draw: Any, shape: dict, src: Any, data: dict, mark: Any) -> Any:
    """On a regime view: the disagreement layer (returned) and circles on the creep cells."""
    from bokeh.models import CDSView, IndexFilter

    # the disagreeing cells only: a hatch drawn at zero alpha still costs its time
    marked = IndexFilter([int(i) for i in np.flatnonzero(mark)])
    layer = draw(**shape, source=src, view=CDSView(filter=marked), fill_alpha=0,
                 line_alpha=0, hatch_pattern="x", hatch_color="#1a1a1a", hatch_alpha=0.55,
                 hatch_scale=9, hatch_weight=0.7)
    layer.selection_glyph = layer.nonselection_glyph = layer.glyph
    creeping = [i for i, c in enumerate(data["creep"]) if c == "yes"]
    if creeping:  # circled, as in the static figures
        dots = fig.scatter("xv", "yv", source=src, size=6, fill_color="white",
                           line_color="black", line_width=1,
                           view=CDSView(filter=IndexFilter(creeping)))
        dots.selection_glyph = dots.nonselection_glyph = dots.glyph
    return layer


def _unsettled_marks(fig: Any, draw: Any, shape: dict, src: Any, data: dict) -> None:
    """On a drift view: the unsettled cells hatched, and counted in the title."""
    from bokeh.models import CDSView, IndexFilter

    unsettled = [i for i, s in enumerate(data["settled"]) if s == "no"]
    if not unsettled:
        return
    hatch = draw(**shape, source=src, view=CDSView(filter=IndexFilter(unsettled)),
                 fill_alpha=0, line_alpha=0, hatch_pattern="/", hatch_color="#444",
                 hatch_alpha=0.45, hatch_scale=9, hatch_weight=0.7)
    hatch.selection_glyph = hatch.nonselection_glyph = hatch.glyph
    fig.title.text += f"; hatched: not settled ({len(unsettled)})"
    if len(fig.title.text.rsplit("\n", 1)[-1]) > DRIFT_TITLE_CHARS:
        fig.title.text = fig.title.text.replace("; hatched", "\nhatched")


def _phase_ranges(sources: list[dict[str, Any]]) -> tuple[Any, Any]:
    """The x and y ranges every phase view shares: the box of all cells, its bounds too."""
    from bokeh.models import Range1d

    box = [np.inf, -np.inf, np.inf, -np.inf]
    for s in sources:
        xs = np.concatenate(s["xs"]) if "xs" in s else np.concatenate([s["left"], s["right"]])
        ys = np.concatenate(s["ys"]) if "ys" in s else np.concatenate([s["bottom"], s["top"]])
        box = [min(box[0], xs.min()), max(box[1], xs.max()), min(box[2], ys.min()), max(box[3], ys.max())]
    return (Range1d(float(box[0]), float(box[1]), bounds=(float(box[0]), float(box[1]))),
            Range1d(float(box[2]), float(box[3]), bounds=(float(box[2]), float(box[3]))))


def _formatters() -> dict[str, Any]:
    """The tooltip's number formats: 4 significant digits ("n/a" for none), periods in words."""
    from bokeh.models import CustomJSHover

    num, period = CustomJSHover(code=_NUM), CustomJSHover(code=_PERIOD)
    out: dict[str, Any] = {f"@{c}": num for c in ("xv", "yv", "m_star", "amplitude", "drift_ratio",
                                                   "drift_velocity", "speed", "settle_periods",
                                                   "gross_slip", "liftoffs")}
    out.update({"@orbit_period": period, "@hop_period": period})
    return out


def _colour_mappers(lim: float) -> tuple[Any, Any]:
    """The regime colours and the drift ratio's diverging scale, from -``lim`` to ``lim``."""
    from bokeh.models import CategoricalColorMapper, LinearColorMapper

    regimes = CategoricalColorMapper(factors=list(COLOURS), palette=list(COLOURS.values()),
                                     nan_color="white")
    return regimes, LinearColorMapper(palette=_drift_palette(), low=-lim, high=lim,
                                      nan_color="#d9d9d9")


def build_document(page: Any) -> Document:
    """The page: header and controls, one (regimes, drift) row per panel, the trace panel.

    ``page`` is a :class:`sawdrift.report.explore.ExplorerData` (not imported: explore imports
    this module)."""
    from bokeh.document import Document
    from bokeh.layouts import column, row
    from bokeh.models import (
        ColorBar,
        ColumnDataSource,
        CustomJS,
        Div,
        HoverTool,
        TapTool,
    )
    from bokeh.plotting import figure

    panels, sources, marks, xa, ya, info = page.panels, page.sources, page.marks, page.xa, page.ya, page.info
    blob, m, fields, lim = page.blob, page.samples, page.fields, page.limit
    regimes, drift = _colour_mappers(lim)
    formatters = _formatters()
    x_range, y_range = _phase_ranges(sources)
    axis_type = {"x_axis_type": "log" if xa.log else "linear", "y_axis_type": "log" if ya.log else "linear"}
    rows, cds, overlays, titles, base = [], [], [], [], []
    for k, (panel, data) in enumerate(zip(panels, sources, strict=True)):
        src = ColumnDataSource(data, name=f"cells-{k}")
        cds.append(src)
        views = []
        head = wrap_title(panel.label)  # a title is cut at the figure's edge: wrap the label
        for kind in ("regimes", "drift"):
            fig = figure(width=360 if kind == "regimes" else 430, height=345, x_range=x_range,
                         y_range=y_range, tools="pan,wheel_zoom,box_zoom,reset,save",
                         active_scroll="wheel_zoom", title=f"{head}\n"
                         + ("regimes" if kind == "regimes" else "drift ratio"),
                         name=f"{kind}-{k}", **axis_type)
            fig.xaxis.axis_label, fig.yaxis.axis_label = xa.label, ya.label
            _device_axes(fig, xa, ya)
            fig.toolbar.logo, fig.toolbar.autohide = None, True
            fill = ({"field": "regime", "transform": regimes} if kind == "regimes"
                    else {"field": "drift_ratio", "transform": drift})
            shape = ({"left": "left", "right": "right", "bottom": "bottom", "top": "top"}
                     if panel.quads is not None else {"xs": "xs", "ys": "ys"})
            draw = fig.quad if panel.quads is not None else fig.patches
            cells = draw(**shape, source=src, fill_color=fill, line_color=None,
                         selection_line_color="black", selection_line_width=2.5)
            cells.nonselection_glyph = cells.glyph
            fig.add_tools(HoverTool(renderers=[cells], tooltips=_tooltip(panel.label, xa, ya, info),
                                    formatters=formatters), TapTool(renderers=[cells]))
            if kind == "regimes":
                overlays.append(_regime_marks(fig, draw, shape, src, data, marks[k]))
                titles.append(fig.title)
                base.append(f"{head}\nregimes")
            else:
                fig.add_layout(ColorBar(color_mapper=drift, width=10, title="drift ratio"), "right")
                _unsettled_marks(fig, draw, shape, src, data)
            views.append(fig)
        rows.append(row(*views))
    trace, t_range, y_ranges, trace_figs, trace_info = _trace_panel(fields, info)
    labels = [p.label for p in panels]
    tap = CustomJS(args={"sources": cds, "labels": labels, "trace": trace, "info": trace_info,
                         "blob": blob, "m": m, "fields": fields, "no_traces": NO_TRACES,
                         "xlabel": xa.label, "ylabel": ya.label, "t_range": t_range,
                         "y_ranges": y_ranges}, code=_TAP_JS)
    for src in cds:
        src.selected.js_on_change("indices", tap)
    controls = _compare_controls(labels, cds, overlays, titles, base, page.marks, info)
    stored = (f"{info['stored']} of {info['cells']} cells have a stored trace: click one."
              if info["stored"] else f"<b>{NO_TRACES}</b>")
    header = Div(width=1250, name="header", text=(
        f"<h2 style='margin:4px 0'>sawdrift explorer: {html.escape(info['name'])}</h2>"
        f"<div>{info['cells']} cells in {len(panels)} panel(s); sawdrift "
        f"{html.escape(str(info['version']))}. Hover a cell for its metrics; zoom and pan move every "
        f"diagram together. {stored}</div><div style='margin-top:4px'>{_swatches()}</div>"))
    side = column(trace_info, *trace_figs)
    doc = Document()
    doc.add_root(column(header, controls, row(column(*rows), side)))
    doc.js_on_event("document_ready", CustomJS(code="window.__sawdrift_ready = true;"))
    doc.title = f"sawdrift explorer: {info['name']}"
    return doc
