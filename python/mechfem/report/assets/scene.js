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
  return { draw: draw, layers: layers, polyline: polyline, traceShape: traceShape };
})();
