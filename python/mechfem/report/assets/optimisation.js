/* The optimisation of a KIN OPT deck on its report page, from D.optimisation (mechfem.report.optimum_report): what the
 * optimiser did, its objective per iteration (uPlot, logarithmic axis), every design variable's start and final
 * value against its bounds, every target's residual, and the start and final designs drawn over each other at
 * position 1 with the points the targets ask for (each shape traced by scene.js's traceShape). A report without it
 * leaves its section hidden. */
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("data").textContent);
  const O = D.optimisation;
  if (!O) return;
  const C = MechfemCharts, el = C.el, fmt = C.fmt;
  const TARGET = "#c0392b", START = "#7b8794", FINAL = "#0072B2";
  const host = document.getElementById("optimisation");
  host.hidden = false;
  const withUnit = (v, unit) => (unit && unit !== "-" ? fmt(v) + " " + unit : fmt(v));

  function table(id, heads, rows) {
    const head = el("tr", {});
    for (const h of heads) head.append(el("th", {}, h));
    const body = el("tbody", {});
    for (const r of rows) {
      const tr = el("tr", {});
      for (const cell of r) tr.append(typeof cell === "object" ? cell : el("td", {}, String(cell)));
      body.append(tr);
    }
    return el("div", { className: "tablewrap" }, el("table", { id: id }, el("thead", {}, head), body));
  }

  // ---- the summary ----
  const iterations = O.history.iteration.length - 1;
  host.append(el("h2", {}, "Optimisation (OPTIMISE, line " + O.line + ")"));
  const verdict = O.success ? "converged" : "did not converge";
  host.append(el("p", { className: O.success ? "ok" : "warn", id: "optsummary" },
    O.method + ", " + verdict + ": " + O.message.replace(/\.$/, "") + ". Objective " + fmt(O.objective.start) + " at the start, " +
    fmt(O.objective.final) + " at the end, after " + iterations + " iteration" + (iterations === 1 ? "" : "s") +
    " (" + O.runs + " mechanism runs, " + fmt(O.seconds) + " s" +
    (O.infeasible ? "; " + O.infeasible + " of them met an infeasible design and were stepped back from" : "") + ")."));
  if (O.unreached) host.append(el("p", { className: "warn" }, O.unreached));
  const grid = el("div", { className: "optgrid" });
  host.append(grid);

  // ---- the start and final designs over each other ----
  const stage = el("section", { className: "card" }, el("h3", {}, "Start and final design at position 1"));
  const canvas = el("canvas", { id: "optdesigns", role: "img" });
  canvas.setAttribute("aria-label", "the start design dashed and faint, the final design solid, the target points as crosses");
  stage.append(el("div", { className: "optcanvas" }, canvas));
  const legend = el("ul", { className: "legend" });
  const swatch = (colour, dash) => el("i", { className: "swatch", style: "background:" + colour + (dash ? ";opacity:0.45" : "") });
  if (O.drawing.start) legend.append(el("li", {}, swatch(START, true), "start design (dashed)"));
  legend.append(el("li", {}, swatch(D.styles.bar.edge), "final design"));
  if (O.drawing.points.length) {
    legend.append(el("li", {}, swatch(FINAL), "path of the final design"), el("li", {}, el("b", { style: "color:" + TARGET }, "\u00d7"), "target points"));
  }
  stage.append(legend);
  grid.append(stage);

  function box() {
    const b = O.drawing.bounds.slice();
    const grow = (x, y) => {
      if (x === null || y === null) return;
      b[0] = Math.min(b[0], x); b[1] = Math.max(b[1], x); b[2] = Math.min(b[2], y); b[3] = Math.max(b[3], y);
    };
    for (const p of O.drawing.points) for (const key of ["target", "start", "final"]) for (const q of p[key]) grow(q[0], q[1]);
    const pad = 0.05 * Math.max(b[1] - b[0], b[3] - b[2], 1e-9);
    return [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad];
  }
  function drawShapes(ctx, X, Y, s, r, design, faded) {
    const order = design.kinds.map((_, i) => i)
      .sort((a, b) => (D.styles[design.roles[a]].layer - D.styles[design.roles[b]].layer) || (a - b));
    ctx.save();
    ctx.globalAlpha = faded ? 0.4 : 1;
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    for (const i of order) {
      const d = design.data[i], kind = design.kinds[i], st = D.styles[design.roles[i]];
      if (d.some((v) => v === null)) continue;
      ctx.strokeStyle = faded ? START : st.edge;
      ctx.lineWidth = st.width * 1.25 * r;
      ctx.setLineDash(faded || st.dash ? [6 * r, 4 * r] : []);
      MechfemScene.traceShape(ctx, kind, d, X, Y, s);
      // The start design is outlines only, so that the final one shows through it.
      if (!faded && st.fill && (kind === "polygon" || kind === "circle")) { ctx.fillStyle = st.fill; ctx.fill(); }
      ctx.stroke();
    }
    ctx.restore();
  }
  function path(ctx, X, Y, pts, colour, width, dash, alpha) {
    ctx.save();
    ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.setLineDash(dash); ctx.globalAlpha = alpha;
    ctx.beginPath();
    let pen = false;
    for (const q of pts) {
      if (q[0] === null || q[1] === null) { pen = false; continue; }
      if (pen) ctx.lineTo(X(q[0]), Y(q[1])); else ctx.moveTo(X(q[0]), Y(q[1]));
      pen = true;
    }
    ctx.stroke();
    ctx.restore();
  }
  function cross(ctx, x, y, h, colour, width) {
    ctx.save();
    ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.setLineDash([]);
    ctx.beginPath();
    ctx.moveTo(x - h, y - h); ctx.lineTo(x + h, y + h); ctx.moveTo(x - h, y + h); ctx.lineTo(x + h, y - h);
    ctx.stroke();
    ctx.restore();
  }
  const drawn = { targets: 0 };
  function drawDesigns() {
    const f = MechfemScene.fit(box(), Math.max(240, canvas.parentElement.clientWidth), 220, 520);
    const w = f.w, h = f.h, r = f.r, s = f.s, cx = f.cx, cy = f.cy;
    MechfemScene.size(canvas, f);
    const X = (x) => (w / 2 + (x - cx) * s) * r, Y = (y) => (h / 2 - (y - cy) * s) * r;
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    if (O.drawing.start) drawShapes(ctx, X, Y, s * r, r, O.drawing.start, true);
    drawShapes(ctx, X, Y, s * r, r, O.drawing.final, false);
    drawn.targets = 0;
    for (const p of O.drawing.points) {
      path(ctx, X, Y, p.start, START, 1.4 * r, [5 * r, 4 * r], 0.7);
      path(ctx, X, Y, p.final, FINAL, 1.8 * r, [], 1);
      for (const q of p.target) {
        if (q[0] === null || q[1] === null) continue;
        cross(ctx, X(q[0]), Y(q[1]), 5 * r, TARGET, 2 * r);
        drawn.targets++;
      }
      const last = p.final[p.final.length - 1];
      if (last && last[0] !== null && last[1] !== null) {
        ctx.font = 12 * r + "px sans-serif"; ctx.fillStyle = "#1f3b57";
        ctx.fillText(p.name, X(last[0]) + 7 * r, Y(last[1]) - 7 * r);
      }
    }
  }

  // ---- the objective per iteration ----
  const chartBox = el("section", { className: "card" }, el("h3", {}, "Objective per iteration"));
  const plot = el("div", { className: "plot", id: "opthistory" });
  chartBox.append(plot);
  const hist = O.history;
  // A logarithmic axis shows only positive values: an objective of exactly 0 (a target met to the last digit)
  // is left out of the curve and said under it.
  const positive = hist.objective.map((v) => (v !== null && v > 0 ? v : null));
  if (positive.some((v) => v === null)) {
    chartBox.append(el("p", { className: "note" }, "Iterations whose objective is 0 (or not finite) have no place on a logarithmic axis and are left out."));
  }
  chartBox.append(el("p", { className: "note" }, "Iteration 0 is the start design; each iteration is a design the optimiser moved to."));
  grid.append(chartBox);
  let u = null;
  // The objective often falls by many decades: the axis has a tick and a grid line at every power of ten, or at
  // every few when they would crowd (uPlot's own log ticks, 1 to 9 in every decade, would fill the chart grey).
  function decadeSplits(self, axis, lo, hi) {
    const a = Math.floor(Math.log10(lo) + 1e-9), b = Math.ceil(Math.log10(hi) - 1e-9);
    const every = Math.max(1, Math.ceil((b - a + 1) / 8));
    const out = [];
    for (let e = Math.ceil(a / every) * every; e <= b; e += every) out.push(Math.pow(10, e));
    return out;
  }
  const decadeLabels = (self, ticks) => ticks.map((v) => (v > 0 ? "1e" + Math.round(Math.log10(v)) : ""));
  function buildChart() {
    const width = Math.max(plot.clientWidth, 240);
    u = new uPlot({
      width: width, height: 250,
      scales: { x: { time: false }, y: { distr: 3 } },
      legend: { show: false },
      cursor: { drag: { x: true, y: false, setScale: true }, points: { size: 7 } },
      series: [{ label: "iteration" }, { label: "objective", stroke: FINAL, width: 1.7, points: { show: true, size: 5 } }],
      axes: [
        { label: "iteration", values: (_, t) => t.map((v) => (Number.isInteger(v) ? String(v) : "")), grid: { stroke: "#e6e9ee" } },
        { label: "objective", splits: decadeSplits, filter: (self, ticks) => ticks, values: decadeLabels, grid: { stroke: "#e6e9ee" }, size: 60 },
      ],
    }, [hist.iteration, positive], plot);
  }

  // ---- the design variables and the targets ----
  const vars = el("section", { className: "card optwide" }, el("h3", {}, "Design variables"));
  vars.append(table("optvariables", ["variable", "unit", "start", "final", "change", "lower bound", "upper bound", "bound active"],
    O.variables.map((v) => [v.name, v.unit || "", fmt(v.start), fmt(v.final), fmt(v.final - v.start), fmt(v.lo), fmt(v.hi),
      el("td", { className: v.active ? "active" : "" }, v.periodic ? "periodic" : (v.active || "no"))])));
  grid.append(vars);
  if (O.targets.length) {
    const tg = el("section", { className: "card optwide" }, el("h3", {}, "Targets at the final design"));
    tg.append(el("p", { className: "note" }, "Residual = target - achieved, in the model's units; every compared position of a TARGET is a row."));
    tg.append(table("opttargets", ["target", "line", "quantity", "where", "target", "achieved", "residual"],
      O.targets.map((t) => [t.keyword, t.line, t.name, t.where, withUnit(t.target, t.unit), withUnit(t.achieved, t.unit), withUnit(t.residual, t.unit)])));
    grid.append(tg);
  }

  // Drawn again when the window's width changes (not on every change of the section's size, which the drawing
  // itself changes).
  let width = window.innerWidth;
  window.addEventListener("resize", () => {
    if (window.innerWidth === width) return;
    width = window.innerWidth;
    drawDesigns();
    u.setSize({ width: Math.max(plot.clientWidth, 240), height: 250 });
  });
  drawDesigns();
  buildChart();

  // The section's own check, beside the page's (...#selftest): what it drew and tabulated.
  if (location.hash === "#selftest") {
    const img = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
    let ink = 0;
    for (let i = 0; i < img.length; i += 4) if (img[i] < 245 || img[i + 1] < 245 || img[i + 2] < 245) ink++;
    const out = {
      ink: ink, targets_drawn: drawn.targets, log: u.scales.y.distr === 3, points: u.data[1].filter((v) => v !== null).length,
      variables: document.querySelectorAll("#optvariables tbody tr").length,
      targets: document.querySelectorAll("#opttargets tbody tr").length,
    };
    host.append(el("pre", { id: "optselftest", hidden: true }, JSON.stringify(out)));
  }
})();
