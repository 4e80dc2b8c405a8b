/* The report page: the mechanism on a canvas with its slider and play controls, the charts (charts.js), the
 * limit positions, the status of the run and the table of buffers, all from the JSON in <script id="data">.
 * Opened as ...#position=N it starts at position N; opened as ...#selftest it checks itself (see the end). */
"use strict";

(function () {
  const errors = [];
  window.addEventListener("error", (e) => errors.push(String(e.message)));
  const consoleError = console.error;
  console.error = (...args) => { errors.push(args.map(String).join(" ")); consoleError.apply(console, args); };
  const D = JSON.parse(document.getElementById("data").textContent);
  const F = D.frames.length;
  const C = MechfemCharts, el = C.el, fmt = C.fmt;
  const RATE = 20; // positions per second at 1x, as in the animation
  const cols = D.columns;
  let cur = 0;
  let timer = null, due = 0;
  const charts = [];
  let detChart = null;

  function $(id) { return document.getElementById(id); }
  function withUnit(text, unit) { return unit ? text + " " + unit : text; }
  function nearestFrame(position) {
    let best = 0;
    D.frames.forEach((k, f) => { if (Math.abs(k - position) < Math.abs(D.frames[best] - position)) best = f; });
    return best;
  }

  // ---- the traced paths: each point its own colour ----
  const pathColours = {};
  let colourCount = 0;
  function pathColour(x, y) {
    const key = x + " " + y;
    if (!(key in pathColours)) pathColours[key] = C.PALETTE[colourCount++ % C.PALETTE.length];
    return pathColours[key];
  }
  D.paths.forEach((p) => pathColour(p.x, p.y));

  // ---- the mechanism ----
  const S = MechfemScene; // the drawing (scene.js)
  const ORDER = S.layers(D);
  // X, Y: model to canvas pixels; s: canvas pixels per unit of length; r: canvas pixels per CSS pixel.
  function drawScene(ctx, X, Y, s, f, alpha, r) { S.draw(D, ORDER, ctx, X, Y, s, f, alpha, r); }

  const mech = { canvas: $("mechanism") };
  (function mechanismBox() {
    let b = D.scene.bounds.slice();
    for (const p of D.paths) {
      for (const v of cols[p.x].values) if (v !== null) { b[0] = Math.min(b[0], v); b[1] = Math.max(b[1], v); }
      for (const v of cols[p.y].values) if (v !== null) { b[2] = Math.min(b[2], v); b[3] = Math.max(b[3], v); }
    }
    const pad = 0.04 * Math.max(b[1] - b[0], b[3] - b[2], 1e-9);
    mech.box = [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad];
  })();

  // The drawing takes the stage's whole width, as high as its shape needs and the window allows.
  function layoutMechanism() {
    const f = MechfemScene.fit(mech.box, Math.max(240, $("canvaswrap").clientWidth), 240, window.innerHeight - 200);
    const w = f.w, h = f.h, r = f.r, s = f.s, cx = f.cx, cy = f.cy;
    if (mech.w === w && mech.h === h && mech.r === r) return;
    Object.assign(mech, { w: w, h: h, r: r });
    MechfemScene.size(mech.canvas, f);
    mech.X = (x) => (w / 2 + (x - cx) * s) * r;
    mech.Y = (y) => (h / 2 - (y - cy) * s) * r;
    mech.s = s * r;
    drawMechanism();
  }

  function drawMechanism() {
    const ctx = mech.canvas.getContext("2d"), X = mech.X, Y = mech.Y, r = mech.r;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, mech.canvas.width, mech.canvas.height);
    ctx.lineJoin = "round";
    // The mechanism first and the paths over it: a coupler point's path runs across its plate.
    drawScene(ctx, X, Y, mech.s, cur, 1, r);
    for (const p of D.paths) {
      const colour = pathColour(p.x, p.y), xs = cols[p.x].values, ys = cols[p.y].values;
      ctx.strokeStyle = colour;
      ctx.globalAlpha = 0.45; ctx.lineWidth = 1.5 * r; S.polyline(ctx, X, Y, xs, ys);
      ctx.globalAlpha = 1; ctx.lineWidth = 2.4 * r; S.polyline(ctx, X, Y, xs, ys, cur);
    }
    for (const p of D.paths) {
      const colour = pathColour(p.x, p.y), x = cols[p.x].values[cur], y = cols[p.y].values[cur];
      if (x === null || y === null) continue;
      const vx = p.vx ? cols[p.vx].values[cur] : null, vy = p.vy ? cols[p.vy].values[cur] : null;
      if (vx !== null && vy !== null && p.scale) C.arrow(ctx, X(x), Y(y), X(x + vx * p.scale), Y(y + vy * p.scale), colour, 2.4 * r);
      C.dot(ctx, X(x), Y(y), 5 * r, colour);
      ctx.font = 12 * r + "px sans-serif";
      ctx.fillStyle = "#1f3b57";
      ctx.fillText(p.name, X(x) + 7 * r, Y(y) - 7 * r);
    }
  }

  // ---- the page's text: header, status, limits, table ----
  function positionText(f) {
    const parts = D.position_columns.map((k) => cols[k].name + " = " + withUnit(fmt(cols[k].values[f]), cols[k].unit));
    return "position " + (D.frames[f] + 1) + " of " + D.positions + (parts.length ? ": " + parts.join(", ") : "");
  }

  function buildText() {
    $("title").textContent = D.stem + ": mechfem report";
    $("summary").textContent = D.deck + " - " + D.positions + " of " + D.asked + " positions computed - mechfem " + D.version;
    document.title = D.stem + " - mechfem report";
    if (D.subsample_note) { $("subsample").textContent = D.subsample_note; $("subsample").hidden = false; }
    const st = $("status");
    if (D.stop) st.append(el("p", { className: "stop" }, "Motion stopped: " + D.stop));
    for (const w of D.warnings) st.append(el("p", { className: "warn" }, "Warning: " + w));
    if (!D.stop && !D.warnings.length) st.append(el("p", { className: "ok" }, "Every position asked for was computed; no warnings."));
    $("drawnotes").textContent = D.drawing_notes.join(" ");
    // Transmission angles and input sweep ranges (mechfem.results.designer), as the print file says them.
    if (D.designer && D.designer.length) {
      $("designer").textContent = D.designer.join("\n");
      $("designer").hidden = false;
    }
    const legend = $("pathlegend");
    for (const p of D.paths) {
      legend.append(el("li", {}, el("i", { className: "swatch", style: "background:" + pathColour(p.x, p.y) }), "path of " + p.name));
    }
    legend.hidden = !D.paths.length;
    const lim = $("limits");
    if (!D.det.limits.length) lim.append(el("li", { className: "note" }, "The run located no limit positions."));
    D.det.limits.forEach((m, k) => {
      const b = el("button", { type: "button", title: "go to position " + (m.position + 1) }, el("b", {}, String(k + 1)), " " + m.text);
      b.dataset.frame = String(nearestFrame(m.position));
      b.addEventListener("click", () => show(+b.dataset.frame));
      lim.append(el("li", {}, b));
    });
    $("tablenote").textContent = D.table.length
      ? (D.subsample_note ? D.subsample_note + " " : "") + "The highlighted row is the slider's position."
      : "The deck records no buffers.";
    const table = $("buffers");
    const head = el("tr", {}, el("th", {}, "position"));
    for (const k of D.table) {
      const th = el("th", { title: cols[k].text }, cols[k].header.split(" ")[0]);
      th.append(el("small", {}, cols[k].axis));
      head.append(th);
    }
    const tbody = el("tbody", {});
    for (let f = 0; f < F; f++) {
      const tr = el("tr", {});
      tr.append(el("td", {}, String(D.frames[f] + 1)));
      for (const k of D.table) tr.append(el("td", {}, fmt(cols[k].values[f])));
      tbody.append(tr);
    }
    table.append(el("thead", {}, head), tbody);
    $("footer").textContent = "Self-contained report written by mechfem " + D.version +
      "; it loads nothing from the network. Charts drawn by uPlot (MIT licence).";
  }

  // ---- the charts ----
  const page = { D: D, cur: () => cur, goTo: (f) => show(f), drawScene: drawScene, pathColour: pathColour };
  function slug(text) { return text.toLowerCase().replace(/[^a-z0-9]+/g, "_").replace(/^_|_$/g, "").slice(0, 40); }
  function buildCharts() {
    const det = D.det;
    detChart = new C.Chart(page, {
      type: "function", x: det.x, series: [{ y: det.y }], xlabel: cols[det.x].axis, ylabel: cols[det.y].axis,
      limits: det.limits, zero: true, title: "det(D^c) against " + cols[det.x].name,
    }, $("detchart"), D.stem + "_det.csv");
    detChart.card = "det";
    charts.push(detChart);
    const host = $("cards");
    host.append(el("p", { className: "note", style: "grid-column: 1 / -1; margin: 0" },
      "On every chart: drag to zoom, double-click or Reset zoom to see everything, click to go to that position; " +
      "CSV saves the chart's numbers."));
    D.cards.forEach((card, i) => {
      const box = el("section", { className: "panel card" }, el("h2", {}, card.title));
      host.append(box);
      card.box = box;
      if (card.note) box.append(el("p", { className: "note" }, card.note));
      if (card.jump) {
        const b = el("button", { type: "button", className: "jump" }, card.jump.text);
        b.addEventListener("click", () => show(card.jump.frame));
        box.append(b);
      }
      const stem = D.stem + "_" + (card.picture ? "pic" + card.picture : slug(card.title));
      card.charts.forEach((spec, k) => {
        const c = new C.Chart(page, spec, box, stem + (card.charts.length > 1 ? "_" + (k + 1) : "") + ".csv");
        c.card = i;
        charts.push(c);
      });
    });
  }

  // ---- the slider, play and speed ----
  let currentRow = null;
  function show(f) {
    cur = Math.max(0, Math.min(F - 1, f | 0));
    $("slider").value = String(cur);
    $("poslabel").textContent = positionText(cur);
    drawMechanism();
    for (const c of charts) c.redraw();
    const rows = $("buffers").tBodies[0] ? $("buffers").tBodies[0].rows : [];
    if (currentRow) currentRow.classList.remove("current");
    currentRow = rows[cur] || null;
    if (currentRow) {
      currentRow.classList.add("current");
      const wrap = $("tablewrap");
      const top = currentRow.offsetTop, bottom = top + currentRow.offsetHeight;
      if (top < wrap.scrollTop + 24 || bottom > wrap.scrollTop + wrap.clientHeight) wrap.scrollTop = Math.max(0, top - wrap.clientHeight / 2);
    }
  }
  // Every tick of 1/RATE s moves the slider by the speed's share of a position.
  function step() {
    due += +$("speed").value;
    const n = Math.floor(due);
    if (n > 0) { due -= n; show((cur + n) % F); }
  }
  function setPlaying(on) {
    if (on && !timer && F > 1) { due = 0; timer = setInterval(step, 1000 / RATE); }
    if (!on && timer) { clearInterval(timer); timer = null; }
    $("play").textContent = timer ? "Pause" : "Play";
  }

  buildText();
  layoutMechanism();
  buildCharts();
  $("slider").max = String(F - 1);
  $("slider").addEventListener("input", (e) => show(+e.target.value));
  $("play").addEventListener("click", () => setPlaying(!timer));
  document.addEventListener("keydown", (e) => {
    if (/^(INPUT|SELECT|BUTTON|TEXTAREA)$/.test(e.target.tagName)) return;
    if (e.key === " ") { setPlaying(!timer); e.preventDefault(); }
    if (e.key === "ArrowRight" || e.key === "ArrowLeft") { show(cur + (e.key === "ArrowRight" ? 1 : -1)); e.preventDefault(); }
  });
  new ResizeObserver(layoutMechanism).observe($("canvaswrap"));
  window.addEventListener("resize", layoutMechanism);
  // #position=N starts at position N; &cards=K,L (0-based, in the data's order) moves those cards to the top of
  // the column of charts, beside the mechanism (as the docs' pictures show them).
  const m = /^#position=(\d+)(?:&cards=([\d,]+))?$/.exec(location.hash);
  if (m && m[2]) {
    for (const k of m[2].split(",").reverse()) if (D.cards[+k]) $("side").insertBefore(D.cards[+k].box, $("side").firstChild);
  }
  show(m ? nearestFrame(+m[1] - 1) : 0);

  // ---- the page's own check (opened as ...#selftest), read by tests/report/test_report_page.py ----
  function snapshot(canvas) {
    const img = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
    let ink = 0;
    for (let i = 0; i < img.length; i += 4) if (img[i + 3] > 0 && (img[i] < 245 || img[i + 1] < 245 || img[i + 2] < 245)) ink++;
    return { ink: ink, pixels: img, width: canvas.width };
  }
  function changed(a, b) {
    let n = 0;
    for (let i = 0; i < a.pixels.length; i += 4) {
      if (a.pixels[i] !== b.pixels[i] || a.pixels[i + 1] !== b.pixels[i + 1] || a.pixels[i + 2] !== b.pixels[i + 2]) n++;
    }
    return n;
  }
  function pixel(shot, x, y, r) {
    const i = 4 * (Math.round(y * r) * shot.width + Math.round(x * r));
    return [shot.pixels[i], shot.pixels[i + 1], shot.pixels[i + 2]];
  }
  const wait = (ms) => new Promise((done) => setTimeout(done, ms));
  function mouse(target, type, x, y) {
    const box = target.getBoundingClientRect();
    target.dispatchEvent(new MouseEvent(type, { bubbles: true, cancelable: true, button: 0, buttons: type === "mouseup" ? 0 : 1,
      clientX: box.left + x, clientY: box.top + y, movementX: 1, movementY: 1 }));
  }
  function pointer(target, type, x, y) {
    const box = target.getBoundingClientRect();
    target.dispatchEvent(new PointerEvent(type, { bubbles: true, button: 0, clientX: box.left + x, clientY: box.top + y }));
  }

  async function selftest() {
    await wait(100);
    const out = { frames: F, errors: errors };
    const root = document.documentElement;
    out.layout = {
      window: window.innerWidth, page: root.clientWidth, scroll: root.scrollWidth,
      stage: Math.round($("stage").getBoundingClientRect().width), side: Math.round($("side").getBoundingClientRect().width),
      mechanism: [mech.canvas.clientWidth, mech.canvas.clientHeight],
    };
    const rect = (e) => { const b = e.getBoundingClientRect(); return [b.left + scrollX, b.top + scrollY, b.width, b.height].map(Math.round); };
    out.rects = { mechanism: rect(mech.canvas), charts: charts.map((c) => rect(c.u.ctx.canvas)), limits: rect($("limits")) };
    out.uplots = document.querySelectorAll(".uplot").length;
    out.position_before = $("poslabel").textContent;
    const before = snapshot(mech.canvas);
    const dots0 = charts.map((c) => c.cursorDots.slice());
    const shots0 = charts.map((c) => snapshot(c.u.ctx.canvas));
    const target = Math.floor((F - 1) / 2);
    $("slider").value = String(target);
    $("slider").dispatchEvent(new Event("input", { bubbles: true }));
    await wait(20); // uPlot draws in a task of its own
    const after = snapshot(mech.canvas);
    out.mechanism = { ink_before: before.ink, ink_after: after.ink, changed_pixels: changed(before, after) };
    out.position_after = $("poslabel").textContent;
    out.slider = { target: target, current: cur };
    out.charts = charts.map((c, i) => {
      const shot = snapshot(c.u.ctx.canvas);
      return {
        card: c.card, type: c.spec.type, uplot: c.u.root.classList.contains("uplot"), curves: c.curves.map((x) => x.name),
        xlabel: c.spec.xlabel, ylabel: c.spec.ylabel, ink: shot.ink, changed_pixels: changed(shots0[i], shot),
        cursor_before: dots0[i], cursor_after: c.cursorDots.slice(), readout: c.readout.textContent, csv: c.csv(),
        forces: c.forceArrows.slice(),
        width: c.u.width,
        // CSS pixels per unit along x and along y (equal for a path in the plane).
        pixels_per_unit: [c.u.valToPos(1, "x") - c.u.valToPos(0, "x"), c.u.valToPos(0, "y") - c.u.valToPos(1, "y")],
      };
    });
    const detShot = snapshot(detChart.u.ctx.canvas);
    out.det = { limits: D.det.limits.length, markers: detChart.markers.slice(),
                marker_colours: detChart.markers.map((m) => pixel(detShot, m.x, m.y, detChart.ratio())) };
    out.limit_clicks = Array.from(document.querySelectorAll("#limits button")).map((b) => {
      show(0);
      b.click();
      return { frame: +b.dataset.frame, position: D.frames[+$("slider").value] + 1, slider: +$("slider").value };
    });
    // A click on the first chart's curve at a quarter of the motion moves the slider there.
    const probe = charts.find((c) => c.card !== "det") || detChart;
    const want = Math.floor((F - 1) / 4), u = probe.u, c0 = probe.curves[0];
    const px = u.valToPos(cols[c0.x].values[want], "x"), py = u.valToPos(cols[c0.y].values[want], "y");
    show(0);
    await wait(20);
    mouse(u.over, "mousemove", px, py);
    await wait(20);
    const hovered = probe.hover;
    pointer(u.over, "pointerdown", px, py);
    pointer(u.over, "pointerup", px, py);
    out.chart_click = { want: want, hovered: hovered, slider: +$("slider").value, readout: probe.readout.textContent };
    mouse(u.over, "mouseleave", -5, -5);
    // Drag to zoom, then double-click back.
    const x0 = u.scales.x.min, x1 = u.scales.x.max, w = u.over.clientWidth, h = u.over.clientHeight;
    mouse(u.over, "mousemove", 0.3 * w, 0.3 * h);
    mouse(u.over, "mousedown", 0.3 * w, 0.3 * h);
    mouse(u.over, "mousemove", 0.6 * w, 0.7 * h);
    mouse(u.over, "mouseup", 0.6 * w, 0.7 * h);
    await wait(20);
    const zoomed = [u.scales.x.min, u.scales.x.max];
    u.over.dispatchEvent(new MouseEvent("dblclick", { bubbles: true, button: 0 }));
    await wait(20);
    out.zoom = { before: [x0, x1], zoomed: zoomed, reset: [u.scales.x.min, u.scales.x.max] };
    // Play at two speeds for the same time.
    out.speeds = Array.from($("speed").options).map((o) => o.value);
    const moved = [];
    for (const s of ["4", "0.5"]) {
      show(0);
      $("speed").value = s;
      $("play").click();
      out.play = $("play").textContent;
      await wait(500);
      $("play").click();
      out.pause = $("play").textContent;
      moved.push(cur);
    }
    out.moved = moved;
    show(target);
    out.table_rows = $("buffers").tBodies[0].rows.length;
    out.current_row = currentRow ? currentRow.cells[0].textContent : null;
    out.resources = performance.getEntriesByType("resource").map((e) => e.name);
    const pre = $("selftest");
    pre.textContent = JSON.stringify(out);
    pre.hidden = false;
  }
  if (location.hash === "#selftest") selftest().catch((e) => { errors.push(String(e && e.stack || e)); $("selftest").textContent = JSON.stringify({ errors: errors }); });
})();
