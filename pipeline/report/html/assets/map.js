/* rockscreen report: the SVG map (Web Mercator, the projection of the optional tiles). */
"use strict";
(function () {
  var RS = window.RS;
  var TILE = 256;

  function world(lon, lat) {
    var s = Math.sin(Math.max(Math.min(lat, 85), -85) * Math.PI / 180);
    return [(lon + 180) / 360 * TILE, (0.5 - Math.log((1 + s) / (1 - s)) / (4 * Math.PI)) * TILE];
  }
  function latOf(y) {
    var n = Math.PI - 2 * Math.PI * y / TILE;
    return 180 / Math.PI * Math.atan(0.5 * (Math.exp(n) - Math.exp(-n)));
  }
  function niceLength(maxMetres) {
    var p = Math.pow(10, Math.floor(Math.log10(maxMetres)));
    var steps = [5, 2, 1];
    for (var i = 0; i < steps.length; i++) { if (steps[i] * p <= maxMetres) { return steps[i] * p; } }
    return p;
  }

  RS.buildMap = function (box, data, onPick) {
    var T = data.strings;
    var placed = data.towers.filter(function (t) { return t.lat !== null && t.lon !== null; });
    var stations = (data.stations || []).filter(function (s) { return s.lat !== null && s.lon !== null; });
    var pts = placed.map(function (t) { return world(t.lon, t.lat); })
      .concat(stations.map(function (s) { return world(s.lon, s.lat); }));
    (data.contours || []).forEach(function (c) {
      c.lines.forEach(function (line) { line.forEach(function (p) { pts.push(world(p[0], p[1])); }); });
    });
    if (!pts.length) { box.textContent = T.map_none; return null; }
    var svg = RS.el("svg", { role: "img", "aria-label": T.sec_map }, box);
    var gTiles = RS.el("g", {}, svg), gBase = RS.el("g", { "class": "basemap" }, svg);
    var gCont = RS.el("g", {}, svg), gSta = RS.el("g", {}, svg);
    var gLab = RS.el("g", { "pointer-events": "none" }, svg);
    var gTow = RS.el("g", {}, svg), gDeco = RS.el("g", {}, svg);
    var tip = document.createElement("div"); tip.className = "tooltip"; box.appendChild(tip);
    var attribution = document.createElement("div"); attribution.className = "attribution"; box.appendChild(attribution);
    var view = { cx: 0, cy: 0, k: 1 }, home = null, tiles = false, selected = null;

    /* the initial view (and "Reset view"): the towers with a margin (data.extent), not every
       station; without an extent, everything drawn */
    function fit() {
      var box0 = data.extent ? [world(data.extent[0], data.extent[3]), world(data.extent[2], data.extent[1])] : pts;
      var xs = box0.map(function (p) { return p[0]; }), ys = box0.map(function (p) { return p[1]; });
      var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
      var y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
      var w = box.clientWidth || 800, h = box.clientHeight || 500;
      var span = Math.max((x1 - x0) / (w - 40), (y1 - y0) / (h - 40), 1e-6);
      home = { cx: (x0 + x1) / 2, cy: (y0 + y1) / 2, k: Math.min(1 / span, Math.pow(2, 17)) };
      view = Object.assign({}, home);
    }
    function screen(p) {
      var w = box.clientWidth, h = box.clientHeight;
      return [(p[0] - view.cx) * view.k + w / 2, (p[1] - view.cy) * view.k + h / 2];
    }
    function clear(g) { while (g.firstChild) { g.removeChild(g.firstChild); } }

    function drawTiles() {
      clear(gTiles);
      attribution.textContent = tiles ? data.tiles.attribution : "";
      if (!tiles) { return; }
      var z = Math.max(0, Math.min(18, Math.round(Math.log2(view.k))));
      var n = Math.pow(2, z), size = TILE / n, w = box.clientWidth, h = box.clientHeight;
      var left = view.cx - w / 2 / view.k, top = view.cy - h / 2 / view.k;
      for (var tx = Math.floor(left / size); tx <= Math.floor((left + w / view.k) / size); tx++) {
        for (var ty = Math.floor(top / size); ty <= Math.floor((top + h / view.k) / size); ty++) {
          if (ty < 0 || ty >= n) { continue; }
          var url = data.tiles.url.replace("{z}", z).replace("{x}", ((tx % n) + n) % n).replace("{y}", ty);
          var s = screen([tx * size, ty * size]);
          var img = RS.el("image", { x: s[0], y: s[1], width: size * view.k + 0.5, height: size * view.k + 0.5,
            preserveAspectRatio: "none" }, gTiles);
          img.addEventListener("error", function () {
            this.remove();
            attribution.textContent = T.map_offline;
          });
          img.setAttribute("href", url);
        }
      }
    }

    function drawDecorations() {
      clear(gDeco);
      var w = box.clientWidth, h = box.clientHeight;
      var lat = latOf(view.cy);
      var metresPerPx = 2 * Math.PI * 6378137 * Math.cos(lat * Math.PI / 180) / TILE / view.k;
      var len = niceLength(metresPerPx * 140), px = len / metresPerPx;
      var x = 16, y = h - 22;
      RS.el("rect", { x: x - 6, y: y - 20, width: px + 12, height: 30, fill: "#fff", opacity: 0.8 }, gDeco);
      RS.el("path", { d: "M" + x + " " + (y - 5) + "v8h" + px + "v-8", fill: "none", stroke: "#000", "stroke-width": 2 }, gDeco);
      RS.text(gDeco, x + px / 2, y - 8, len >= 1000 ? len / 1000 + " km" : len + " m", { "text-anchor": "middle" });
      var ax = w - 30, ay = 18;
      RS.el("path", { d: "M" + ax + " " + ay + "l9 26l-9 -7l-9 7z", fill: "#000" }, gDeco);
      RS.text(gDeco, ax, ay + 42, "N", { "text-anchor": "middle", "font-weight": "bold" });
    }

    /* coastlines and borders (Natural Earth, shipped with rockscreen: works offline) */
    function drawBase() {
      clear(gBase);
      (data.basemap || []).forEach(function (line) {
        var d = line.map(function (p) { var s = screen(world(p[0], p[1])); return s[0].toFixed(1) + "," + s[1].toFixed(1); });
        RS.el("polyline", { points: d.join(" "), fill: "none", stroke: "#8c8c8c", "stroke-width": 1 }, gBase);
      });
      if (!tiles) { attribution.textContent = (data.basemap || []).length ? data.basemap_source : ""; }
    }

    function drawContours() {
      clear(gCont);
      (data.contours || []).forEach(function (c, i) {
        c.lines.forEach(function (line) {
          var d = line.map(function (p) { var s = screen(world(p[0], p[1])); return s[0].toFixed(1) + "," + s[1].toFixed(1); });
          RS.el("polyline", { points: d.join(" "), fill: "none", stroke: "#56b4e9", "stroke-width": 1.5 }, gCont);
          if (line.length) {
            var m = screen(world(line[Math.floor(line.length / 2)][0], line[Math.floor(line.length / 2)][1]));
            RS.text(gCont, m[0], m[1], c.label, { fill: "#0072b2", stroke: "#fff", "stroke-width": 3,
              "paint-order": "stroke", "font-size": 11 });
          }
        });
      });
    }

    function drawStations() {
      clear(gSta);
      stations.forEach(function (st) {
        var s = screen(world(st.lon, st.lat));
        var mark = RS.el("path", { d: "M" + s[0] + " " + (s[1] - 8) + "l7 12h-14z", fill: "#fff", stroke: "#000",
          "stroke-width": 1.5, "class": "station" }, gSta);
        RS.el("title", {}, mark).textContent = st.key;
      });
    }

    /* Tower ids next to their markers: each label takes the first of eight places around its
       marker that overlaps no marker and no label placed before it (riskiest first); a label
       that finds no free place is left out (the tooltip still names the tower). */
    function drawLabels(order) {
      var w = box.clientWidth, h = box.clientHeight, taken = [];
      var marks = order.map(function (t) { var s = screen(world(t.lon, t.lat)); return [s[0] - 7, s[1] - 7, s[0] + 7, s[1] + 7]; })
        .concat(stations.map(function (st) { var s = screen(world(st.lon, st.lat)); return [s[0] - 8, s[1] - 9, s[0] + 8, s[1] + 5]; }));
      function free(r) {
        if (r[0] < 0 || r[1] < 0 || r[2] > w || r[3] > h) { return false; }
        return !taken.concat(marks).some(function (q) { return r[0] < q[2] && q[0] < r[2] && r[1] < q[3] && q[1] < r[3]; });
      }
      var places = [[9, 4, "start"], [-9, 4, "end"], [0, -10, "middle"], [0, 18, "middle"],
        [8, -7, "start"], [-8, -7, "end"], [8, 15, "start"], [-8, 15, "end"]];
      order.slice().reverse().forEach(function (t) {
        var s = screen(world(t.lon, t.lat)), tw = 6.6 * String(t.id).length + 4;
        for (var i = 0; i < places.length; i++) {
          var p = places[i], x = s[0] + p[0], y = s[1] + p[1];
          var x0 = p[2] === "start" ? x : p[2] === "end" ? x - tw : x - tw / 2;
          var r = [x0, y - 11, x0 + tw, y + 3];
          if (free(r)) {
            taken.push(r);
            RS.text(gLab, x, y, t.id, { "text-anchor": p[2], "font-size": 11, stroke: "#fff", "stroke-width": 3,
              "paint-order": "stroke", "class": "tower-label" });
            return;
          }
        }
      });
      /* station codes after the towers, below, above, right or left of their triangle where
         there is room (a station whose label finds none is still named by its tooltip) */
      stations.forEach(function (st) {
        var s = screen(world(st.lon, st.lat)), tw = 7.2 * String(st.key).length + 4;
        var spots = [[0, 18, "middle"], [0, -12, "middle"], [11, 4, "start"], [-11, 4, "end"]];
        for (var i = 0; i < spots.length; i++) {
          var p = spots[i], x = s[0] + p[0], y = s[1] + p[1];
          var x0 = p[2] === "start" ? x : p[2] === "end" ? x - tw : x - tw / 2;
          var r = [x0, y - 11, x0 + tw, y + 3];
          if (free(r)) {
            taken.push(r);
            RS.text(gLab, x, y, st.key, { "text-anchor": p[2], "font-size": 11, "font-weight": "bold",
              stroke: "#fff", "stroke-width": 3, "paint-order": "stroke", "class": "station-label" });
            return;
          }
        }
      });
    }

    function drawTowers() {
      clear(gTow);
      clear(gLab);
      /* the riskiest last, so they are drawn on top */
      var order = placed.slice().sort(function (a, b) { return RS.classRank(b.risk_class) - RS.classRank(a.risk_class); });
      order.forEach(function (t) {
        var s = screen(world(t.lon, t.lat));
        var c = RS.el("circle", { cx: s[0], cy: s[1], r: t.id === selected ? 9 : 6, fill: RS.classColour(t.risk_class),
          stroke: t.id === selected ? "#0072b2" : "#000", "stroke-width": t.id === selected ? 3 : 1,
          "class": "tower", "data-id": t.id, tabindex: 0 }, gTow);
        c.addEventListener("mouseenter", function () {
          tip.textContent = t.id + " · " + RS.classLabel(t.risk_class);
          tip.style.left = (s[0] + 10) + "px"; tip.style.top = (s[1] - 10) + "px"; tip.style.display = "block";
        });
        c.addEventListener("mouseleave", function () { tip.style.display = "none"; });
        c.addEventListener("click", function (ev) { ev.stopPropagation(); onPick(t.id); });
        c.addEventListener("keydown", function (ev) { if (ev.key === "Enter") { onPick(t.id); } });
      });
      drawLabels(order);
    }

    function draw() { drawTiles(); drawBase(); drawContours(); drawStations(); drawTowers(); drawDecorations(); }

    var drag = null;
    svg.addEventListener("pointerdown", function (ev) {
      if (ev.target.classList && ev.target.classList.contains("tower")) { return; }
      drag = { x: ev.clientX, y: ev.clientY, cx: view.cx, cy: view.cy };
      svg.classList.add("dragging");
    });
    window.addEventListener("pointermove", function (ev) {
      if (!drag) { return; }
      view.cx = drag.cx - (ev.clientX - drag.x) / view.k;
      view.cy = drag.cy - (ev.clientY - drag.y) / view.k;
      draw();
    });
    window.addEventListener("pointerup", function () { drag = null; svg.classList.remove("dragging"); });
    svg.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      var r = svg.getBoundingClientRect(), f = ev.deltaY < 0 ? 1.25 : 0.8;
      var mx = ev.clientX - r.left - r.width / 2, my = ev.clientY - r.top - r.height / 2;
      view.cx += mx / view.k * (1 - 1 / f); view.cy += my / view.k * (1 - 1 / f);
      view.k = Math.min(view.k * f, Math.pow(2, 19));
      draw();
    }, { passive: false });
    window.addEventListener("resize", draw);

    fit(); draw();
    return {
      reset: function () { view = Object.assign({}, home); draw(); },
      setTiles: function (on) { tiles = on; draw(); },
      select: function (id) { selected = id; drawTowers(); }
    };
  };
})();
