/* The mechanism's drawing on a canvas, from the report's scene data (python/mechfem/report/html.py, _scene): shapes by
 * kind and role, those that never move sent once, the moving ones per frame, each drawn in its role's style, the
 * layers in order. Used by the report's page (page.js), its optimisation section (optimisation.js) and the studio. */
"use strict";
const MechfemScene = (function () {
  const PT = 1.25; // CSS pixels per point, for the drawing's line widths

  function shapeData(D, f) {
    const sc = D.scene;
    const out = new Array(sc.kinds.length);
    for (const k in sc.static) out[+k] = sc.static[k];
    sc.moving.forEach((i, j) => { out[i] = sc.frames[f][j]; });
    return out;
  }
  function layers(D) {
    return D.scene.kinds.map((_, i) => i)
      .sort((a, b) => (D.styles[D.scene.roles[a]].layer - D.styles[D.scene.roles[b]].layer) || (a - b));
  }

  /* The outline of one shape (mechfem.viz.drawing: kind "line", "polygon", "circle", "arc" or "segments", d its numbers
   * in the model's units) as a new path on ctx, to be stroked or filled by the caller. */
  function traceShape(ctx, kind, d, X, Y, s) {
    ctx.beginPath();
    if (kind === "line" || kind === "polygon") {
      ctx.moveTo(X(d[0]), Y(d[1]));
      for (let j = 2; j < d.length; j += 2) ctx.lineTo(X(d[j]), Y(d[j + 1]));
      if (kind === "polygon") ctx.closePath();
    } else if (kind === "circle") {
      ctx.arc(X(d[0]), Y(d[1]), Math.max(d[2] * s, 0.5), 0, 2 * Math.PI);
    } else if (kind === "arc") {
      // Counter-clockwise with y up is anticlockwise on the canvas, whose y points down.
      ctx.arc(X(d[0]), Y(d[1]), d[2] * s, -d[3], -d[4], true);
    } else if (kind === "segments") {
      for (let j = 0; j < d.length; j += 4) {
        ctx.moveTo(X(d[j]), Y(d[j + 1]));
        ctx.lineTo(X(d[j + 2]), Y(d[j + 3]));
      }
    }
  }

  // X, Y: model to canvas pixels; s: canvas pixels per unit of length; r: canvas pixels per CSS pixel.
  function draw(D, order, ctx, X, Y, s, f, alpha, r) {
    const sc = D.scene, data = shapeData(D, f);
    ctx.save();
    ctx.globalAlpha = alpha;
    ctx.lineJoin = "round";
    ctx.lineCap = "round";
    for (const i of order) {
      const d = data[i];
      if (d.some((x) => x === null)) continue;
      const st = D.styles[sc.roles[i]], kind = sc.kinds[i];
      ctx.strokeStyle = st.edge;
      ctx.lineWidth = st.width * PT * r;
      ctx.setLineDash(st.dash ? [6 * r, 4 * r] : []);
      traceShape(ctx, kind, d, X, Y, s);
      if (st.fill && (kind === "polygon" || kind === "circle")) { ctx.fillStyle = st.fill; ctx.fill(); }
      ctx.stroke();
    }
    ctx.restore();
  }
  function polyline(ctx, X, Y, xs, ys, upto) {
    ctx.beginPath();
    let pen = false;
    const n = upto === undefined ? xs.length : Math.min(upto + 1, xs.length);
    for (let k = 0; k < n; k++) {
      if (xs[k] === null || ys[k] === null) { pen = false; continue; }
      if (pen) ctx.lineTo(X(xs[k]), Y(ys[k])); else ctx.moveTo(X(xs[k]), Y(ys[k]));
      pen = true;
    }
    ctx.stroke();
  }
  /* How a drawing of the model's box b ([xmin, xmax, ymin, ymax]) fits w CSS pixels of width: as high as its shape
   * needs between hMin and hMax, its scale s (CSS pixels per model unit), the box's centre and the device pixel ratio. */
  function fit(b, w, hMin, hMax) {
    const aspect = (b[3] - b[2]) / Math.max(b[1] - b[0], 1e-12);
    const h = Math.round(Math.max(hMin, Math.min(w * aspect, hMax)));
    const s = Math.min((w - 12) / Math.max(b[1] - b[0], 1e-12), (h - 12) / Math.max(b[3] - b[2], 1e-12));
    return { w: w, h: h, r: window.devicePixelRatio || 1, s: s, cx: (b[0] + b[1]) / 2, cy: (b[2] + b[3]) / 2 };
  }
  /* The canvas holds the fit f in device pixels and is shown at its size in CSS pixels, sharp on any screen. */
  function size(canvas, f) {
    canvas.width = Math.round(f.w * f.r);
    canvas.height = Math.round(f.h * f.r);
    canvas.style.width = f.w + "px";
    canvas.style.height = f.h + "px";
  }
  return { draw: draw, fit: fit, layers: layers, polyline: polyline, size: size, traceShape: traceShape };
})();
