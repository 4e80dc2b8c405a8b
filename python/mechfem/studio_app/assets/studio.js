/* The studio's page: the design from the server (over the websocket, as the report's data plus data.studio), the
 * mechanism on a canvas whose points can be dragged, the named dimensions, det(D^c) with its limit positions and the
 * report's charts (charts.js), undo/redo, save, open, and the optimisation of a path through clicked points.
 * window.mechfemStudio exposes the state the browser tests and the benchmark read. */
"use strict";
(function () {
  const C = MechfemCharts, el = C.el, fmt = C.fmt;
  const $ = (id) => document.getElementById(id);
  const token = new URLSearchParams(location.search).get("token") || "";
  const RATE = 20; // positions per second while playing, as in the report
  const HANDLE = 7; // radius of a point's handle, CSS pixels
  const state = {
    D: null, cur: 0, box: null, charts: [], detChart: null, timer: null,
    drag: null, group: 0, inflight: false, queued: null, sentAt: 0,
    latencies: [], revision: -1, messages: 0, picking: false, targets: [], lastSaved: null, lastReply: null,
    optimising: false, iterations: 0, errors: [],
  };
  window.addEventListener("error", (e) => state.errors.push(String(e.message)));
  window.mechfemStudio = state;

  // ---- the websocket ----
  const ws = new WebSocket("ws://" + location.host + "/ws?token=" + encodeURIComponent(token));
  function send(message) {
    if (state.inflight) { state.queued = message; return; }
    state.inflight = true;
    state.sentAt = performance.now();
    ws.send(JSON.stringify(message));
  }
  state.send = send;
  ws.addEventListener("message", (e) => {
    const t0 = performance.now();
    const m = JSON.parse(e.data);
    state.parseMs = performance.now() - t0;
    state.arriveMs = t0 - state.sentAt;
    state.messages++;
    if (m.type === "hello") { hello(m); return; }
    if (m.type === "iteration") { state.iterations++; showDesign(m.design, false); optStatus("iteration " + m.number + ": objective " + fmt(m.objective)); return; }
    state.inflight = false;
    if (m.changes) m.design = merge(state.D, m.changes);
    state.lastReply = m;
    reply(m);
    if (state.queued) { const q = state.queued; state.queued = null; send(q); }
  });
  ws.addEventListener("close", () => say("refused", "The connection to the studio's server is closed: start `mechfem studio` again."));

  // An edit's answer holds only what differs from the design on screen (python/mechfem/studio_app/delta.py): put it
  // into a copy of that design, object by object ("__gone__" lists the keys no longer there).
  function merge(old, changes) {
    const out = Object.assign({}, old);
    for (const k of Object.keys(changes)) {
      const v = changes[k], before = out[k];
      if (k === "__gone__") continue;
      const plain = (o) => o !== null && typeof o === "object" && !Array.isArray(o);
      out[k] = plain(v) && plain(before) ? merge(before, v) : v;
    }
    for (const k of changes.__gone__ || []) delete out[k];
    return out;
  }
  state.merge = merge;

  function hello(m) {
    const sel = $("examples");
    for (const name of m.examples) sel.append(el("option", { value: name }, name));
    sel.hidden = !m.examples.length;
    listFiles(m);
    if (m.design) showDesign(m.design, true);
  }
  // The decks of the folder the studio was pointed at (opened by their path, with the files beside them).
  function listFiles(m) {
    if (!("files" in m)) return;
    const sel = $("files");
    sel.textContent = "";
    sel.append(el("option", { value: "" }, "Decks in " + (m.folder || "the folder") + "…"));
    for (const name of m.files) sel.append(el("option", { value: name }, name));
    sel.hidden = !m.folder;
    state.files = m.files;
  }

  function reply(m) {
    const took = performance.now() - state.sentAt;
    if (m.type === "design") {
      const sentAt = state.sentAt;
      showDesign(m.design, !!m.opened);
      const drawn = performance.now() - sentAt;
      // Edit to redraw: until the frame after the new design is drawn (uPlot draws its charts in a task of their own).
      // Until the end of the task: the charts' own drawing (uPlot draws in a microtask after the new numbers).
      setTimeout(() => { state.committedMs = performance.now() - sentAt; }, 0);
      requestAnimationFrame(() => {
        const frame = performance.now() - sentAt;
        setTimeout(() => state.latencies.push({ drawn: drawn, painted: performance.now() - sentAt, server: m.server_ms, server_cpu: m.server_cpu_ms, run: m.run_ms,
          arrive: state.arriveMs, parse: state.parseMs, charts: state.chartsMs, show: state.showMs, shown: drawn, frame: frame, committed: state.committedMs }));
      });
      if (m.branch) { say("branch", m.branch); state.branchGroup = state.group; }
      // A branch change during a drag stays said for the rest of that drag (until the next edit).
      else if (state.branchGroup === state.group && !m.opened && !m.optimised) void 0;
      else if (m.opened) say("ok", "Opened " + (m.design.studio.deck || m.design.studio.name) + ".");
      else if (m.optimised) optimised(m.optimised);
      else say("ok", "Recomputed " + m.design.positions + " positions in " + fmt(Math.round(drawn)) + " ms (the core: " + fmt(m.run_ms === undefined ? m.server_ms : m.run_ms) + " ms).");
    } else if (m.type === "refused") {
      if (state.optimising) { state.optimising = false; optStatus(m.message); }
      say("refused", "Not applied: " + m.message + " The last good design is shown.");
      if (state.D) { showDimensions(true); draw(); }
    } else if (m.type === "saved") {
      state.lastSaved = m;
      say("ok", "Saved " + m.files.join(", ") + ".");
      listFiles({ folder: m.folder, files: m.decks });
    } else if (m.type === "files") {
      listFiles(m);
    } else {
      say("refused", m.message || "the server could not act on that");
    }
    void took;
  }

  function say(kind, text) {
    const st = $("status");
    st.className = "status " + kind;
    st.textContent = text;
  }

  // ---- the design on screen ----
  function showDesign(D, opened) {
    const first = !state.D || opened;
    state.D = D;
    state.revision = D.studio.revision;
    state.cur = Math.min(state.cur, D.frames.length - 1);
    if (first || !state.box || (!state.drag && !inside(state.box))) fit();
    $("title").textContent = D.studio.name + ": mechfem studio";
    $("summary").textContent = (D.studio.deck || "not saved yet") + " - " + D.positions + " of " + D.asked + " positions" +
      (D.stop ? " - the motion stops: " + D.stop : "");
    $("slider").max = String(D.frames.length - 1);
    $("undo").disabled = !D.studio.can_undo;
    $("redo").disabled = !D.studio.can_redo;
    $("save").disabled = false;
    if (!$("savepath").value) $("savepath").value = D.studio.deck ? D.studio.deck.replace(/\.mec$/i, "_studio.mec") : D.studio.name + ".mec";
    if (first) buildOptimise();
    if (first || dimensionsOf !== dimensionNames(D)) buildDimensions();
    else if (!state.drag) showDimensions();
    const t0 = performance.now();
    buildCharts();
    const t1 = performance.now();
    const limits = JSON.stringify([D.stop, D.det.limits]);
    if (first || limits !== limitsShown) { buildLimits(); limitsShown = limits; }
    show(state.cur);
    state.chartsMs = t1 - t0;
    state.showMs = performance.now() - t1;
  }

  // The box of the drawing, its paths and the clicked targets.
  function extent() {
    const D = state.D;
    const b = D.scene.bounds.map((v) => (v === null ? 0 : v));
    for (const t of state.targets) { b[0] = Math.min(b[0], t[0]); b[1] = Math.max(b[1], t[0]); b[2] = Math.min(b[2], t[1]); b[3] = Math.max(b[3], t[1]); }
    for (const p of D.paths) {
      for (const v of D.columns[p.x].values) if (v !== null) { b[0] = Math.min(b[0], v); b[1] = Math.max(b[1], v); }
      for (const v of D.columns[p.y].values) if (v !== null) { b[2] = Math.min(b[2], v); b[3] = Math.max(b[3], v); }
    }
    return b;
  }
  function inside(box) {
    const b = extent();
    return b[0] >= box[0] && b[1] <= box[1] && b[2] >= box[2] && b[3] <= box[3];
  }
  function fit() {
    const b = extent();
    const pad = 0.12 * Math.max(b[1] - b[0], b[3] - b[2], 1e-9);
    state.box = [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad];
    layout(true);
  }

  const mech = { canvas: $("mechanism") };
  function layout(force) {
    if (!state.box) return;
    const f = MechfemScene.fit(state.box, Math.max(240, $("canvaswrap").clientWidth), 240, window.innerHeight - 220);
    const w = f.w, h = f.h, r = f.r, s = f.s, cx = f.cx, cy = f.cy;
    if (!force && mech.w === w && mech.h === h && mech.r === r) return;
    Object.assign(mech, { w: w, h: h, r: r });
    MechfemScene.size(mech.canvas, f);
    mech.s = s;
    mech.X = (x) => w / 2 + (x - cx) * s; // CSS pixels
    mech.Y = (y) => h / 2 - (y - cy) * s;
    mech.x = (X) => cx + (X - w / 2) / s; // back to the model
    mech.y = (Y) => cy - (Y - h / 2) / s;
    draw();
  }

  let order = null, orderOf = null;
  function draw() {
    const D = state.D;
    if (!D || !mech.X) return;
    if (orderOf !== D) { order = MechfemScene.layers(D); orderOf = D; }
    const ctx = mech.canvas.getContext("2d"), r = mech.r;
    const X = (x) => mech.X(x) * r, Y = (y) => mech.Y(y) * r;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, mech.canvas.width, mech.canvas.height);
    MechfemScene.draw(D, order, ctx, X, Y, mech.s * r, state.cur, 1, r);
    D.paths.forEach((p, k) => {
      const colour = C.PALETTE[k % C.PALETTE.length], xs = D.columns[p.x].values, ys = D.columns[p.y].values;
      ctx.strokeStyle = colour;
      ctx.globalAlpha = 0.45; ctx.lineWidth = 1.5 * r; MechfemScene.polyline(ctx, X, Y, xs, ys);
      ctx.globalAlpha = 1; ctx.lineWidth = 2.4 * r; MechfemScene.polyline(ctx, X, Y, xs, ys, state.cur);
      const x = xs[state.cur], y = ys[state.cur];
      if (x !== null && y !== null) C.dot(ctx, X(x), Y(y), 5 * r, colour);
    });
    // The handles: at position 1 of the last good run (a moving point's start estimate is drawn faint).
    ctx.font = 12 * r + "px sans-serif";
    for (const p of D.studio.points) {
      const x = X(p.at[0]), y = Y(p.at[1]);
      ctx.lineWidth = 1.5 * r;
      ctx.strokeStyle = p.fixed ? "#1f3b57" : "#0072B2";
      ctx.fillStyle = state.drag && state.drag.name === p.name ? "#ffd54f" : "rgba(255,255,255,0.85)";
      ctx.beginPath();
      if (p.fixed) ctx.rect(x - HANDLE * r, y - HANDLE * r, 2 * HANDLE * r, 2 * HANDLE * r);
      else ctx.arc(x, y, HANDLE * r, 0, 2 * Math.PI);
      ctx.fill(); ctx.stroke();
      ctx.fillStyle = "#1f3b57";
      ctx.fillText(p.name, x + 9 * r, y - 9 * r);
    }
    // The clicked target points of a path's optimisation.
    if ($("opttarget").value === "path") state.targets.forEach((t, k) => {
      const x = X(t[0]), y = Y(t[1]);
      ctx.strokeStyle = "#c0392b"; ctx.lineWidth = 2 * r;
      ctx.beginPath(); ctx.moveTo(x - 6 * r, y - 6 * r); ctx.lineTo(x + 6 * r, y + 6 * r);
      ctx.moveTo(x + 6 * r, y - 6 * r); ctx.lineTo(x - 6 * r, y + 6 * r); ctx.stroke();
      ctx.fillStyle = "#c0392b"; ctx.fillText("T" + (k + 1), x + 8 * r, y + 14 * r);
    });
  }

  function positionText(f) {
    const D = state.D, cols = D.columns;
    const parts = D.position_columns.map((k) => cols[k].name + " = " + (cols[k].unit ? fmt(cols[k].values[f]) + " " + cols[k].unit : fmt(cols[k].values[f])));
    return "position " + (D.frames[f] + 1) + " of " + D.positions + (parts.length ? ": " + parts.join(", ") : "");
  }
  function show(f) {
    const D = state.D;
    state.cur = Math.max(0, Math.min(D.frames.length - 1, f | 0));
    $("slider").value = String(state.cur);
    $("poslabel").textContent = positionText(state.cur);
    draw();
    for (const c of state.charts) c.redraw();
  }

  // ---- charts: det(D^c) and the report's cards, built anew for every design ----
  const page = {
    get D() { return state.D; }, cur: () => state.cur, goTo: (f) => show(f),
    drawScene: (ctx, X, Y, s, f, alpha, r) => MechfemScene.draw(state.D, order || MechfemScene.layers(state.D), ctx, X, Y, s, f, alpha, r),
    pathColour: (x, y) => { const k = state.D.paths.findIndex((p) => p.x === x && p.y === y); return C.PALETTE[Math.max(k, 0) % C.PALETTE.length]; },
  };
  // The charts' make-up (which curves against which, in which cards): while it stays, an edit's new numbers are drawn
  // into the charts there are (Chart.update); a new uPlot chart costs many times more.
  function chartsMakeUp(D) {
    const chart = (c) => [c.type, c.x, c.series.map((s) => [s.x, s.y, s.fx, s.fy]), (c.hodographs || []).length, c.title, c.xlabel, c.ylabel];
    return JSON.stringify([D.stem, D.det.x, D.det.y, D.columns[D.det.x].axis, D.cards.map((card) => [card.title, card.note, card.charts.map(chart)])]);
  }
  const chartPage = { D: null, cur: page.cur, goTo: page.goTo, drawScene: page.drawScene, pathColour: page.pathColour };
  let madeUp = null;
  function buildCharts() {
    const D = state.D;
    const det = D.det;
    const detSpec = {
      type: "function", x: det.x, series: [{ y: det.y }], xlabel: D.columns[det.x].axis, ylabel: D.columns[det.y].axis,
      limits: det.limits, zero: true, title: "det(D^c) against " + D.columns[det.x].name,
    };
    const makeUp = chartsMakeUp(D);
    chartPage.D = D;
    if (makeUp === madeUp && state.charts.length) {
      const specs = [detSpec].concat(...D.cards.map((card) => card.charts));
      state.charts.forEach((c, k) => c.update(specs[k]));
      return;
    }
    madeUp = makeUp;
    for (const c of state.charts) c.u.destroy();
    state.charts = [];
    $("detchart").textContent = "";
    $("cards").textContent = "";
    state.detChart = new C.Chart(chartPage, detSpec, $("detchart"), D.stem + "_det.csv");
    state.charts.push(state.detChart);
    for (const card of D.cards) {
      const box = el("section", { className: "panel card" }, el("h2", {}, card.title));
      $("cards").append(box);
      if (card.note) box.append(el("p", { className: "note" }, card.note));
      card.charts.forEach((spec, k) => state.charts.push(new C.Chart(chartPage, spec, box, D.stem + "_" + k + ".csv")));
    }
  }
  function buildLimits() {
    const D = state.D, lim = $("limits");
    lim.textContent = "";
    if (D.stop) lim.append(el("li", { className: "stop" }, "Motion stopped: " + D.stop));
    if (!D.det.limits.length) lim.append(el("li", { className: "note" }, "The run located no limit positions."));
    D.det.limits.forEach((m, k) => {
      const b = el("button", { type: "button" }, el("b", {}, String(k + 1)), " " + m.text);
      b.addEventListener("click", () => show(D.frames.indexOf(m.position) >= 0 ? D.frames.indexOf(m.position) : 0));
      lim.append(el("li", {}, b));
    });
  }

  // ---- dimensions: a slider and a number field each, in the model's units ----
  const ranges = {};
  let dimensionsOf = null, limitsShown = null;
  const dimensionNames = (D) => D.studio.dimensions.map((d) => d.name + "|" + d.unit).join("\n");
  // The values of an edited design into the fields there are (a field being typed into is left alone, unless
  // its edit was refused).
  function showDimensions(force) {
    for (const d of state.D.studio.dimensions) {
      const row = dimRows[d.name];
      if (!row) continue;
      const text = String(Number(d.value.toPrecision(10)));
      if ((force || document.activeElement !== row.num) && row.num.value !== text) row.num.value = text;
      if (force || document.activeElement !== row.range) row.range.value = String(d.value);
    }
  }
  const dimRows = {};
  function buildDimensions() {
    const D = state.D, host = $("dimlist");
    dimensionsOf = dimensionNames(D);
    host.textContent = "";
    for (const d of D.studio.dimensions) {
      if (!(d.name in ranges) || state.revision === 0) {
        const span = d.angle ? (d.unit === "deg" ? 180 : Math.PI) : Math.max(Math.abs(d.value), 1e-3);
        ranges[d.name] = d.angle ? [d.value - span, d.value + span] : [Math.min(0, d.value - span), d.value + span];
      }
      const [lo, hi] = ranges[d.name];
      const range = el("input", { type: "range", min: String(lo), max: String(hi), step: String((hi - lo) / 1000), value: String(d.value) });
      const num = el("input", { type: "number", step: "any", value: String(Number(d.value.toPrecision(10))) });
      range.setAttribute("aria-label", d.name);
      num.setAttribute("aria-label", d.name + " value");
      num.dataset.name = d.name;
      const label = el("label", { title: d.formula + (d.kind === "input" ? " (the input's start)" : "") }, d.name + (d.unit ? " [" + d.unit + "]" : ""));
      // One slider drag (or one key press on it) is one edit to undo.
      range.addEventListener("pointerdown", () => { state.group++; });
      range.addEventListener("keydown", () => { state.group++; });
      range.addEventListener("input", () => { num.value = range.value; edit({ [d.name]: +range.value }, true); });
      num.addEventListener("change", () => { state.group++; if (num.value !== "" && isFinite(+num.value)) edit({ [d.name]: +num.value }, false); });
      dimRows[d.name] = { range: range, num: num };
      host.append(el("div", { className: "dim" }, label, range, num));
    }
    if (!D.studio.dimensions.length) host.append(el("p", { className: "note" }, "This model has no prescribed values to change; drag its points."));
  }

  function edit(changes, grouped) {
    send({ op: "edit", changes: changes, group: grouped ? state.group : null });
  }

  // ---- dragging points and clicking targets on the canvas ----
  function at(e) {
    const b = mech.canvas.getBoundingClientRect();
    return [e.clientX - b.left, e.clientY - b.top];
  }
  function handleNear(px, py) {
    let best = null, bestD = (HANDLE + 4) ** 2;
    for (const p of state.D.studio.points) {
      const dx = mech.X(p.at[0]) - px, dy = mech.Y(p.at[1]) - py, d = dx * dx + dy * dy;
      if (d <= bestD) { bestD = d; best = p; }
    }
    return best;
  }
  mech.canvas.addEventListener("pointerdown", (e) => {
    if (!state.D) return;
    const [px, py] = at(e);
    if (state.picking) {
      state.targets.push([mech.x(px), mech.y(py)]);
      optStatus(state.targets.length + " point(s) clicked");
      draw();
      return;
    }
    const p = handleNear(px, py);
    if (!p) return;
    mech.canvas.setPointerCapture(e.pointerId);
    state.group++;
    state.drag = { name: p.name, dx: mech.x(px) - p.at[0], dy: mech.y(py) - p.at[1] };
    show(0);
  });
  mech.canvas.addEventListener("pointermove", (e) => {
    if (!state.D) return;
    const [px, py] = at(e);
    if (!state.drag) { mech.canvas.classList.toggle("grab", !state.picking && !!handleNear(px, py)); return; }
    const x = mech.x(px) - state.drag.dx, y = mech.y(py) - state.drag.dy;
    edit({ [state.drag.name]: [x, y] }, true);
  });
  function endDrag() {
    if (!state.drag) return;
    state.drag = null;
    showDimensions();
    if (!inside(state.box)) fit(); else draw();
  }
  mech.canvas.addEventListener("pointerup", endDrag);
  mech.canvas.addEventListener("pointercancel", endDrag);
  state.handleAt = (name) => {
    const p = state.D.studio.points.find((q) => q.name === name), b = mech.canvas.getBoundingClientRect();
    return [b.left + mech.X(p.at[0]), b.top + mech.Y(p.at[1])];
  };
  state.toScreen = (x, y) => { const b = mech.canvas.getBoundingClientRect(); return [b.left + mech.X(x), b.top + mech.Y(y)]; };

  // ---- optimisation ----
  function optStatus(text) { $("optstatus").textContent = text; }
  function buildOptimise() {
    const D = state.D, sel = $("optpoint"), vary = $("optvary");
    sel.textContent = "";
    const moving = D.studio.points.filter((p) => !p.fixed);
    for (const p of moving) sel.append(el("option", { value: p.name }, p.name));
    if (D.paths.length) sel.value = D.paths[D.paths.length - 1].name;
    const quantity = $("optquantity");
    quantity.textContent = "";
    for (const q of D.studio.quantities) quantity.append(el("option", { value: q }, q));
    vary.textContent = "";
    const names = D.studio.dimensions.filter((d) => d.kind !== "input").map((d) => d.name);
    // Every dimension and every frame pivot but the first (which keeps the design where it is) may vary.
    const pivots = D.studio.points.filter((p) => p.fixed).map((p) => p.name);
    for (const p of pivots) names.push(p + ".x", p + ".y");
    for (const n of names) {
      const box = el("input", { type: "checkbox", value: n, checked: !pivots.length || !n.startsWith(pivots[0] + ".") });
      box.setAttribute("aria-label", "vary " + n);
      vary.append(el("label", {}, box, " " + n));
    }
    state.targets = [];
    $("optimise").hidden = !names.length;
    $("opttarget").querySelector("option[value=path]").disabled = !moving.length;
    $("opttarget").querySelector("option[value=extremum]").disabled = !D.studio.quantities.length;
    $("opttarget").querySelector("option[value=transmission]").disabled = !D.studio.transmission;
    if ($("opttarget").selectedOptions[0].disabled) $("opttarget").value = moving.length ? "path" : "extremum";
    targetChosen();
  }
  // The controls of the target chosen: the clicked points of a path; the extremum's quantity and goal; the
  // transmission angle's least value (the bound of its own target, or a bound that goes with an extremum).
  function targetChosen() {
    const target = $("opttarget").value, D = state.D;
    $("optpath").hidden = target !== "path";
    $("optext").hidden = target !== "extremum";
    $("opttrans").hidden = target === "path" || !D || !D.studio.transmission;
    $("opttransok").parentElement.hidden = target === "transmission";
    $("optvalue").hidden = $("optgoal").value !== "value";
    const unit = D && D.studio.units.angle ? D.studio.units.angle : "rad", half = unit === "deg" ? 180 : Math.PI;
    $("opttranshi").textContent = "to " + fmt(half - (+$("opttranslo").value || 0)) + " " + unit + " at every position";
    if (target !== "path" && state.picking) $("optclick").click();
    draw();
  }
  $("opttarget").addEventListener("change", targetChosen);
  $("optgoal").addEventListener("change", targetChosen);
  $("opttranslo").addEventListener("input", targetChosen);
  $("optclick").addEventListener("click", () => {
    state.picking = !state.picking;
    $("optclick").setAttribute("aria-pressed", String(state.picking));
    $("optclick").textContent = state.picking ? "Done clicking" : "Click target points";
    mech.canvas.classList.toggle("picking", state.picking);
  });
  $("optclear").addEventListener("click", () => { state.targets = []; optStatus(""); draw(); });
  $("optrun").addEventListener("click", () => {
    const vary = Array.from($("optvary").querySelectorAll("input:checked")).map((b) => b.value);
    const target = $("opttarget").value;
    const message = { op: "optimise", target: target, vary: vary };
    if (target === "path") {
      if (!state.targets.length) { optStatus("Click the points the path should pass through first."); return; }
      if (state.picking) $("optclick").click();
      Object.assign(message, { point: $("optpoint").value, points: state.targets });
    } else if (target === "extremum") {
      Object.assign(message, { quantity: $("optquantity").value, which: $("optwhich").value, goal: $("optgoal").value,
        value: $("optgoal").value === "value" ? $("optvalue").value : null,
        transmission: $("opttransok").checked ? $("opttranslo").value : null });
    } else {
      message.transmission = $("opttranslo").value;
    }
    state.optimising = true;
    state.iterations = 0;
    optStatus("optimising...");
    say("busy", "Optimising: the drawing shows the optimiser's designs as it goes.");
    send(message);
  });
  function optimised(o) {
    state.optimising = false;
    let text = "Done in " + o.iterations + " iterations (objective " + fmt(o.objective) + "): ";
    if (o.target === "path") {
      text += "the path of " + $("optpoint").value + " passes within " + fmt(Math.max(...o.distances)) +
        " of every clicked point, as drawn at the motion's positions.";
    } else text += o.said;
    optStatus(text + " " + o.message);
    say("ok", "Optimised: " + Object.entries(o.values).map(([k, v]) => k + " = " + fmt(v)).join(", ") + ". Undo goes back.");
  }

  // ---- open, undo, redo, save ----
  $("template").addEventListener("click", () => send({ op: "template" }));
  $("files").addEventListener("change", (e) => { if (e.target.value) send({ op: "open_path", name: e.target.value }); e.target.value = ""; });
  $("files").addEventListener("focus", () => send({ op: "files" }));
  $("examples").addEventListener("change", (e) => { if (e.target.value) send({ op: "example", name: e.target.value }); e.target.value = ""; });
  function openFile(file) { file.text().then((text) => send({ op: "open_text", name: file.name, text: text })); }
  $("file").addEventListener("change", (e) => { if (e.target.files[0]) openFile(e.target.files[0]); e.target.value = ""; });
  document.addEventListener("dragover", (e) => { e.preventDefault(); document.body.classList.add("dropping"); });
  document.addEventListener("dragleave", () => document.body.classList.remove("dropping"));
  document.addEventListener("drop", (e) => {
    e.preventDefault();
    document.body.classList.remove("dropping");
    if (e.dataTransfer.files[0]) openFile(e.dataTransfer.files[0]);
  });
  $("undo").addEventListener("click", () => send({ op: "undo" }));
  $("redo").addEventListener("click", () => send({ op: "redo" }));
  $("save").addEventListener("click", () => send({ op: "save", path: $("savepath").value }));
  $("fit").addEventListener("click", fit);
  $("slider").addEventListener("input", (e) => show(+e.target.value));
  function setPlaying(on) {
    if (on && !state.timer && state.D) state.timer = setInterval(() => show((state.cur + 1) % state.D.frames.length), 1000 / RATE);
    if (!on && state.timer) { clearInterval(state.timer); state.timer = null; }
    $("play").textContent = state.timer ? "Pause" : "Play";
  }
  $("play").addEventListener("click", () => setPlaying(!state.timer));
  document.addEventListener("keydown", (e) => {
    if (/^(INPUT|SELECT|TEXTAREA)$/.test(e.target.tagName)) return;
    if ((e.ctrlKey || e.metaKey) && e.key.toLowerCase() === "z") { send({ op: e.shiftKey ? "redo" : "undo" }); e.preventDefault(); }
    if (e.key === " ") { setPlaying(!state.timer); e.preventDefault(); }
  });
  new ResizeObserver(() => layout(false)).observe($("canvaswrap"));
})();
