"""How the study report's figures sit in its page (:mod:`.study_report`), self-contained.

The page carries plotly.js once and each figure as a data block, both
gzip-compressed and base64-encoded inside ``<script type="application/octet-stream">``
elements (inert: the browser neither runs nor shows them); the page's
:data:`LOADER_SCRIPT` decompresses them with the browser's own
``DecompressionStream`` (Chromium and Edge 80+, Firefox 113+, Safari 16.4+),
runs plotly.js and draws the figures. No network: the page opens offline.

* **plotly.js**: the ``plotly.min.js`` that the installed plotly package ships,
  byte for byte, compressed (:func:`plotly_block`; 4.8 MB, 1.96 MB as it sits
  in the page for plotly.js 4.1.1), in ``<script id="tyrelab-plotly">``.
* **A figure** (:func:`pack_figure`): gzip of ``[u32 length][JSON][binary arrays]``;
  the JSON is the plotly figure (``data``, ``layout``, ``config``) where each
  packed array is a reference ``{"tyrelab_array": 1, "dtype", "at", "n",
  "offset", "scale", "base", "cumsum", "zigzag"}`` to ``n`` numbers of
  ``dtype`` (``u1``, ``u2``, ``u4``, ``f8``) at byte ``at`` of the binary part
  (8-byte aligned), stored as byte planes (the numbers' first little-endian
  bytes, then their second bytes, ...: gzip finds the slowly changing high
  bytes together). Stored number ``r_i`` becomes ``v_i = r_i``, or with
  ``zigzag`` ``(r_i >> 1) ^ -(r_i & 1)`` (0, 1, 2, 3, ... for 0, -1, 1, -2,
  ...); ``w_i`` is ``v_i`` or, with ``cumsum``, ``v_0 + ... + v_i``; the value
  is ``offset + scale * (base + w_i)``.

What is stored (``packed=True``, the overlays): every trace's ``x`` and ``y``.
Times on a uniform grid (every run's output) are stored as the grid steps
between kept samples (``cumsum``): exact to float64 rounding; other times as
``f8``. Values are rounded to the figure's *quantum* (:func:`value_quantum`:
the smallest 1, 2 or 5 x 10^k giving at most :data:`LEVELS` steps over the
figure's range, i.e. 4.4-4.8 significant digits of the range, 0.2 N to 2 N on a
wheel-load figure; a plot area is a few hundred pixels high) and stored as
the change in quanta from one point to the next (``zigzag``, ``cumsum``).
Other arrays (distributions, the cost scatter) are written in the JSON to
:data:`SIGNIFICANT` significant digits. With ``exact=True`` (the
full-resolution page) nothing is rounded: values as ``f8``, times as grid
steps or ``f8``, other arrays as Python writes them.

:func:`unpack_figure` reads a block back (what the loader does, in Python):
the tests check the page against the study's signals with it.

The page's self-checks: :data:`ERRORS_SCRIPT` (first in the page) records
script errors; the loader stamps each drawn figure's div with
``data-points`` (numbers drawn) and ``data-trace-extremes`` (each trace's
smallest and largest ``y`` as decoded, ``min max`` per trace, ``;`` between
traces) and fires ``tyrelab-figures-drawn`` when done; :data:`RENDERED_SCRIPT`
(last) then counts the figures plotly drew.
"""

from __future__ import annotations

import base64
import functools
import gzip
import html
import json
import math
import re
import struct

import numpy as np

#: most quantum steps over a packed figure's value range (u2 holds 65 535)
LEVELS = 65_000
#: significant digits of the numbers of unpacked arrays
SIGNIFICANT = 5

_CONFIG = {"displaylogo": False, "responsive": True, "scrollZoom": False,
           "modeBarButtonsToRemove": ["select2d", "lasso2d"]}

