/* rockscreen report: table (sort, filter, CSV), tower sheets, wiring. Data: #report-data. */
"use strict";
(function () {
  var RS = window.RS;
  var data = JSON.parse(document.getElementById("report-data").textContent);
  var T = data.strings;
  RS.data = data;
  RS.DECIMAL = T.decimal || ".";
  var classIndex = {};
  data.classes.forEach(function (c, i) { classIndex[c.key] = i; });
  RS.classRank = function (key) { return key in classIndex ? classIndex[key] : data.classes.length; };
  RS.classColour = function (key) { return key in classIndex ? data.classes[classIndex[key]].colour : "#999999"; };
  RS.classLabel = function (key) { return key in classIndex ? data.classes[classIndex[key]].label : key; };

  function h(tag, attrs, text) {
    var node = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) { node.setAttribute(k, attrs[k]); });
    if (text !== undefined) { node.textContent = text; }
    return node;
  }
  function header(col) { return col.label + (col.unit ? " [" + col.unit + "]" : ""); }

  /* ---------------------------------------------------------------- legend */
  var legend = document.getElementById("legend");
  var counts = {};
  data.towers.forEach(function (t) { counts[t.risk_class] = (counts[t.risk_class] || 0) + 1; });
  data.classes.forEach(function (c) {
    if (!counts[c.key]) { return; }
    var item = h("span");
    var sw = h("span", { "class": "sw" }); sw.style.background = c.colour;
    item.appendChild(sw); item.appendChild(document.createTextNode(c.label + " (" + counts[c.key] + ")"));
    legend.appendChild(item);
  });
  if ((data.stations || []).length) { legend.appendChild(h("span", {}, "△ " + T.map_station)); }
  if ((data.contours || []).length) { legend.appendChild(h("span", {}, "— " + T.map_contour)); }
  var unplaced = data.towers.filter(function (t) { return t.lat === null || t.lon === null; });
  if (unplaced.length) {
    legend.appendChild(h("span", { "class": "muted" }, unplaced.length + " " + (unplaced.length === 1 ? T.map_no_coords_one : T.map_no_coords) + ": " +
      unplaced.slice(0, 10).map(function (t) { return t.id; }).join(", ")));
  }

  /* ---------------------------------------------------------------- table */
  /* riskiest first: by class when the table has one, else unsorted (archive order) */
  var hasClass = data.columns.some(function (c) { return c.key === "risk_class"; });
  var state = { key: hasClass ? "risk_class" : "", dir: 1, text: "", cls: "" };
  var table = document.getElementById("towers");
  var thead = h("thead"), tbody = h("tbody"), headRow = h("tr");
  data.columns.forEach(function (col) {
    var th = h("th", { scope: "col", "data-key": col.key, tabindex: 0 }, header(col));
    th.addEventListener("click", function () { sortBy(col.key); });
    th.addEventListener("keydown", function (ev) { if (ev.key === "Enter") { sortBy(col.key); } });
    headRow.appendChild(th);
  });
  thead.appendChild(headRow); table.appendChild(thead); table.appendChild(tbody);
  var select = document.getElementById("class-filter");
  select.appendChild(h("option", { value: "" }, T.all));
  data.classes.forEach(function (c) { if (counts[c.key]) { select.appendChild(h("option", { value: c.key }, c.label)); } });

  function value(t, col) {
    var v = t[col.key];
    if (col.kind === "class") { return RS.classRank(v); }
    if (col.kind === "num") { return v === "inf" ? Infinity : (v === null || v === undefined ? null : v); }
    return v === null || v === undefined ? "" : String(v).toLowerCase();
  }
  function visible() {
    var needle = state.text.toLowerCase();
    var rows = data.towers.filter(function (t) {
      if (state.cls && t.risk_class !== state.cls) { return false; }
      if (!needle) { return true; }
      return data.columns.some(function (col) { return String(t[col.key] === null ? "" : t[col.key]).toLowerCase().indexOf(needle) >= 0; });
    });
    if (state.key) {
      var col = data.columns.filter(function (c) { return c.key === state.key; })[0];
      rows.sort(function (a, b) {
        var x = value(a, col), y = value(b, col);
        if (x === null && y === null) { return 0; }
        if (x === null) { return 1; }
        if (y === null) { return -1; }
        return (x < y ? -1 : x > y ? 1 : 0) * state.dir;
      });
    }
    return rows;
  }
  function bound(t, col) { return (t.bounds && t.bounds[col.key]) || ""; }
  function cellText(t, col) {
    var v = t[col.key];
    if (col.kind === "class") { return RS.classLabel(v); }
    if (col.labels && v && T[col.labels + v]) { return T[col.labels + v]; }
    if (col.kind === "num") { return (bound(t, col) ? bound(t, col) + " " : "") + RS.fmt(v, col.digits); }
    return v === null || v === undefined ? "" : String(v);
  }
  function renderTable() {
    var rows = visible();
    var frag = document.createDocumentFragment();
    rows.forEach(function (t) {
      var tr = h("tr", { "data-id": t.id });
      if (t.id === RS.selected) { tr.className = "selected"; }
      data.columns.forEach(function (col) {
        var td = h("td", col.kind === "num" ? { "class": "num" } : {});
        if (col.kind === "class") {
          var badge = h("span", { "class": "cls" }, cellText(t, col));
          badge.style.background = RS.classColour(t.risk_class);
          badge.style.color = RS.classRank(t.risk_class) <= 1 ? "#fff" : "#000";
          td.appendChild(badge);
        } else {
          td.textContent = cellText(t, col);
          if (col.kind === "text") { td.title = td.textContent; }
          if (bound(t, col)) { td.title = bound(t, col) === ">" ? T.lower_bound_hint : T.upper_bound_hint; }
        }
        tr.appendChild(td);
      });
      tr.addEventListener("click", function () { openSheet(t.id); });
      frag.appendChild(tr);
    });
    tbody.textContent = "";
    tbody.appendChild(frag);
    document.getElementById("count").textContent = rows.length + " / " + data.towers.length + " " + T.shown;
    Array.prototype.forEach.call(headRow.children, function (th) {
      th.removeAttribute("aria-sort");
      if (th.getAttribute("data-key") === state.key) { th.setAttribute("aria-sort", state.dir > 0 ? "ascending" : "descending"); }
    });
  }
  function sortBy(key) {
    state.dir = state.key === key ? -state.dir : 1;
    state.key = key;
    renderTable();
  }
  document.getElementById("filter").addEventListener("input", function (ev) { state.text = ev.target.value; renderTable(); });
  select.addEventListener("change", function (ev) { state.cls = ev.target.value; renderTable(); });

  /* CSV of the rows shown; cells that a spreadsheet would run as a formula are neutralised. */
  RS.csvCell = function (text) {
    text = String(text);
    if (/^[=+\-@\t\r]/.test(text)) { text = "'" + text; }
    return /[",\n\r]/.test(text) ? "\"" + text.replace(/"/g, "\"\"") + "\"" : text;
  };
  RS.csv = function () {
    var lines = [data.columns.map(function (c) { return RS.csvCell(header(c)); }).join(",")];
    visible().forEach(function (t) {
      lines.push(data.columns.map(function (col) {
        var v = t[col.key];
        if (v === null || v === undefined) { return ""; }
        return RS.csvCell(col.kind === "class" ? v : v === "inf" ? "inf" : bound(t, col) + v);
      }).join(","));
    });
    return lines.join("\r\n") + "\r\n";
  };
  document.getElementById("export").addEventListener("click", function () {
    var blob = new Blob(["\ufeff" + RS.csv()], { type: "text/csv;charset=utf-8" });
    var a = h("a", { href: URL.createObjectURL(blob), download: "rockscreen-towers.csv" });
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(function () { URL.revokeObjectURL(a.href); }, 1000);
  });

  /* ---------------------------------------------------------------- sheet */
  function historyFigure(fig) {
    var wrap = h("div");
    var lines = fig.series.map(function (s) { return { label: s.label, points: RS.decode(s) }; });
    var chart = RS.chart({ title: fig.title, xlabel: fig.xlabel, ylabel: fig.ylabel, lines: lines,
      bounds: fig.bounds ? [-1, 1] : [], yExtra: fig.bounds ? [-1.05, 1.05] : [] });
    if (chart) { wrap.appendChild(chart); }
    var ends = [];
    lines.forEach(function (l) { l.points.forEach(function (p) { ends.push(p[0]); }); });
    var range = ends.length ? [Math.min.apply(null, ends), Math.max.apply(null, ends)] : null;
    var seen = {};
    fig.series.forEach(function (s) {
      var m = s.ref && data.motions[s.ref];
      if (!m || seen[s.ref]) { return; }
      seen[s.ref] = true;
      var mc = RS.chart({ title: T.s_motion + ": " + m.label, xlabel: T.s_time, ylabel: T.s_acc, height: 170,
        lines: [{ label: "", points: RS.decode(m), colour: "#555555" }], xRange: range });
      if (mc) { wrap.appendChild(mc); }
    });
    return wrap;
  }
  function xyFigure(fig) {
    var lines = fig.curves.map(function (c) {
      return { label: c.label, style: c.style, points: c.x.map(function (x, i) { return [x, c.y[i]]; }) };
    });
    var opts = { title: fig.title, xlabel: fig.xlabel, ylabel: fig.ylabel, lines: lines, logx: fig.logx };
    if (fig.yrange) { opts.yRange = fig.yrange; }
    if (fig.xrange && !fig.logx) { opts.xRange = fig.xrange; }
    return RS.chart(opts);
  }
  function openSheet(id) {
    var sheet = data.sheets[id];
    var tower = data.towers.filter(function (t) { return t.id === id; })[0];
    if (!sheet || !tower) { return; }
    RS.selected = id;
    var box = document.getElementById("sheet");
    box.textContent = "";
    box.hidden = false;
    var head = h("div", { "class": "sheet-head" });
    var title = h("h3", { id: "sheet-title" }, T.sec_sheet + ": " + id);
    var badge = h("span", { "class": "cls" }, RS.classLabel(tower.risk_class));
    badge.style.background = RS.classColour(tower.risk_class);
    badge.style.color = RS.classRank(tower.risk_class) <= 1 ? "#fff" : "#000";
    title.appendChild(document.createTextNode(" ")); title.appendChild(badge);
    var close = h("button", { type: "button" }, T.s_close);
    close.addEventListener("click", function () { box.hidden = true; RS.selected = null; if (RS.map) { RS.map.select(null); } renderTable(); });
    head.appendChild(title); head.appendChild(close); box.appendChild(head);
    box.appendChild(h("h3", {}, T.s_verdict));
    var verdict = h("div", { "class": "verdict" });
    sheet.verdict.forEach(function (line) { verdict.appendChild(h("p", {}, line)); });
    box.appendChild(verdict);
    if (sheet.risk && sheet.risk.length) {
      /* the screening risk: its own heading, apart from the code's verdict */
      box.appendChild(h("h3", { "class": "risk-head" }, T.s_risk));
      var risk = h("div", { "class": "verdict risk" });
      sheet.risk.forEach(function (line) { risk.appendChild(h("p", {}, line)); });
      box.appendChild(risk);
      if (sheet.sensitivity && sheet.sensitivity.length) {
        var sens = h("table", { "class": "sens" });
        var cap = h("caption", {}, T.s_sensitivity); sens.appendChild(cap);
        var sh = h("tr");
        [T.s_sens_input, T.s_sens_index, "", T.s_sens_narrowing].forEach(function (label) { sh.appendChild(h("th", { scope: "col" }, label)); });
        var shead = h("thead"); shead.appendChild(sh); sens.appendChild(shead);
        var sbody = h("tbody");
        sheet.sensitivity.forEach(function (bar) {
          var tr = h("tr");
          tr.appendChild(h("th", { scope: "row" }, bar[0] + (bar[4] ? " (" + T.judgement + ")" : "")));
          tr.appendChild(h("td", { "class": "num" }, bar[2]));
          var cell = h("td", { "class": "bar" });
          var fill = h("span", { "class": bar[4] ? "fill judgement" : "fill" });
          fill.style.width = Math.max(0, Math.min(1, bar[1] || 0)) * 100 + "%";
          cell.appendChild(fill); tr.appendChild(cell);
          tr.appendChild(h("td", { "class": "num" }, bar[3]));
          sbody.appendChild(tr);
        });
        sens.appendChild(sbody);
        box.appendChild(sens);
      }
    }
    if (sheet.checks && sheet.checks.length) {
      box.appendChild(h("h3", {}, T.s_code_verdict + ": " + T.s_checks));
      var checks = h("table", { "class": "checks" });
      var headRow = h("tr");
      [T.s_check_col, T.s_ac_col, T.s_is_col, T.s_detail_col].forEach(function (label) { headRow.appendChild(h("th", { scope: "col" }, label)); });
      var thead = h("thead"); thead.appendChild(headRow); checks.appendChild(thead);
      var tbody = h("tbody");
      sheet.checks.forEach(function (cells) {
        var tr = h("tr");
        cells.forEach(function (cell, i) { tr.appendChild(h(i === 0 ? "th" : "td", i === 0 ? { scope: "row" } : {}, cell)); });
        tbody.appendChild(tr);
      });
      checks.appendChild(tbody);
      box.appendChild(checks);
      sheet.checks_text.forEach(function (line) { box.appendChild(h("p", { "class": "checks-text" }, line)); });
    }
    box.appendChild(h("h3", {}, T.s_inputs));
    var dl = h("dl", { "class": "kv" });
    sheet.inputs.forEach(function (pair) { dl.appendChild(h("dt", {}, pair[0])); dl.appendChild(h("dd", {}, pair[1])); });
    box.appendChild(dl);
    var charts = h("div", { "class": "charts" });
    sheet.figures.forEach(function (fig) {
      var node = fig.kind === "history" ? historyFigure(fig) : xyFigure(fig);
      if (node) { charts.appendChild(node); }
    });
    if (!sheet.figures.length) { charts.appendChild(h("p", { "class": "muted" }, T.s_no_history)); }
    box.appendChild(charts);
    if (sheet.notes.length) {
      box.appendChild(h("h3", {}, T.s_notes));
      var ul = h("ul");
      sheet.notes.forEach(function (n) { ul.appendChild(h("li", {}, n)); });
      box.appendChild(ul);
    }
    if (RS.map) { RS.map.select(id); }
    renderTable();
    box.scrollIntoView({ block: "start" });
    if (history.replaceState) { history.replaceState(null, "", "#tower=" + encodeURIComponent(id)); }
  }
  RS.openSheet = openSheet;
  /* the ranked list of the first screen (assess): a row opens its tower's sheet */
  Array.prototype.forEach.call(document.querySelectorAll("#risk-list tbody tr[data-id]"), function (tr) {
    tr.addEventListener("click", function () { openSheet(tr.getAttribute("data-id")); });
  });

  /* ---------------------------------------------------------------- map and start */
  RS.map = RS.buildMap(document.getElementById("map"), data, openSheet);
  var bg = document.getElementById("background");
  if (bg && RS.map) { bg.addEventListener("change", function () { RS.map.setTiles(bg.checked); }); }
  var reset = document.getElementById("reset");
  if (reset && RS.map) { reset.addEventListener("click", function () { RS.map.reset(); }); }
  renderTable();
  var match = /^#tower=(.*)$/.exec(location.hash);
  if (match) { openSheet(decodeURIComponent(match[1])); }
  document.documentElement.setAttribute("data-ready", "1");
})();
