/* rockscreen report: small SVG charts drawn from the embedded data (no library). */
"use strict";
var RS = window.RS || {};
window.RS = RS;
RS.SVG = "http://www.w3.org/2000/svg";
RS.PALETTE = ["#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000"];

RS.el = function (name, attrs, parent) {
  var node = document.createElementNS(RS.SVG, name);
  Object.keys(attrs || {}).forEach(function (k) { node.setAttribute(k, attrs[k]); });
  if (parent) { parent.appendChild(node); }
  return node;
};

RS.text = function (parent, x, y, content, attrs) {
  var node = RS.el("text", Object.assign({ x: x, y: y }, attrs || {}), parent);
  node.textContent = content;
  return node;
};

/* Decode a reduced series: base64 int16 (min, max) pairs per bin -> [[t, v], ...]. */
RS.decode = function (series) {
  if (!series || !series.data) { return []; }
  var raw = atob(series.data);
  var view = new DataView(new ArrayBuffer(raw.length));
  for (var i = 0; i < raw.length; i++) { view.setUint8(i, raw.charCodeAt(i)); }
  var n = raw.length / 4, k = series.scale / 32767, points = [];
  for (var b = 0; b < n; b++) {
    var lo = view.getInt16(4 * b, true) * k, hi = view.getInt16(4 * b + 2, true) * k;
    var t = series.t0 + b * series.dt;
    /* min then max, or max then min, whichever continues the line from the previous bin */
    var last = points.length ? points[points.length - 1][1] : 0;
    if (Math.abs(last - lo) <= Math.abs(last - hi)) {
      points.push([t, lo]); points.push([t + series.dt, hi]);
    } else {
      points.push([t, hi]); points.push([t + series.dt, lo]);
    }
  }
  return points;
};

RS.ticks = function (lo, hi, count, log) {
  if (log) {
    var out = [];
    for (var e = Math.floor(Math.log10(lo)); e <= Math.ceil(Math.log10(hi)); e++) {
      var v = Math.pow(10, e);
      if (v >= lo * 0.999 && v <= hi * 1.001) { out.push(v); }
    }
    return out.length ? out : [lo, hi];
  }
  var span = hi - lo || 1, step = Math.pow(10, Math.floor(Math.log10(span / count)));
  var err = span / count / step;
  step *= err >= 7.5 ? 10 : err >= 3.5 ? 5 : err >= 1.5 ? 2 : 1;
  var ticks = [];
  for (var t = Math.ceil(lo / step) * step; t <= hi + step * 1e-9; t += step) {
    ticks.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  }
  return ticks;
};

/* Number text with the page's decimal separator (RS.DECIMAL: "," in Italian). */
RS.DECIMAL = ".";
RS.fmt = function (value, digits) {
  if (value === null || value === undefined || value === "") { return "–"; }
  if (value === "inf") { return "∞"; }
  if (typeof value !== "number") { return String(value); }
  if (value === 0) { return "0"; }
  var a = Math.abs(value);
  var text = a >= 1e6 || a < 1e-3 ? value.toExponential(Math.max(digits - 1, 0)) : String(Number(value.toPrecision(digits)));
  return text.replace(".", RS.DECIMAL);
};

/* One chart: lines = [{label, points: [[x, y], ...], style, colour}]. */
RS.chart = function (opts) {
  var W = 880, H = opts.height || 260, L = 62, R = 14, T = 26, B = 40;
  var svg = RS.el("svg", { "class": "chart", viewBox: "0 0 " + W + " " + H, role: "img" });
  RS.el("title", {}, svg).textContent = opts.title;
  var xs = [], ys = [];
  opts.lines.forEach(function (line) {
    line.points.forEach(function (p) {
      if (isFinite(p[0]) && isFinite(p[1]) && (!opts.logx || p[0] > 0)) { xs.push(p[0]); ys.push(p[1]); }
    });
  });
  (opts.yExtra || []).forEach(function (y) { ys.push(y); });
  if (!xs.length) { return null; }
  var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
  if (opts.xRange) { x0 = opts.xRange[0]; x1 = opts.xRange[1]; }
  var y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
  if (opts.yRange) { y0 = opts.yRange[0]; y1 = opts.yRange[1]; }
  if (x1 === x0) { x1 = x0 + 1; }
  if (y1 === y0) { y0 -= 1; y1 += 1; }
  var pad = (y1 - y0) * 0.05;
  if (!opts.yRange) { y0 -= pad; y1 += pad; }
  var lx = function (x) { return opts.logx ? Math.log10(x) : x; };
  var sx = function (x) { return L + (lx(x) - lx(x0)) / (lx(x1) - lx(x0) || 1) * (W - L - R); };
  var sy = function (y) { return T + (y1 - y) / (y1 - y0) * (H - T - B); };
  RS.text(svg, L, 16, opts.title, { "font-weight": "bold" });
  RS.ticks(x0, x1, 8, opts.logx).forEach(function (t) {
    RS.el("line", { x1: sx(t), x2: sx(t), y1: T, y2: H - B, "class": "grid" }, svg);
    RS.text(svg, sx(t), H - B + 14, RS.fmt(t, 3), { "text-anchor": "middle" });
  });
  RS.ticks(y0, y1, 5).forEach(function (t) {
    RS.el("line", { x1: L, x2: W - R, y1: sy(t), y2: sy(t), "class": "grid" }, svg);
    RS.text(svg, L - 5, sy(t) + 4, RS.fmt(t, 3), { "text-anchor": "end" });
  });
  RS.el("rect", { x: L, y: T, width: W - L - R, height: H - T - B, fill: "none", "class": "axis" }, svg);
  RS.text(svg, (L + W - R) / 2, H - 6, opts.xlabel, { "text-anchor": "middle" });
  RS.text(svg, 14, (T + H - B) / 2, opts.ylabel,
    { "text-anchor": "middle", transform: "rotate(-90 14 " + (T + H - B) / 2 + ")" });
  (opts.bounds || []).forEach(function (b) {
    if (b >= y0 && b <= y1) { RS.el("line", { x1: L, x2: W - R, y1: sy(b), y2: sy(b), "class": "bound" }, svg); }
  });
  var legendX = L + 8;
  opts.lines.forEach(function (line, i) {
    var colour = line.colour || RS.PALETTE[i % RS.PALETTE.length];
    var pts = line.points.filter(function (p) { return isFinite(p[1]) && (!opts.logx || p[0] > 0); });
    if (line.style === "points") {
      pts.forEach(function (p) {
        RS.el("circle", { cx: sx(p[0]), cy: sy(p[1]), r: 4, fill: colour, stroke: "#000", "stroke-width": 0.6 }, svg);
      });
    } else {
      var d = pts.map(function (p) { return sx(p[0]).toFixed(1) + "," + sy(p[1]).toFixed(1); }).join(" ");
      RS.el("polyline", { points: d, fill: "none", stroke: colour, "stroke-width": 1.3,
        "stroke-dasharray": line.style === "dashed" ? "6 4" : "none" }, svg);
    }
    if (line.label) {
      RS.el("rect", { x: legendX - 4, y: T + 3 + 14 * i, width: 7 * line.label.length + 24, height: 14,
        fill: "#fff", opacity: 0.85 }, svg);
      RS.el("rect", { x: legendX, y: T + 6 + 14 * i, width: 10, height: 10, fill: colour }, svg);
      RS.text(svg, legendX + 14, T + 15 + 14 * i, line.label);
    }
  });
  return svg;
};