#: the page's first script: records script errors, failed resource loads, unhandled
#: promise rejections and ``console.error`` calls in ``<pre id="tyrelab-errors">``
ERRORS_SCRIPT = """<script>(function () {
  var errors = [];
  function show() {
    var el = document.getElementById('tyrelab-errors');
    if (el) { el.textContent = errors.join('\\n'); }
    if (errors.length) { document.documentElement.setAttribute('data-script-errors', errors.length); }
  }
  function record(msg) { errors.push(String(msg)); show(); }
  window.addEventListener('error', function (e) {
    if (e.target && e.target !== window && (e.target.src || e.target.href)) {
      record('failed to load ' + (e.target.src || e.target.href));
    } else {
      record('error: ' + e.message + ' (' + (e.filename || '') + ':' + (e.lineno || 0) + ')');
    }
  }, true);
  window.addEventListener('unhandledrejection', function (e) {
    var r = e.reason; record('unhandled rejection: ' + ((r && r.stack) || r));
  });
  var consoleError = console.error;
  console.error = function () {
    record('console.error: ' + Array.prototype.slice.call(arguments).join(' '));
    return consoleError.apply(console, arguments);
  };
  document.addEventListener('DOMContentLoaded', show);
})();</script>"""

#: after every figure's data block: decompresses plotly.js and the figures, draws them in
#: page order, stamps each div (module docstring), then fires ``tyrelab-figures-drawn``
LOADER_SCRIPT = """<script>(function () {
  'use strict';
  var DTYPES = {u1: Uint8Array, u2: Uint16Array, u4: Uint32Array, f8: Float64Array};
  var blocks = Array.prototype.slice.call(document.querySelectorAll('script.tyrelab-figure-data'));
  function finished() {
    window.tyrelabFiguresDrawn = true;
    document.dispatchEvent(new Event('tyrelab-figures-drawn'));
  }
  function bytes(el) {
    var s = atob(el.textContent), b = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) { b[i] = s.charCodeAt(i); }
    return b;
  }
  function gunzip(el) {
    var stream = new Response(bytes(el)).body.pipeThrough(new DecompressionStream('gzip'));
    return new Response(stream).arrayBuffer();
  }
  function unpack(node, buf, start) {
    if (Array.isArray(node)) { return node.map(function (v) { return unpack(v, buf, start); }); }
    if (node === null || typeof node !== 'object') { return node; }
    if (node.tyrelab_array) {
      var T = DTYPES[node.dtype], k = T.BYTES_PER_ELEMENT, n = node.n, i, j, v, w = 0;
      var planes = new Uint8Array(buf, start + node.at, n * k), le = new Uint8Array(n * k);
      for (j = 0; j < k; j++) { for (i = 0; i < n; i++) { le[i * k + j] = planes[j * n + i]; } }
      var raw = new T(le.buffer), out = new Float64Array(n);
      for (i = 0; i < n; i++) {
        v = node.zigzag ? (raw[i] >>> 1) ^ -(raw[i] & 1) : raw[i];
        w = node.cumsum ? w + v : v;
        out[i] = node.offset + node.scale * (node.base + w);
      }
      return out;
    }
    var copy = {};
    for (var k in node) { copy[k] = unpack(node[k], buf, start); }
    return copy;
  }
  function figure(buf) {
    var n = new DataView(buf).getUint32(0, true);
    var spec = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, n)));
    spec.data = unpack(spec.data, buf, (4 + n + 7) & ~7);
    return spec;
  }
  function stamp(div, data) {
    var points = 0, extremes = [];
    data.forEach(function (trace) {
      var y = trace.y || [], lo = Infinity, hi = -Infinity;
      points += (trace.x ? trace.x.length : 0) + y.length;
      for (var i = 0; i < y.length; i++) {
        if (typeof y[i] === 'number') { lo = Math.min(lo, y[i]); hi = Math.max(hi, y[i]); }
      }
      extremes.push(lo + ' ' + hi);
    });
    div.setAttribute('data-points', String(points));
    div.setAttribute('data-trace-extremes', extremes.join(';'));
  }
  function failed(div, err) {
    div.textContent = 'Figure not drawn: ' + err;
    console.error('figure ' + div.id + ' not drawn: ' + ((err && err.stack) || err));
  }
  if (!blocks.length) { finished(); return; }
  var divs = blocks.map(function (el) { return document.getElementById(el.getAttribute('data-figure')); });
  if (typeof DecompressionStream === 'undefined') {
    divs.forEach(function (div) { failed(div, 'this browser cannot decompress the figures '
                                          + '(no DecompressionStream; any browser from 2023 on can)'); });
    finished();
    return;
  }
  gunzip(document.getElementById('tyrelab-plotly')).then(function (buf) {
    window.PlotlyConfig = {MathJaxConfig: 'local'};
    var lib = document.createElement('script');
    lib.textContent = new TextDecoder().decode(buf);
    document.head.appendChild(lib);
    if (!window.Plotly) { throw new Error('plotly.js did not load'); }
    var specs = blocks.map(function (el) { return gunzip(el).then(figure); });
    return specs.reduce(function (chain, spec, i) {
      return chain.then(function () { return spec; }).then(function (s) {
        stamp(divs[i], s.data);
        return Plotly.newPlot(divs[i], s.data, s.layout, s.config);
      }).catch(function (err) { failed(divs[i], err); });
    }, Promise.resolve());
  }).catch(function (err) {
    divs.forEach(function (div) { failed(div, err); });
  }).then(finished);
})();</script>"""

