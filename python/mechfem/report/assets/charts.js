/* The report's charts, drawn by uPlot (inlined before this script).
 *
 * A chart is one uPlot plot of columns of the report's data: "function" charts draw columns against one
 * horizontal column that moves one way (uPlot's ordinary mode, points sorted by x); "xy" charts draw curves in
 * the plane (uPlot's mode 2, points in the order of the motion, equal scales for paths of points). Every point
 * of a chart is one frame (a position the report shows), so that the pointer, the slider and the CSV all speak
 * of positions. The page (page.js) owns the slider; a chart asks it for the current frame and tells it where
 * to go when clicked.
 */
"use strict";
const MechfemCharts = (function () {
  // Okabe and Ito's colour-blind-safe palette; yellow comes last, as it is faint on white.
  const PALETTE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"];
  const LIMIT = "#c0392b";
  const HEIGHT = 250;

  function el(tag, props, ...children) {
    const e = document.createElement(tag);
    Object.assign(e, props || {});
    for (const c of children) e.append(c);
    return e;
  }
  function fmt(v) {
    if (v === null || v === undefined || Number.isNaN(v)) return "-";
    if (v === 0) return "0";
    const a = Math.abs(v);
    if (a >= 1e6 || a < 1e-4) return v.toExponential(4);
    return String(Number(v.toPrecision(6)));
  }
  function tick(v) {
    if (v === null) return "";
    const a = Math.abs(v);
    if (v !== 0 && (a >= 1e5 || a < 1e-3)) return v.toExponential(1);
    return String(Number(v.toPrecision(9)));
  }
  function withUnit(text, unit) { return unit ? text + " " + unit : text; }
  function csvCell(s) {
    s = String(s);
    return /[",\r\n]/.test(s) ? '"' + s.replace(/"/g, '""') + '"' : s;
  }
  function download(name, text) {
    const link = el("a", { download: name });
    link.setAttribute("href", URL.createObjectURL(new Blob([text], { type: "text/csv;charset=utf-8" })));
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.getAttribute("href")), 1000);
  }
  // A vertical axis as wide as its longest tick label.
  function axisSize(u, values) {
    if (!values) return 48;
    const longest = values.reduce((m, v) => Math.max(m, String(v).length), 0);
    return Math.ceil(longest * 6.5) + 16;
  }
  function arrow(ctx, x0, y0, x1, y1, colour, width) {
    const len = Math.hypot(x1 - x0, y1 - y0);
    if (!(len > 0.5)) return;
    const h = Math.min(9 * width / 1.5, 0.35 * len + 3), a = Math.atan2(y1 - y0, x1 - x0);
    ctx.strokeStyle = colour; ctx.fillStyle = colour; ctx.lineWidth = width;
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1 - 0.6 * h * Math.cos(a), y1 - 0.6 * h * Math.sin(a)); ctx.stroke();
    ctx.beginPath(); ctx.moveTo(x1, y1);
    ctx.lineTo(x1 - h * Math.cos(a - 0.38), y1 - h * Math.sin(a - 0.38));
    ctx.lineTo(x1 - h * Math.cos(a + 0.38), y1 - h * Math.sin(a + 0.38));
    ctx.closePath(); ctx.fill();
  }
  // The vector of a polar plot: from the origin to the curve's point at the slider's position.
  function originVector(ctx, x0, y0, x1, y1, colour, r) {
    ctx.globalAlpha = 0.8;
    arrow(ctx, x0, y0, x1, y1, colour, 1.6 * r);
    ctx.globalAlpha = 1;
  }
  function dot(ctx, x, y, r, colour) {
    ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI); ctx.fillStyle = colour; ctx.fill();
    ctx.lineWidth = r / 3; ctx.strokeStyle = "#fff"; ctx.stroke();
  }
  // uPlot's own line builder thins out points by x, which suits sorted data only: curves in the plane are
  // drawn through every point, in the order of the motion, with gaps where a value does not exist.
  function xyPath(u, si, i0, i1) {
    const xs = u.data[si][0], ys = u.data[si][1];
    const p = new Path2D();
    let pen = false;
    for (let i = i0; i <= i1; i++) {
      if (xs[i] === null || ys[i] === null) { pen = false; continue; }
      const X = u.valToPos(xs[i], "x", true), Y = u.valToPos(ys[i], "y", true);
      if (pen) p.lineTo(X, Y); else p.moveTo(X, Y);
      pen = true;
    }
    return { stroke: p, fill: null, clip: null, band: null, gaps: null, flags: 0 };
  }
  function padded(lo, hi) {
    const p = 0.06 * (hi - lo || Math.abs(hi) || 1);
    return [lo - p, hi + p];
  }
  function extent(arrays) {
    let lo = Infinity, hi = -Infinity;
    for (const a of arrays) for (const v of a) if (v !== null) { if (v < lo) lo = v; if (v > hi) hi = v; }
    if (!isFinite(lo)) return [-1, 1];
    if (hi - lo <= 1e-12 * Math.max(1, Math.abs(hi))) { const d = Math.max(Math.abs(hi) * 0.05, 0.5); return [lo - d, hi + d]; }
    return [lo, hi];
  }

  /* One chart. page: {D, cur(), goTo(frame), drawScene(ctx, X, Y, scale, frame, alpha), pathColour(x, y)};
   * spec: {type, x (function), series: [{x?, y, name?}], hodographs?, xlabel, ylabel, equal?, mechanism?,
   * limits?, title?}; host: the element to append to; name: the CSV file's name. */
  function Chart(page, spec, host, name) {
    this.page = page;
    this.spec = spec;
    this.D = page.D;
    this.name = name;
    this.hover = null;
    this.markers = [];
    this.cursorDots = [];
    const cols = this.D.columns;
    this.box = el("div", { className: "chart" });
    const csv = el("button", { type: "button", title: "save this chart's numbers as a CSV file" }, "CSV");
    const reset = el("button", { type: "button", title: "show everything again (double-click does the same)" }, "Reset zoom");
    csv.addEventListener("click", () => download(this.name, this.csv()));
    reset.addEventListener("click", () => this.resetZoom());
    this.box.append(el("div", { className: "chartbar" }, el("span", {}, spec.title || ""), reset, csv));
    this.plot = el("div", { className: "plot" });
    this.readout = el("div", { className: "readout" });
    this.box.append(this.plot, this.readout);
    host.append(this.box);

    // The curves: a name, a colour and the columns of each.
    this.curves = spec.series.map((s, k) => ({
      name: s.name || cols[s.y].name, colour: PALETTE[k % PALETTE.length], x: s.x || spec.x, y: s.y,
      force: s.fx ? { fx: s.fx, fy: s.fy } : null, short: s.short,
    }));
    this.forceArrows = [];
    for (const h of spec.hodographs || []) {
      this.curves.push({ name: h.name, colour: page.pathColour(h.x, h.y), x: h.x, y: h.y, hodograph: h });
    }
    const width = Math.max(this.plot.clientWidth, 240);
    if (spec.type === "function") this.buildFunction(width); else this.buildXY(width);
    this.buildReadout();
    this.bindClick();
    new ResizeObserver(() => {
      const w = Math.max(this.plot.clientWidth, 240);
      if (Math.abs(w - this.u.width) < 2) return;
      this.u.setSize({ width: w, height: this.spec.height || HEIGHT });
    }).observe(this.plot);
  }

  Chart.prototype.axes = function () {
    const grid = { stroke: "#e6e9ee", width: 1 };
    return [
      { label: this.spec.xlabel, values: (u, s) => s.map(tick), grid: grid, ticks: { stroke: "#c9ced6" }, labelSize: 20, size: 36 },
      { label: this.spec.ylabel, values: (u, s) => s.map(tick), grid: grid, ticks: { stroke: "#c9ced6" }, labelSize: 20, size: axisSize },
    ];
  };
  Chart.prototype.hooks = function () {
    return {
      drawAxes: [(u) => this.drawBehind(u)],
      draw: [(u) => this.drawMarks(u)],
      setCursor: [(u) => this.onCursor(u)],
      setSelect: [() => { this.zoomed = true; }],
      // The axes take their width from their tick labels, which changes the plot's size: equal scales are
      // fitted again to the size the plot ends up with, unless the reader zoomed.
      setSize: [(u) => {
        const fit = this.fitted;
        if (this.spec.type === "xy" && !this.zoomed && fit && (fit[0] !== u.bbox.width || fit[1] !== u.bbox.height)) this.resetZoom();
      }],
    };
  };

  // Function charts: the points sorted by x; frameOf maps a point to its frame (-1: a limit marker's place).
  Chart.prototype.functionData = function () {
    const D = this.D, cols = D.columns, xs = cols[this.spec.x].values;
    const rows = [];
    for (let f = 0; f < D.frames.length; f++) if (xs[f] !== null) rows.push({ x: xs[f], f: f });
    // A limit the motion stopped at lies beyond the last position: the axis reaches it.
    for (const m of this.spec.limits || []) if (m.x !== null) rows.push({ x: m.x, f: -1 });
    rows.sort((a, b) => a.x - b.x || b.f - a.f);
    this.frameOf = rows.map((r) => r.f);
    this.indexOf = new Array(D.frames.length).fill(-1);
    rows.forEach((r, i) => { if (r.f >= 0 && this.indexOf[r.f] < 0) this.indexOf[r.f] = i; });
    const data = [rows.map((r) => r.x)];
    for (const c of this.curves) data.push(rows.map((r) => (r.f < 0 ? null : cols[c.y].values[r.f])));
    return data;
  };

  Chart.prototype.buildFunction = function (width) {
    const cols = this.D.columns;
    const data = this.functionData();
    const opts = {
      width: width, height: HEIGHT,
      // det(D^c) is read against zero: its axis always shows it.
      scales: { x: { time: false }, y: this.spec.zero ? { range: (u, lo, hi) => padded(Math.min(lo, 0), Math.max(hi, 0)) } : {} },
      legend: { show: false },
      cursor: { drag: { x: true, y: false, setScale: true }, points: { size: 7 } },
      series: [{ label: cols[this.spec.x].name }].concat(this.curves.map((c) => ({
        label: c.name, stroke: c.colour, width: 1.7, spanGaps: false, points: { show: false },
      }))),
      axes: this.axes(),
      hooks: this.hooks(),
    };
    this.u = new uPlot(opts, data, this.plot);
  };

  // Curves in the plane: one uPlot facet per curve, every point in the order of the motion (index = frame).
  Chart.prototype.xyData = function () {
    const cols = this.D.columns;
    const data = [null];
    const xs = [], ys = [];
    for (const c of this.curves) {
      const x = cols[c.x].values, y = cols[c.y].values;
      data.push([x.map((v, f) => (v === null || y[f] === null ? null : v)), y.map((v, f) => (v === null || x[f] === null ? null : v))]);
      xs.push(x); ys.push(y);
      const h = c.hodograph;
      if (h && h.scale) {
        // The arrow tips count too, so that no arrow leaves the chart.
        xs.push(h.ax.map((v, k) => (v === null || h.avx[k] === null ? null : v + h.avx[k] * h.scale)));
        ys.push(h.ay.map((v, k) => (v === null || h.avy[k] === null ? null : v + h.avy[k] * h.scale)));
      }
      if (c.force) {
        // A pin force's arrow tips count too, at every position.
        const fx = cols[c.force.fx].values, fy = cols[c.force.fy].values, s = this.spec.force_scale;
        xs.push(x.map((v, f) => (v === null || fx[f] === null ? null : v + fx[f] * s)));
        ys.push(y.map((v, f) => (v === null || fy[f] === null ? null : v + fy[f] * s)));
      }
    }
    // The pin forces' chart shows the whole mechanism; a hodograph's only the path, the mechanism faint behind.
    if (this.spec.force_scale) { const b = this.D.scene.bounds; xs.push([b[0], b[1]]); ys.push([b[2], b[3]]); }
    if (this.spec.origin) { xs.push([0]); ys.push([0]); }
    const [x0, x1] = extent(xs), [y0, y1] = extent(ys);
    const px = 0.05 * (x1 - x0), py = 0.05 * (y1 - y0);
    this.bounds = [x0 - px, x1 + px, y0 - py, y1 + py];
    return data;
  };

  Chart.prototype.buildXY = function (width) {
    const data = this.xyData();
    const opts = {
      mode: 2,
      width: width, height: this.spec.height || HEIGHT,
      scales: {
        x: { time: false, auto: false, range: () => [this.bounds[0], this.bounds[1]] },
        y: { auto: false, range: () => [this.bounds[2], this.bounds[3]] },
      },
      legend: { show: false },
      cursor: {
        drag: { x: true, y: true, setScale: true },
        points: { size: 7 },
        dataIdx: (u, si) => {
          if (si === 1) this.hover = this.nearest(u);
          return this.hover;
        },
        bind: { dblclick: () => (e) => { if (e.button === 0) this.resetZoom(); return null; } },
      },
      series: [{}].concat(this.curves.map((c) => ({
        label: c.name, stroke: c.colour, width: 1.7, paths: xyPath, points: { show: false },
        facets: [{ scale: "x", auto: false }, { scale: "y", auto: false }],
      }))),
      axes: this.axes(),
      hooks: this.hooks(),
    };
    this.u = new uPlot(opts, data, this.plot);
    this.resetZoom();
  };

  // The frame of the point nearest the pointer, over every curve (xy charts), within 40 pixels.
  Chart.prototype.nearest = function (u) {
    const L = u.cursor.left, T = u.cursor.top;
    if (L === null || L < 0) return null;
    let best = null, bestD = 40 * 40;
    for (let si = 1; si < u.data.length; si++) {
      const xs = u.data[si][0], ys = u.data[si][1];
      for (let f = 0; f < xs.length; f++) {
        if (xs[f] === null) continue;
        const dx = u.valToPos(xs[f], "x") - L, dy = u.valToPos(ys[f], "y") - T;
        const d = dx * dx + dy * dy;
        if (d < bestD) { bestD = d; best = f; }
      }
    }
    return best;
  };

  Chart.prototype.resetZoom = function () {
    const u = this.u;
    this.zoomed = false;
    if (this.spec.type === "function") {
      const xs = u.data[0];
      u.setScale("x", { min: xs[0], max: xs[xs.length - 1] });
      return;
    }
    let [x0, x1, y0, y1] = this.bounds;
    if (this.spec.equal && u.bbox.width > 0 && u.bbox.height > 0) {
      // Equal scales: a path keeps its shape.
      const w = u.bbox.width, h = u.bbox.height, s = Math.min(w / (x1 - x0), h / (y1 - y0));
      const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
      [x0, x1, y0, y1] = [cx - w / 2 / s, cx + w / 2 / s, cy - h / 2 / s, cy + h / 2 / s];
    }
    this.fitted = [u.bbox.width, u.bbox.height];
    u.batch(() => { u.setScale("x", { min: x0, max: x1 }); u.setScale("y", { min: y0, max: y1 }); });
  };

  // A click (not a drag) on the plot moves the slider to the position under the pointer.
  Chart.prototype.bindClick = function () {
    let down = null;
    this.u.over.addEventListener("pointerdown", (e) => { down = [e.clientX, e.clientY]; });
    this.u.over.addEventListener("pointerup", (e) => {
      if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4 && this.hover !== null) this.page.goTo(this.hover);
      down = null;
    });
  };

  Chart.prototype.onCursor = function (u) {
    if (this.spec.type === "function") {
      const i = u.cursor.idx;
      this.hover = i === null || i === undefined || u.cursor.left < 0 || this.frameOf[i] < 0 ? null : this.frameOf[i];
    } else if (u.cursor.left < 0) {
      this.hover = null;
    }
    this.updateReadout();
  };

  // ---- drawing on top of uPlot's canvas ----
  Chart.prototype.ratio = function () { return this.u.pxRatio || window.devicePixelRatio || 1; };
  Chart.prototype.drawBehind = function (u) {
    const ctx = u.ctx, b = u.bbox;
    ctx.save();
    ctx.beginPath(); ctx.rect(b.left, b.top, b.width, b.height); ctx.clip();
    if (this.spec.mechanism) {
      const X = (v) => u.valToPos(v, "x", true), Y = (v) => u.valToPos(v, "y", true);
      const s = Math.abs(u.valToPos(1, "x", true) - u.valToPos(0, "x", true));
      this.page.drawScene(ctx, X, Y, s, this.page.cur(), this.spec.mechanism_alpha || 0.3, this.ratio());
    }
    if (this.spec.type === "function" && u.scales.y.min < 0 && u.scales.y.max > 0) {
      const Y = u.valToPos(0, "y", true);
      ctx.strokeStyle = "#9aa3ad"; ctx.lineWidth = this.ratio();
      ctx.beginPath(); ctx.moveTo(b.left, Y); ctx.lineTo(b.left + b.width, Y); ctx.stroke();
    }
    ctx.restore();
  };

  Chart.prototype.drawMarks = function (u) {
    const ctx = u.ctx, b = u.bbox, r = this.ratio(), f = this.page.cur(), cols = this.D.columns;
    const X = (v) => u.valToPos(v, "x", true), Y = (v) => u.valToPos(v, "y", true);
    const inside = (x, y) => x >= b.left - 1 && x <= b.left + b.width + 1 && y >= b.top - 1 && y <= b.top + b.height + 1;
    ctx.save();
    ctx.beginPath(); ctx.rect(b.left, b.top, b.width, b.height); ctx.clip();
    for (const c of this.curves) {
      const h = c.hodograph;
      if (!h || !h.scale) continue;
      h.ax.forEach((x, k) => {
        const y = h.ay[k];
        if (x === null || y === null || h.avx[k] === null || h.avy[k] === null) return;
        ctx.globalAlpha = 0.55;
        arrow(ctx, X(x), Y(y), X(x + h.avx[k] * h.scale), Y(y + h.avy[k] * h.scale), c.colour, 1.3 * r);
        ctx.globalAlpha = 1;
      });
    }
    // The limit positions (det chart): a numbered line at each.
    this.markers = [];
    (this.spec.limits || []).forEach((m, k) => {
      if (m.x === null) return;
      const x = X(m.x);
      if (x < b.left - 1 || x > b.left + b.width + 1) return;
      const y = Math.min(Math.max(Y(m.det === null ? 0 : m.det), b.top), b.top + b.height);
      ctx.strokeStyle = LIMIT; ctx.lineWidth = 1.5 * r; ctx.setLineDash([5 * r, 4 * r]);
      ctx.beginPath(); ctx.moveTo(x, b.top); ctx.lineTo(x, b.top + b.height); ctx.stroke(); ctx.setLineDash([]);
      ctx.fillStyle = LIMIT;
      ctx.beginPath(); ctx.moveTo(x, y - 6 * r); ctx.lineTo(x + 6 * r, y); ctx.lineTo(x, y + 6 * r); ctx.lineTo(x - 6 * r, y); ctx.closePath(); ctx.fill();
      ctx.font = `bold ${12 * r}px system-ui, sans-serif`; ctx.textAlign = "left"; ctx.textBaseline = "top";
      ctx.fillText(String(k + 1), x + 4 * r, b.top + 3 * r);
      this.markers.push({ n: k + 1, x: x / r, y: y / r });
    });
    // The slider's position: a dashed line (function charts) and a dot on every curve.
    this.cursorDots = [];
    this.forceArrows = [];
    if (this.spec.type === "function" && this.indexOf[f] >= 0) {
      const x = X(u.data[0][this.indexOf[f]]);
      ctx.strokeStyle = "#444"; ctx.lineWidth = r; ctx.setLineDash([4 * r, 3 * r]);
      ctx.beginPath(); ctx.moveTo(x, b.top); ctx.lineTo(x, b.top + b.height); ctx.stroke(); ctx.setLineDash([]);
    }
    for (const c of this.curves) {
      const xv = cols[c.x].values[f], yv = cols[c.y].values[f];
      if (xv === null || yv === null) continue;
      const x = X(xv), y = Y(yv);
      if (this.spec.origin) originVector(ctx, X(0), Y(0), x, y, c.colour, r);
      if (c.force) this.drawForce(ctx, c, f, X, Y, r);
      const h = c.hodograph;
      if (h && h.scale && cols[h.vx] && cols[h.vy] && cols[h.vx].values[f] !== null && cols[h.vy].values[f] !== null) {
        arrow(ctx, x, y, X(xv + cols[h.vx].values[f] * h.scale), Y(yv + cols[h.vy].values[f] * h.scale), c.colour, 2.4 * r);
      }
      if (!inside(x, y)) continue;
      dot(ctx, x, y, 4.5 * r, c.colour);
      this.cursorDots.push([Math.round(x / r * 10) / 10, Math.round(y / r * 10) / 10]);
    }
    ctx.restore();
  };

  // A pin force at the slider's position: an arrow from the pin, on the chart's one scale, labelled |F|.
  Chart.prototype.drawForce = function (ctx, c, f, X, Y, r) {
    const cols = this.D.columns, s = this.spec.force_scale;
    const x = cols[c.x].values[f], y = cols[c.y].values[f], fx = cols[c.force.fx].values[f], fy = cols[c.force.fy].values[f];
    if (x === null || y === null || fx === null || fy === null) return;
    arrow(ctx, X(x), Y(y), X(x + fx * s), Y(y + fy * s), c.colour, 2.4 * r);
    const text = withUnit(fmt(Math.hypot(fx, fy)), this.spec.force_unit);
    ctx.font = 12 * r + "px sans-serif"; ctx.fillStyle = "#1f3b57"; ctx.textAlign = "left"; ctx.textBaseline = "bottom";
    ctx.fillText((c.short || c.name) + " " + text, X(x + fx * s) + 4 * r, Y(y + fy * s) - 2 * r);
    this.forceArrows.push({ name: c.name, x: x, y: y, fx: fx, fy: fy, tip: [x + fx * s, y + fy * s] });
  };

  // ---- the readout under the chart: every curve's value under the pointer, or at the slider ----
  Chart.prototype.buildReadout = function () {
    this.readHead = el("div", { className: "head" });
    this.readout.append(this.readHead);
    this.readValues = this.curves.map((c) => {
      const v = el("span", {});
      this.readout.append(el("span", { className: "name" }, el("i", { className: "swatch", style: "background:" + c.colour }), c.name), v);
      return v;
    });
    this.updateReadout();
  };
  Chart.prototype.updateReadout = function () {
    if (!this.readValues) return; // uPlot reports its cursor while it is being built
    const D = this.D, cols = D.columns;
    const f = this.hover !== null ? this.hover : this.page.cur();
    let head = (this.hover !== null ? "under the pointer: " : "at the slider: ") + "position " + (D.frames[f] + 1);
    if (this.spec.type === "function" && this.spec.x !== "pos") {
      const x = cols[this.spec.x];
      head += ", " + x.name + " = " + withUnit(fmt(x.values[f]), x.unit);
    }
    this.readHead.textContent = head;
    this.curves.forEach((c, k) => {
      const y = cols[c.y];
      if (c.force) {
        const fx = cols[c.force.fx], fy = cols[c.force.fy], u = this.spec.force_unit;
        const m = fx.values[f] === null || fy.values[f] === null ? null : Math.hypot(fx.values[f], fy.values[f]);
        this.readValues[k].textContent = "|F| = " + withUnit(fmt(m), u) + " (" + fmt(fx.values[f]) + ", " + fmt(fy.values[f]) + ")";
        return;
      }
      this.readValues[k].textContent = this.spec.type === "function"
        ? withUnit(fmt(y.values[f]), y.unit)
        : "(" + withUnit(fmt(cols[c.x].values[f]), cols[c.x].unit) + ", " + withUnit(fmt(y.values[f]), y.unit) + ")";
    });
  };

  // ---- the chart's numbers as CSV: the position, then every column the chart draws ----
  Chart.prototype.columns = function () {
    const keys = [];
    // The position is the first column already.
    const add = (k) => { if (k && k !== "pos" && this.D.columns[k] && !keys.includes(k)) keys.push(k); };
    if (this.spec.type === "function") add(this.spec.x);
    for (const c of this.curves) {
      add(c.x); add(c.y);
      if (c.hodograph) { add(c.hodograph.vx); add(c.hodograph.vy); }
      if (c.force) { add(c.force.fx); add(c.force.fy); }
    }
    return keys;
  };
  Chart.prototype.csv = function () {
    const D = this.D, keys = this.columns();
    const lines = [["position"].concat(keys.map((k) => D.columns[k].header)).map(csvCell).join(",")];
    for (let f = 0; f < D.frames.length; f++) {
      const row = [String(D.frames[f] + 1)];
      for (const k of keys) { const v = D.columns[k].values[f]; row.push(v === null ? "" : String(v)); }
      lines.push(row.join(","));
    }
    return lines.join("\n") + "\n";
  };

  /* The same chart of another design (a page that changes its data: the studio): the curves' numbers and the limit
   * markers from page.D and spec, given anew, drawn into the uPlot chart there is (a new uPlot costs many times more). */
  Chart.prototype.update = function (spec) {
    this.D = this.page.D;
    this.spec = spec;
    const hodographs = (spec.hodographs || []).values();
    for (const c of this.curves) if (c.hodograph) c.hodograph = hodographs.next().value;
    if (spec.type === "function") {
      this.u.setData(this.functionData(), !this.zoomed);
    } else {
      const data = this.xyData();
      this.u.setData(data, false);
      if (!this.zoomed) this.resetZoom(); else this.u.redraw(false, false);
    }
    if (this.hover === null) this.updateReadout();
  };

  Chart.prototype.redraw = function () {
    this.u.redraw(false, false);
    if (this.hover === null) this.updateReadout();
  };

  return { Chart: Chart, PALETTE: PALETTE, fmt: fmt, el: el, arrow: arrow, dot: dot };
})();