#: the page's last script: once the loader is done, sets the body's ``data-figures-rendered``
#: to the number of drawn figures (``.js-plotly-plot`` holding an ``svg.main-svg``) and
#: ``data-figures-done`` to "yes" if that reaches ``<meta name="tyrelab-figures">``, else "no"
RENDERED_SCRIPT = """<script>(function () {
  var meta = document.querySelector('meta[name="tyrelab-figures"]');
  var want = meta ? Number(meta.content) : 0;
  function count() {
    var n = 0, divs = document.querySelectorAll('.js-plotly-plot');
    for (var i = 0; i < divs.length; i++) { if (divs[i].querySelector('svg.main-svg')) { n++; } }
    return n;
  }
  function mark() {
    var n = count();
    document.body.setAttribute('data-figures-rendered', String(n));
    document.body.setAttribute('data-figures-done', n >= want ? 'yes' : 'no');
  }
  if (window.tyrelabFiguresDrawn) { mark(); }
  else { document.addEventListener('tyrelab-figures-drawn', mark); }
})();</script>"""


def _e(x) -> str:
    return html.escape(str(x))


def _b64gzip(data: bytes) -> str:
    return base64.b64encode(gzip.compress(data, compresslevel=9, mtime=0)).decode("ascii")


@functools.lru_cache(maxsize=1)
def _plotly() -> tuple[str, str]:
    from plotly.offline import get_plotlyjs
    js = get_plotlyjs()
    version = re.search(r"plotly\.js v([\w.\-]+)", js[:200])
    return (version.group(1) if version else "unknown"), _b64gzip(js.encode("utf-8"))


def plotly_block() -> str:
    """plotly.js, once: the installed package's ``plotly.min.js``, gzip + base64."""
    version, data = _plotly()
    return (f"<script type='application/octet-stream' id='tyrelab-plotly' data-library='plotly.min.js' "
            f"data-version='{_e(version)}' data-encoding='gzip+base64'>{data}</script>")


def value_quantum(lo: float, hi: float) -> float:
    """The step values in ``[lo, hi]`` are rounded to: the smallest 1, 2 or 5 x 10^k
    giving at most :data:`LEVELS` steps over the range (the size of the larger end
    when the range is empty)."""
    span = float(hi) - float(lo)
    if not span > 0:
        span = max(abs(float(lo)), abs(float(hi))) or 1.0
    k = math.floor(math.log10(span / LEVELS))
    return next(q for q in (m * 10.0 ** k for m in (1, 2, 5, 10)) if span / q <= LEVELS)


def _round_sig(v: float) -> float | None:
    return float(f"{v:.{SIGNIFICANT}g}") if math.isfinite(v) else None


def _plain(node, exact: bool, listed: bool = False):
    """JSON-ready: arrays as lists, their numbers to :data:`SIGNIFICANT` digits unless
    ``exact`` (single numbers, such as a segment's bounds, as they are); numpy scalars
    as Python's; non-finite numbers as null."""
    if isinstance(node, dict):
        if "tyrelab_array" in node:
            return node
        if "bdata" in node and "dtype" in node:       # plotly's typed array: read it back
            kind = np.dtype(node["dtype"]).newbyteorder("<")
            a = np.frombuffer(base64.b64decode(node["bdata"]), dtype=kind)
            shape = node.get("shape")
            if shape:
                a = a.reshape([int(v) for v in str(shape).split(",")])
            return _plain(a, exact)
        return {k: _plain(v, exact) for k, v in node.items()}
    if isinstance(node, np.ndarray):
        node = node.tolist()
    if isinstance(node, (list, tuple)):
        return [_plain(v, exact, True) for v in node]
    if isinstance(node, np.generic):
        node = node.item()
    if isinstance(node, float):
        if not math.isfinite(node):
            return None
        return _round_sig(node) if listed and not exact else node
    return node


class _Arrays:
    """The binary part of a block: arrays appended 8-byte aligned, each as byte planes."""

    def __init__(self):
        self.data = bytearray()

    def add(self, raw: np.ndarray, offset=0.0, scale=1.0, base=0, cumsum=False, zigzag=False) -> dict:
        raw = np.ascontiguousarray(raw, dtype=raw.dtype.newbyteorder("<"))
        self.data += b"\0" * (-len(self.data) % 8)
        ref = {"tyrelab_array": 1, "dtype": raw.dtype.str[1:], "at": len(self.data), "n": int(raw.size),
               "offset": float(offset), "scale": float(scale), "base": int(base), "cumsum": bool(cumsum),
               "zigzag": bool(zigzag)}
        self.data += raw.view(np.uint8).reshape(-1, raw.itemsize).T.tobytes()
        return ref


def _uint(a: np.ndarray) -> np.ndarray:
    top = int(a.max()) if a.size else 0
    return a.astype("u1" if top < 2 ** 8 else "u2" if top < 2 ** 16 else "u4")


def _pack_times(t: np.ndarray, arrays: _Arrays) -> dict:
    """Times on a uniform grid as grid steps between samples (exact to float64 rounding);
    any others as f8."""
    d = np.diff(t)
    if t.size > 2 and np.all(d > 0):
        for m in (1, 2, 3, 4):
            step0 = d.min() / m
            ticks = np.round((t - t[0]) / step0)
            step = (t[-1] - t[0]) / ticks[-1]
            if np.all(np.abs(t[0] + ticks * step - t) <= 1e-9 * max(1.0, np.abs(t).max())):
                k = ticks.astype(np.int64)
                return arrays.add(_uint(np.diff(k, prepend=0)), offset=t[0], scale=step, cumsum=True)
    return arrays.add(t.astype("<f8"))


def _pack_values(y: np.ndarray, q: float | None, arrays: _Arrays) -> dict:
    """Values as multiples of ``q``: the change from one to the next, zigzag-coded
    (0, -1, 1, -2, ... as 0, 1, 2, 3, ...); without ``q``, or with gaps, as f8."""
    if q is None or not np.all(np.isfinite(y)) or y.size == 0:
        return arrays.add(y.astype("<f8"))
    steps = np.round(y / q).astype(np.int64)
    d = np.diff(steps, prepend=steps[0])
    return arrays.add(_uint((d << 1) ^ (d >> 63)), scale=q, base=int(steps[0]), cumsum=True,
                      zigzag=True)


def pack_figure(fig, *, packed: bool, exact: bool = False) -> tuple[str, dict]:
    """A figure as the page's data block (gzip + base64 of the module docstring's layout).

    ``packed``: store every trace's ``x`` and ``y`` in the binary part (times exact,
    values rounded to the figure's :func:`value_quantum`), else everything in the
    JSON; ``exact``: round nothing. Returns the block's text and
    ``{"quantum": step values were rounded to or None, "points": numbers packed}``.
    """
    spec = fig.to_plotly_json()
    arrays, info = _Arrays(), {"quantum": None, "points": 0}
    data = spec.get("data", [])
    if packed:
        xy = [(tr, np.asarray(src.x, dtype=float), np.asarray(src.y, dtype=float))
              for tr, src in zip(data, fig.data) if src.x is not None and src.y is not None]
        ys = [y[np.isfinite(y)] for _, _, y in xy]
        ys = [y for y in ys if y.size]
        if ys and not exact:
            info["quantum"] = value_quantum(min(y.min() for y in ys), max(y.max() for y in ys))
        q = info["quantum"]
        for tr, x, y in xy:
            tr["x"], tr["y"] = _pack_times(x, arrays), _pack_values(y, q, arrays)
            info["points"] += x.size + y.size
    spec["config"] = _CONFIG
    text = json.dumps(_plain(spec, exact), separators=(",", ":"), allow_nan=False).encode("utf-8")
    block = struct.pack("<I", len(text)) + text
    block += b"\0" * (-len(block) % 8) + bytes(arrays.data)
    return _b64gzip(block), info


def unpack_figure(block: str) -> dict:
    """A data block read back (what the page's loader does): the plotly figure as a
    dict, packed arrays as float64 arrays."""
    raw = gzip.decompress(base64.b64decode(block))
    n = struct.unpack_from("<I", raw)[0]
    spec = json.loads(raw[4:4 + n].decode("utf-8"))
    start = (4 + n + 7) & ~7

    def walk(node):
        if isinstance(node, list):
            return [walk(v) for v in node]
        if not isinstance(node, dict):
            return node
        if node.get("tyrelab_array"):
            kind, n = np.dtype("<" + node["dtype"]), node["n"]
            planes = np.frombuffer(raw, np.uint8, n * kind.itemsize, start + node["at"])
            w = planes.reshape(kind.itemsize, n).T.copy().view(kind).ravel()
            if node["zigzag"]:
                w = (w.astype(np.int64) >> 1) ^ -(w.astype(np.int64) & 1)
            w = np.cumsum(w) if node["cumsum"] else w
            return node["offset"] + node["scale"] * (node["base"] + w.astype(float))
        return {k: walk(v) for k, v in node.items()}

    spec["data"] = walk(spec["data"])
    return spec


class FigureSink:
    """Numbers the page's figures and writes each as a div and its data block;
    ``exact`` (the full-resolution page) rounds nothing. plotly.js and the
    loader go into the page once, after the last figure (:func:`page_scripts`)."""

    def __init__(self, exact: bool = False, deferred: bool = False):
        """``deferred``: the figures are a part of a page built elsewhere (a study's worker):
        numbered ``tyrelab-fig-<k>`` for the page to number them in turn (:meth:`take`)."""
        self.count = 0
        self.exact = exact
        self.deferred = deferred

    def add(self, fig, kind: str, caption: str, *, packed: bool = False) -> str:
        self.count += 1
        div_id = f"tyrelab-fig-<{self.count}>" if self.deferred else f"tyrelab-fig-{self.count}"
        block, _ = pack_figure(fig, packed=packed, exact=self.exact)
        height = fig.layout.height or 420
        return (f"<figure class='tyrelab-figure' data-kind='{kind}'>"
                f"<div id='{div_id}' class='plotly-graph-div' style='height:{height}px;width:100%'></div>"
                f"<script type='application/octet-stream' class='tyrelab-figure-data' data-figure='{div_id}'"
                f" data-encoding='gzip+base64'>{block}</script>"
                f"<figcaption>{_e(caption)}</figcaption></figure>\n")

    def page_scripts(self) -> str:
        """plotly.js and the loader, once (nothing when the page has no figure)."""
        return (plotly_block() + "\n" + LOADER_SCRIPT) if self.count else ""

    def take(self, text: str, count: int) -> str:
        """The HTML ``text`` of ``count`` figures a deferred sink made, numbered after this
        sink's own: the page then reads as if this sink had made them. Captions are
        escaped, so "<" in the text is only ever in a deferred figure number."""
        first = self.count
        self.count += count
        return _DEFERRED_FIGURE.sub(lambda m: f"tyrelab-fig-{first + int(m[1])}", text)


#: a deferred sink's figure number (FigureSink(deferred=True))
_DEFERRED_FIGURE = re.compile(r"tyrelab-fig-<(\d+)>")
