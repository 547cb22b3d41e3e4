/* velpoly html: draws the sheet from the poses precomputed by velpoly (no solver here).
 *
 * Every drawn point, image and pole carries data-key, data-x, data-y (mechanism units: lengths,
 * velocities or accelerations) and data-sx, data-sy (SVG units of its panel), so that what is drawn
 * can be checked against `velpoly solve`. <body data-rendered="ANGLE"> says which pose was drawn. */
(function () {
  "use strict";
  var S = window.VELPOLY_STATIC, RAW = window.VELPOLY_POSES;
  var N = S.angles.length;
  var cache = [];
  var state = { i: S.start, step: 0, playing: false, timer: null, pinned: null };

  // -- data ---------------------------------------------------------------------------------------
  function decode(rec) {
    var nums = rec[1], sids = rec[2], ni = 0, si = 0;
    function fill(t) {
      if (t === 0) return nums[ni++];
      if (t === "") return RAW.strings[sids[si++]];
      if (Array.isArray(t)) { var a = []; for (var j = 0; j < t.length; j++) a.push(fill(t[j])); return a; }
      if (t && typeof t === "object") { var o = {}; for (var k in t) o[k] = fill(t[k]); return o; }
      return t;
    }
    return fill(RAW.templates[rec[0]]);
  }
  function pose(i) { if (!cache[i]) cache[i] = decode(RAW.poses[i]); return cache[i]; }

  // -- text ---------------------------------------------------------------------------------------
  function esc(s) {
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
  }
  var GREEK = { omega: "\u03c9", alpha: "\u03b1", theta: "\u03b8" };
  // a label such as b4, c', O_v, P_13, P_{10-12}, p\u2082 (p of link 2), p(cam) (p of link cam) in SVG: the
  // letters, a subscript, primes (velpoly.names writes a point of a link so)
  var SUBDIGITS = "\u2080\u2081\u2082\u2083\u2084\u2085\u2086\u2087\u2088\u2089";
  function splitLabel(s) {   // [letters, subscript, primes], or null
    var m = /^([A-Za-z]+)([0-9]*)([\u2080-\u2089]+|\([^()]*\))('*)$/.exec(s);
    if (m) {
      var link = m[3].charAt(0) === "(" ? m[3].slice(1, -1) :
        m[3].replace(/[\u2080-\u2089]/g, function (c) { return String(SUBDIGITS.indexOf(c)); });
      return [m[1], (m[2] ? m[2] + "," : "") + link, m[4].length];
    }
    m = /^([A-Za-z]+)_\{?([0-9A-Za-z\-]+)\}?('*)$/.exec(s) || /^([A-Za-z]+?)([0-9]*)('*)$/.exec(s);
    return m ? [m[1], m[2], m[3].length] : null;
  }
  function svgLabel(s) {
    var m = splitLabel(s);
    if (!m) return esc(s);
    return esc(m[0]) + (m[1] ? '<tspan baseline-shift="sub" font-size="72%">' + esc(m[1]) + "</tspan>" : "") +
      (m[2] ? '<tspan font-style="normal">' + "\u2032".repeat(m[2]) + "</tspan>" : "");
  }
  // a step's equation (velpoly.polygons Step.equation) as HTML: V_CB -> V<sub>CB</sub>, omega -> ω ...
  function eqHtml(eq) {
    var s = esc(eq);
    s = s.replace(/(^|[^A-Za-z\\])(omega|alpha|theta|[VARP])(\^[nstc])?_\{?((?:[A-Za-z0-9@]|[\u2080-\u2089]|\([^()\s]*\))+(?:\/(?:[A-Za-z0-9]|[\u2080-\u2089]|\([^()\s]*\))+)?|[0-9]+-[0-9]+)\}?(\^[0-9])?/g,
      function (all, pre, name, sup, index, power) {
        var out = pre + "<i>" + (GREEK[name] || name) + "</i>";
        if (sup) out += "<sup>" + sup.slice(1) + "</sup>";
        out += "<sub>" + subIndex(index) + "</sub>";
        if (power) out += "<sup>" + power.slice(1) + "</sup>";
        return out;
      });
    s = s.replace(/\bomega\b/g, "\u03c9").replace(/\balpha\b/g, "\u03b1");
    s = s.replace(/\bO_([av])\b/g, "<i>O</i><sub>$1</sub>");
    // a caption's point names: O₂ -> O<sub>2</sub>, as the figures' captions set them
    s = s.replace(/[\u2080-\u2089]+/g, function (d) {
      return "<sub>" + d.replace(/[\u2080-\u2089]/g, function (c) { return String(c.charCodeAt(0) - 0x2080); }) + "</sub>";
    });
    s = s.replace(/([0-9]) deg\b/g, "$1\u00b0").replace(/ x /g, " \u00d7 ").replace(/ - /g, " \u2212 ");
    return s;
  }
  // a subscript's names with their links lowered again: P\u2082/P(cam) -> P<sub>2</sub>/P<sub>cam</sub>
  function subIndex(index) {
    return index.replace(/([\u2080-\u2089]+)|\(([^()\s]*)\)/g, function (all, digits, word) {
      return "<sub>" + (digits ? digits.replace(/[\u2080-\u2089]/g, function (c) { return String(SUBDIGITS.indexOf(c)); }) : word) + "</sub>";
    });
  }
  // A number as the sheets' tables print it (velpoly.render.table.number): d significant digits (5), plain
  // digits from 1e-5 to 1e8 (after rounding), else a power of ten in superscript digits, 1.0477×10⁸⁹, never
  // a computer exponent (1.0477e+89); a minus sign, not a hyphen.
  function fmt(x, d, z) {   // z: below it the value is rounding noise and prints 0 (noise())
    if (x === null || x === undefined || !isFinite(x)) return "\u2013";
    if (x === 0 || Math.abs(x) < z) return "0";
    var sci = x.toExponential((d || 5) - 1), e = Number(sci.split("e")[1]);
    var s = e < -5 || e >= 8 ? tens(sci) : String(Number(x.toPrecision(d || 5)));   // plain digits, no trailing zeros
    return s.replace(/-/g, "\u2212");
  }
  var SUPDIGITS = "\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079";
  function tens(sci) {   // "1.0500e-9" -> 1.05×10⁻⁹
    var parts = sci.split("e"), e = Number(parts[1]);
    return parts[0].replace(/\.?0+$/, "") + "\u00d710" + (e < 0 ? "\u207b" : "") +
      String(Math.abs(e)).replace(/[0-9]/g, function (c) { return SUPDIGITS[Number(c)]; });
  }
  function polar(v, z) {
    if (!v) return "\u2013";
    var mag = Math.hypot(v[0], v[1]);
    if (mag === 0 || mag < z) return "0";
    // a direction in [0, 360), rounded and then folded, as velpoly.names.direction prints it
    var ang = Number((Math.atan2(v[1], v[0]) * 180 / Math.PI).toFixed(2));
    ang = ((ang % 360) + 360) % 360;
    if (Number(ang.toFixed(2)) >= 360) ang = 0;
    return fmt(mag) + " \u2220 " + (ang + 0).toFixed(2) + "\u00b0";
  }
  function wrap(a) { var w = ((a + 180) % 360 + 360) % 360 - 180; return w === -180 ? 180 : w; }
  function angleText(i) {
    var a = S.angles[i];
    if (S.driver.slider) return "s = " + fmt(a, 6) + (S.units ? " " + S.units : "");
    return "\u03b8" + sub(S.driver.link) + " = " + fmt(wrap(a), 6) + "\u00b0";
  }
  function sub(s) { return "<sub>" + esc(s) + "</sub>"; }
  // a file without units has "units/s", never "1/s" (read as an angular velocity): velpoly.names.unit
  function unitsOf(power) { return (S.units || "units") + ["", "/s", "/s\u00b2"][power]; }
  // a point key as velpoly.names writes it: P@2 -> P\u2082, P@cam -> P(cam)
  function keyText(key) {
    var i = key.indexOf("@");
    if (i < 0) return key;
    var lk = key.slice(i + 1);
    return key.slice(0, i) + (/^[0-9]+$/.test(lk) ? lk.replace(/[0-9]/g, function (c) { return SUBDIGITS.charAt(+c); }) : "(" + lk + ")");
  }
  function subKey(key) { return "<sub>" + subIndex(esc(keyText(key))) + "</sub>"; }
  function withUnit(x, power) { var u = unitsOf(power); return fmt(x, 3) + (u ? " " + u : ""); }

  // -- geometry -----------------------------------------------------------------------------------
  function X(v, x) { return v.k * (x - v.x0); }
  function Y(v, y) { return v.k * (v.y1 - y); }
  function n2(x) { return Math.round(x * 100) / 100; }
  function line(x1, y1, x2, y2, cls, extra) {
    return '<line x1="' + n2(x1) + '" y1="' + n2(y1) + '" x2="' + n2(x2) + '" y2="' + n2(y2) + '" class="' + cls + '"' + (extra || "") + "/>";
  }
  function text(x, y, html, cls, extra) {
    return '<text x="' + n2(x) + '" y="' + n2(y) + '" class="' + cls + '"' + (extra || "") + ">" + html + "</text>";
  }
  // an arrow from (x1, y1) to (x2, y2) in SVG units: the shaft stops where the head begins
  function arrow(x1, y1, x2, y2, kind, now, tip) {
    var dx = x2 - x1, dy = y2 - y1, L = Math.hypot(dx, dy);
    if (L < 0.5) return "";
    var ux = dx / L, uy = dy / L, h = Math.min(13, 0.45 * L), w = h * 0.36;
    var bx = x2 - ux * h, by = y2 - uy * h;
    var cls = kind + (now ? " now" : "");
    return '<g' + (tip ? ' data-tip="' + esc(tip) + '"' : "") + ">" +
      line(x1, y1, bx + ux * 1.5, by + uy * 1.5, "vec " + cls) +
      '<path class="head ' + cls + '" d="M' + n2(x2) + "," + n2(y2) + "L" + n2(bx - uy * w) + "," + n2(by + ux * w) +
      "L" + n2(bx + uy * w) + "," + n2(by - ux * w) + 'Z"/></g>';
  }
  function hull(pts) {   // convex hull, monotone chain
    pts = pts.slice().sort(function (a, b) { return a[0] - b[0] || a[1] - b[1]; });
    if (pts.length < 3) return pts;
    function cross(o, a, b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }
    var lo = [], up = [], i;
    for (i = 0; i < pts.length; i++) {
      while (lo.length >= 2 && cross(lo[lo.length - 2], lo[lo.length - 1], pts[i]) <= 0) lo.pop();
      lo.push(pts[i]);
    }
    for (i = pts.length - 1; i >= 0; i--) {
      while (up.length >= 2 && cross(up[up.length - 2], up[up.length - 1], pts[i]) <= 0) up.pop();
      up.push(pts[i]);
    }
    lo.pop(); up.pop();
    return lo.concat(up);
  }
  function dataAttrs(key, x, y, sx, sy, extra) {
    return ' data-key="' + esc(key) + '" data-x="' + x + '" data-y="' + y + '" data-sx="' + sx + '" data-sy="' + sy + '"' + (extra || "");
  }
  // a label beside an anchor, away from a direction (ux, uy) in SVG units
  function labelAt(x, y, ux, uy, html, cls, gap) {
    var L = Math.hypot(ux, uy);
    if (L < 1e-9) { ux = 0.7; uy = -0.7; L = 1; }
    ux /= L; uy /= L;
    gap = gap || 13;
    var tx = x + ux * gap, ty = y + uy * gap + 6;
    var anchor = ux > 0.35 ? "start" : ux < -0.35 ? "end" : "middle";
    if (uy > 0.5) ty += 6;
    // kept inside the panel (its width guessed from its letters)
    var w = 10 * html.replace(/<[^>]*>/g, "").replace(/&[a-z]+;/g, "x").length, W = S.views.panel[0], H = S.views.panel[1];
    var left = anchor === "start" ? tx : anchor === "end" ? tx - w : tx - w / 2;
    if (left < 3) tx += 3 - left; else if (left + w > W - 3) tx -= left + w - W + 3;
    ty = Math.max(16, Math.min(H - 4, ty));
    return text(tx, ty, html, cls, ' text-anchor="' + anchor + '"');
  }

  // -- steps --------------------------------------------------------------------------------------
  // the construction in order: the velocity polygon's steps, the acceleration polygon's, then the
  // poles in their order of discovery (as `velpoly draw --steps`); step 0 is the whole sheet
  function stepList(P) {
    var out = [], j;
    if (P.vp) for (j = 0; j < P.vp.st.length; j++) out.push({ level: "velocity", n: j + 1, s: P.vp.st[j] });
    if (P.ap) for (j = 0; j < P.ap.st.length; j++) out.push({ level: "acceleration", n: j + 1, s: P.ap.st[j] });
    if (P.poles) {
      var found = [];
      for (var k in P.poles) if (P.poles[k].o > 0) found.push([P.poles[k].o, k]);
      found.sort(function (a, b) { return a[0] - b[0]; });
      for (j = 0; j < found.length; j++) out.push({ level: "poles", n: found[j][0], key: found[j][1], s: P.poles[found[j][1]] });
    }
    return out;
  }
  // how far each construction is drawn at the current step: null = whole
  function upto(steps, step) {
    if (!step) return { velocity: null, acceleration: null, poles: null, cur: null };
    var cur = steps[step - 1];
    var u = { velocity: null, acceleration: null, poles: null, cur: cur };
    if (cur.level === "velocity") { u.velocity = cur.n; u.acceleration = 0; u.poles = 0; }
    else if (cur.level === "acceleration") { u.acceleration = cur.n; u.poles = 0; }
    else u.poles = cur.n;
    return u;
  }

  // -- space diagram --------------------------------------------------------------------------------
  var neighbours = {};   // point name -> the other points of its links
  (function () {
    for (var lk in S.points) {
      var pts = S.points[lk];
      for (var a = 0; a < pts.length; a++) {
        neighbours[pts[a]] = neighbours[pts[a]] || {};
        for (var b = 0; b < pts.length; b++) if (a !== b) neighbours[pts[a]][pts[b]] = 1;
      }
    }
  })();
  function position(P, name) {
    if (P.P[name]) return P.P[name];
    for (var k in P.P) if (k.split("@")[0] === name) return P.P[k];
    return null;
  }
  function linkMatrix(v, q) {
    var c = Math.cos(q[2]), s = Math.sin(q[2]);
    return "matrix(" + [c, -s, s, c].map(function (x) { return x.toFixed(7); }).join(" ") + " " +
      n2(v.k * (q[0] - v.x0)) + " " + n2(v.k * (v.y1 - q[1])) + ")";
  }
  function mechanism(P, v, st, light, withPoints) {
    var out = [], j, lk;
    out.push('<g class="' + (light ? "light" : "") + '">');
    out.push('<g transform="translate(' + n2(-v.k * v.x0) + " " + n2(v.k * v.y1) + ')">');
    for (j = 0; j < st.ground.length; j++) out.push('<path class="' + st.ground[j][1] + '" d="' + st.ground[j][0] + '"/>');
    out.push("</g>");
    for (j = 0; j < S.moving.length; j++) {
      lk = S.moving[j];
      var b = st.bodies[lk];
      if (!b) continue;
      out.push('<g transform="' + linkMatrix(v, P.q[j]) + '" data-link="' + esc(lk) + '"><path class="body" d="' + b.d + '"/>' +
        (b.holes ? '<path class="hole" d="' + b.holes + '"/>' : "") + "</g>");
    }
    if (!light) {
      // link numbers, circled, where each link carries its anchor
      for (j = 0; j < S.moving.length; j++) {
        lk = S.moving[j];
        var a = st.numbers[lk], q = P.q[j];
        if (!a) continue;
        var c = Math.cos(q[2]), s = Math.sin(q[2]);
        var ax = q[0] + c * a[0] - s * a[1], ay = q[1] + s * a[0] + c * a[1];
        out.push('<g><circle cx="' + n2(X(v, ax)) + '" cy="' + n2(Y(v, ay)) + '" r="10" class="pin"/>' +
          text(X(v, ax), Y(v, ay), esc(lk), "num") + "</g>");
      }
      out.push(driverArrow(P, v));
    }
    if (withPoints) out.push(points(P, v, st, light));
    out.push("</g>");
    return out.join("");
  }
  function driverArrow(P, v) {
    var d = S.driver;
    if (d.slider) {   // an arrow beside the block, along its velocity
      var key = P.V[d.slider] ? d.slider : Object.keys(P.V).filter(function (k) { return k.split("@")[0] === d.slider; })[0];
      var pc = P.P[key], vc = P.V[key];
      if (!pc || !vc || !Math.hypot(vc[0], vc[1])) return "";
      var L = Math.hypot(vc[0], vc[1]), ux = vc[0] / L, uy = -vc[1] / L, bx = X(v, pc[0]) + uy * 52, by = Y(v, pc[1]) - ux * 52;
      return '<g data-tip="' + esc("driver: " + S.driver.text) + '">' + arrow(bx - ux * 22, by - uy * 22, bx + ux * 22, by + uy * 22, "absolute") +
        labelAt(bx, by, uy, -ux, "V" + '<tspan baseline-shift="sub" font-size="72%">' + esc(d.slider) + "</tspan>", "lab", 18) + "</g>";
    }
    if (!S.pivot) return "";
    var p = position(P, S.pivot);
    if (!p) return "";
    var th = P.th[d.link] * Math.PI / 180, sense = d.omega >= 0 ? 1 : -1, r = 30;
    var a0 = th + sense * 0.45, a1 = th + sense * 1.75, n = 24, pts = [];
    var cx = X(v, p[0]), cy = Y(v, p[1]);
    for (var j = 0; j <= n; j++) { var t = a0 + (a1 - a0) * j / n; pts.push([cx + r * Math.cos(t), cy - r * Math.sin(t)]); }
    var path = "M" + pts.slice(0, n - 2).map(function (q) { return n2(q[0]) + "," + n2(q[1]); }).join("L");
    var tip = "driver: " + S.driver.text;
    var e = pts[n - 3], f = pts[n];
    var mid = pts[n / 2];
    return '<g data-tip="' + esc(tip) + '"><path class="vec relative" d="' + path + '"/>' + arrow(e[0], e[1], f[0], f[1], "relative") +
      labelAt(mid[0], mid[1], mid[0] - cx, mid[1] - cy, "\u03c9" + '<tspan baseline-shift="sub" font-size="72%">' + esc(d.link) + "</tspan>", "lab", 8) + "</g>";
  }
  function points(P, v, st, light) {
    var out = [], seen = {};
    for (var key in P.P) {
      var p = P.P[key];
      if (!p) continue;
      var name = key.split("@")[0], sx = X(v, p[0]), sy = Y(v, p[1]);
      var kind = st.kinds[key] || "dot";
      var tip = keyText(key) + ": (" + fmt(p[0]) + ", " + fmt(p[1]) + ") " + S.units;
      if (P.V[key]) tip += "\nV = " + polar(P.V[key]) + " " + unitsOf(1);
      if (P.A && P.A[key]) tip += "\nA = " + polar(P.A[key]) + " " + unitsOf(2);
      var attrs = dataAttrs(key, p[0], p[1], sx, sy, ' data-tip="' + esc(tip) + '"');
      if (kind === "pin") out.push('<circle cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="4.6" class="pin"/>');
      else if (kind === "centre") out.push(line(sx - 5, sy, sx + 5, sy, "cross") + line(sx, sy - 5, sx, sy + 5, "cross"));
      else out.push('<circle cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="2.6" class="dot"/>');
      out.push('<circle class="hit pt" cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="11"' + attrs + "/>");
      if (light || seen[name]) continue;
      // one label a point, unless its keys have drifted apart (a contact's two points)
      var label = name, others = [];
      for (var k2 in P.P) if (k2 !== key && k2.split("@")[0] === name && P.P[k2] &&
        Math.hypot(P.P[k2][0] - p[0], P.P[k2][1] - p[1]) > 1e-9 * S.size) label = keyText(key);
      if (label === name) seen[name] = 1;
      var ux = 0, uy = 0;
      for (var nb in neighbours[name] || {}) {
        var q = position(P, nb);
        if (!q) continue;
        var dx = X(v, q[0]) - sx, dy = Y(v, q[1]) - sy, L = Math.hypot(dx, dy);
        if (L > 1e-9) { ux -= dx / L; uy -= dy / L; }
      }
      out.push(labelAt(sx, sy, ux, uy, svgLabel(label), "lab", 12));
    }
    return out.join("");
  }
  function scaleBar(v, power) {
    // a round length near a sixth of the panel
    var target = v.w / 6 / v.k, e = Math.pow(10, Math.floor(Math.log10(target))), m = target / e;
    var len = (m >= 5 ? 5 : m >= 2 ? 2 : 1) * e, px = len * v.k, x = 14, y = v.h - 12;
    return '<g data-tip="scale: ' + fmt(len) + " " + unitsOf(power) + '">' + line(x, y, x + px, y, "scalebar") + line(x, y - 4, x, y + 2, "scalebar") +
      line(x + px, y - 4, x + px, y + 2, "scalebar") + text(x + px + 6, y + 4, fmt(len) + " " + esc(unitsOf(power)), "small", ' style="fill:#111;font-style:normal"') + "</g>";
  }

  // -- polygons -------------------------------------------------------------------------------------
  // a polygon's view at one pose: a round scale (1, 1.2, 1.5 ... 8 x 10^n units a centimetre) that fits
  // every image, vector and line base of the whole construction (stepping does not rescale it)
  var CM = 37.8;   // SVG units a centimetre of the panel at its nominal size
  function niceUp(x) {
    var e = Math.pow(10, Math.floor(Math.log10(x))), m = x / e;
    var nice = [1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10];
    for (var j = 0; j < nice.length; j++) if (m <= nice[j] * (1 + 1e-12)) return nice[j] * e;
    return 10 * e;
  }
  function polyView(poly) {
    var W = S.views.panel[0], H = S.views.panel[1], M = S.views.margin;
    var xs = [0], ys = [0], j, k;
    function add(p) { if (p && isFinite(p[0]) && isFinite(p[1])) { xs.push(p[0]); ys.push(p[1]); } }
    if (poly) {
      for (k in poly.img) add(poly.img[k]);
      for (k in poly.aux) add(poly.aux[k].i);
      for (j = 0; j < poly.st.length; j++) {
        var s = poly.st[j];
        for (k = 0; k < s.v.length; k++) { add([s.v[k][0], s.v[k][1]]); add([s.v[k][2], s.v[k][3]]); }
        for (k = 0; k < s.ln.length; k++) add([s.ln[k][0], s.ln[k][1]]);
      }
    }
    var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs), y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
    var span = Math.max(x1 - x0, y1 - y0, 1e-300);
    var fit = Math.min((W - 2 * M) / Math.max(x1 - x0, span * 1e-3), (H - 2 * M) / Math.max(y1 - y0, span * 1e-3));
    var kk = CM / niceUp(CM / fit);
    if (!isFinite(kk) || kk <= 0) kk = 1;
    return { k: kk, x0: (x0 + x1) / 2 - W / 2 / kk, y1: (y0 + y1) / 2 + H / 2 / kk, w: W, h: H };
  }
  // -- vectors on one line drawn apart, as the sheets draw them (velpoly/render/polygon.py: Beside, lying_along):
  // a vector lying along one drawn before it (parallel within ONE_LINE degrees, within half the offset of its line
  // over more than ALONG px) is drawn APART arrowheads (HEAD px) to one side, or twice that, ...; two of one kind
  // from one tail in one sense whose heads are HEADS_APART arrowheads apart stay on their ray
  var APART = 0.7, ONE_LINE = 1.5, ALONG = 3.0, HEADS_APART = 2.0, HEAD = 13;
  function lyingAlong(p, q, t, h, near, along) {   // whether segment p-q lies along segment t-h
    var size = Math.hypot(h[0] - t[0], h[1] - t[1]), el = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (!(size > 0) || !(el > 0)) return false;
    var ux = (h[0] - t[0]) / size, uy = (h[1] - t[1]) / size;
    if (Math.abs(ux * (q[1] - p[1]) - uy * (q[0] - p[0])) / el > Math.sin(ONE_LINE * Math.PI / 180)) return false;
    var rpx = p[0] - t[0], rpy = p[1] - t[1], rqx = q[0] - t[0], rqy = q[1] - t[1];
    var dp = ux * rpy - uy * rpx, dq = ux * rqy - uy * rqx, tp = ux * rpx + uy * rpy, tq = ux * rqx + uy * rqy;
    var slope = dq - dp, lo = 0, hi = 1;
    if (Math.abs(slope) <= 1e-12 * near) { if (Math.abs(dp) > near) return false; }
    else {
      var l1 = (-near - dp) / slope, l2 = (near - dp) / slope;
      lo = Math.min(Math.max(Math.min(l1, l2), 0), 1); hi = Math.min(Math.max(Math.max(l1, l2), 0), 1);
    }
    if (!(hi > lo)) return false;
    var a = tp + lo * (tq - tp), b = tp + hi * (tq - tp);
    return Math.min(Math.max(a, b), size) - Math.max(Math.min(a, b), 0) > along;
  }
  function crosses(p, q, t, h) {   // whether segments p-q and t-h meet
    function side(o, a, b) { var c = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); return c > 0 ? 1 : c < 0 ? -1 : 0; }
    return side(p, q, t) * side(p, q, h) <= 0 && side(t, h, p) * side(t, h, q) <= 0;
  }
  function Beside() { this.drawn = []; this.apart = APART * HEAD; }
  Beside.prototype.along = function (p, q, kind) {   // how many drawn vectors p-q lies along (kind: its own rays spared)
    var n = 0, self = this;
    this.drawn.forEach(function (d) {
      if (!lyingAlong(p, q, d.t, d.h, 0.5 * self.apart, ALONG)) return;
      if (kind !== undefined && d.kind === kind && Math.hypot(d.t[0] - p[0], d.t[1] - p[1]) <= 0.5 * self.apart &&
          (d.h[0] - d.t[0]) * (q[0] - p[0]) + (d.h[1] - d.t[1]) * (q[1] - p[1]) > 0 &&
          Math.hypot(d.h[0] - q[0], d.h[1] - q[1]) >= HEADS_APART * HEAD) return;
      n++;
    });
    return n;
  };
  Beside.prototype.add = function (t, h, centre, kind) {   // the shift [dx, dy] px the vector t-h is drawn with
    var s = [0, 0];
    if (this.along(t, h, kind)) {
      var L = Math.hypot(h[0] - t[0], h[1] - t[1]), nx = -(h[1] - t[1]) / L, ny = (h[0] - t[0]) / L;
      var side = nx * ((t[0] + h[0]) / 2 - centre[0]) + ny * ((t[1] + h[1]) / 2 - centre[1]) >= 0 ? 1 : -1;
      var best = null, self = this;
      for (var k = 0; k < 5 && !(best && best.hits === 0); k++) {
        (k === 0 ? [0] : [side * k, -side * k]).forEach(function (m) {
          var o = [m * self.apart * nx, m * self.apart * ny], p = [t[0] + o[0], t[1] + o[1]], q = [h[0] + o[0], h[1] + o[1]];
          var hits = self.along(p, q), cross = 0;
          self.drawn.forEach(function (d) { if (crosses(p, q, d.t, d.h)) cross++; });
          if (!best || hits < best.hits || (hits === best.hits && cross < best.cross)) best = { hits: hits, cross: cross, s: o };
        });
      }
      s = best.s;
    }
    this.drawn.push({ t: [t[0] + s[0], t[1] + s[1]], h: [h[0] + s[0], h[1] + s[1]], kind: kind });
    return s;
  };
  function besideAll(poly, v) {   // {ids: per step, per vector its id (null: not drawn), shift: per id [dx, dy] px}
    var drawn = new Beside(), order = [], kinds = {}, shift = {}, cx = 0, cy = 0, m = 1, key;
    for (key in poly.img) if (poly.img[key]) { cx += poly.img[key][0]; cy += poly.img[key][1]; m++; }
    var centre = [X(v, cx / m), Y(v, cy / m)], ends = {};
    var ids = poly.st.map(function (s) {
      return s.v.map(function (vv) {
        if (!vv[0] && vv[0] !== 0) return null;
        var t = [X(v, vv[0]), Y(v, vv[1])], h = [X(v, vv[2]), Y(v, vv[3])];
        if (Math.hypot(h[0] - t[0], h[1] - t[1]) < 0.5) return null;
        var id = [t, h].map(function (p) { return n2(p[0]) + "," + n2(p[1]); }).join(" ");
        if (!(id in kinds)) { order.push(id); ends[id] = [t, h]; kinds[id] = vv[4]; }
        else if (vv[4] === "absolute") kinds[id] = "absolute";
        return id;
      });
    });
    order.forEach(function (id) { shift[id] = drawn.add(ends[id][0], ends[id][1], centre, kinds[id]); });
    return { ids: ids, shift: shift };
  }

  function polygon(P, level, v, n, cur) {
    var poly = level === "velocity" ? P.vp : P.ap, out = [];
    if (!poly) {
      var why = level === "acceleration" && !P.A ? "no accelerations: a contact is given by its normal only"
        : (P.msg && P.msg.length ? P.msg.join("; ") : "no construction at this pose");
      return text(v.w / 2, v.h / 2, esc(why), "msg");
    }
    var power = level === "velocity" ? 1 : 2;
    var steps = poly.st, last = n === null ? steps.length : Math.min(n, steps.length);
    var known = {}, j, k, s;
    for (j = 0; j < last; j++) for (k = 0; k < steps[j].f.length; k++) known[steps[j].f[k]] = j + 1;
    var now = cur && cur.level === level ? cur.n : 0;
    // link images, shaded
    for (var lk in poly.li) {
      var keys = poly.li[lk], pts = [];
      for (k = 0; k < keys.length; k++) if (known[keys[k]] && poly.img[keys[k]]) pts.push([X(v, poly.img[keys[k]][0]), Y(v, poly.img[keys[k]][1])]);
      var h = hull(pts);
      if (h.length >= 3) out.push('<path class="image-shade" d="M' + h.map(function (p) { return n2(p[0]) + "," + n2(p[1]); }).join("L") + 'Z"/>');
    }
    // construction lines of the steps drawn: through their base, past the image they find
    for (j = 0; j < last; j++) {
      s = steps[j];
      for (k = 0; k < s.ln.length; k++) {
        var ln = s.ln[k], bx = X(v, ln[0]), by = Y(v, ln[1]), dx = ln[2], dy = -ln[3];
        var target = null;
        for (var f = 0; f < s.f.length; f++) if (poly.img[s.f[f]]) target = poly.img[s.f[f]];
        if (!target && s.aux.length && poly.aux[s.aux[0]]) target = poly.aux[s.aux[0]].i;
        var t1 = target ? (X(v, target[0]) - bx) * dx + (Y(v, target[1]) - by) * dy : 0;
        var lo = Math.min(0, t1) - 28, hi = Math.max(0, t1) + 28;
        var isNow = j + 1 === now;
        out.push('<g data-tip="' + esc("line through " + ln[4] + ", " + ln[5]) + '">' +
          line(bx + dx * lo, by + dy * lo, bx + dx * hi, by + dy * hi, "cl" + (isNow ? " now" : "")) + "</g>");
        if (isNow) {   // its reason along the current step's line (the others: hover)
          var mx = bx + dx * (lo + hi) / 2, my = by + dy * (lo + hi) / 2;
          var rot = Math.atan2(dy, dx) * 180 / Math.PI;
          if (rot > 90) rot -= 180; else if (rot < -90) rot += 180;
          var off = 9;
          out.push(text(mx - dy * off, my + dx * off, esc(ln[5]), "small", ' text-anchor="middle" transform="rotate(' + n2(rot) + " " + n2(mx - dy * off) + " " + n2(my + dx * off) + ')"'));
        }
      }
    }
    // vectors, each beside those on its line (planned over every step: a step draws it where the last has it); one
    // arrow a vector (an absolute one that is also relative stays absolute), marked now if a current step has it
    var plan = besideAll(poly, v), pick = {}, nowIds = {}, id;
    for (j = 0; j < last; j++) for (k = 0; k < steps[j].v.length; k++) {
      id = plan.ids[j][k];
      if (id === null) continue;
      if (j + 1 === now) nowIds[id] = true;
      if (!pick[id] || (steps[j].v[k][4] === "absolute" && pick[id].kind !== "absolute"))
        pick[id] = { j: j, k: k, kind: steps[j].v[k][4] };
    }
    for (j = 0; j < last; j++) {
      s = steps[j];
      for (k = 0; k < s.v.length; k++) {
        var vv = s.v[k], sh = plan.shift[plan.ids[j][k]];
        if (plan.ids[j][k] === null || pick[plan.ids[j][k]].j !== j || pick[plan.ids[j][k]].k !== k) continue;
        out.push(arrow(X(v, vv[0]) + sh[0], Y(v, vv[1]) + sh[1], X(v, vv[2]) + sh[0], Y(v, vv[3]) + sh[1], vv[4],
          !!nowIds[plan.ids[j][k]], vv[5] + " = " + polar([vv[2] - vv[0], vv[3] - vv[1]]) + " " + unitsOf(power)));
      }
    }
    // images: one label for coincident ones (O_v, a, d)
    var groups = [], tol = 1e-9 * (v.w / v.k);
    var origin = [0, 0];
    groups.push({ p: origin, labels: [poly.o], keys: [] });
    for (var key in poly.img) {
      if (!known[key] || !poly.img[key]) continue;
      var p = poly.img[key], g = null;
      for (k = 0; k < groups.length; k++) if (Math.hypot(groups[k].p[0] - p[0], groups[k].p[1] - p[1]) <= tol) { g = groups[k]; break; }
      if (!g) { g = { p: p, labels: [], keys: [] }; groups.push(g); }
      g.labels.push(poly.lab[key] || key.toLowerCase());
      g.keys.push(key);
    }
    for (var a in poly.aux) {
      var ax = poly.aux[a];
      var step = 0;
      for (j = 0; j < last; j++) if (steps[j].aux.indexOf(a) >= 0) step = j + 1;
      if (!step || !ax.i) continue;
      var ga = null;
      for (k = 0; k < groups.length; k++) if (Math.hypot(groups[k].p[0] - ax.i[0], groups[k].p[1] - ax.i[1]) <= tol) { ga = groups[k]; break; }
      if (!ga) { ga = { p: ax.i, labels: [], keys: [] }; groups.push(ga); }
      if (ax.lab && ga.labels.indexOf(ax.lab) < 0) ga.labels.push(ax.lab);
    }
    var sym = level === "velocity" ? "V" : "A";
    for (k = 0; k < groups.length; k++) {
      var G = groups[k], sx = X(v, G.p[0]), sy = Y(v, G.p[1]);
      var fresh = false;
      for (j = 0; j < G.keys.length; j++) if (known[G.keys[j]] === now) fresh = true;
      out.push('<circle cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="' + (fresh ? 4.5 : 2.8) + '" class="' + (fresh ? "found" : "imgdot") + '"/>');
      for (j = 0; j < G.keys.length; j++) {
        var ik = G.keys[j], ip = poly.img[ik];
        var tip = (poly.lab[ik] || ik) + ": " + sym + "_" + ik + " = " + polar(ip) + " " + unitsOf(power) + "\n(" + fmt(ip[0]) + ", " + fmt(ip[1]) + ")";
        out.push('<circle class="hit img" cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="10"' +
          dataAttrs(ik, ip[0], ip[1], sx, sy, ' data-level="' + level + '" data-step="' + known[ik] + '" data-tip="' + esc(tip) + '"') + "/>");
      }
      var ux = G.p[0] * v.k, uy = -G.p[1] * v.k;
      if (Math.hypot(ux, uy) < 1) { ux = -1; uy = 0.6; }
      out.push(labelAt(sx, sy, ux, uy, G.labels.map(svgLabel).join(", "), "lab", 11));
    }
    out.push(scaleBar(v, power));
    return out.join("");
  }

  // -- poles ----------------------------------------------------------------------------------------
  function poleName(key) {
    var ij = key.split("-");
    return ij[0].length === 1 && ij[1].length === 1 ? "P_" + ij[0] + ij[1] : "P_{" + key + "}";
  }
  function clipToView(v, x, y, ux, uy, inset) {   // where the ray from (x, y) along (ux, uy) leaves the panel
    var t = Infinity;
    if (ux > 1e-12) t = Math.min(t, (v.w - inset - x) / ux); else if (ux < -1e-12) t = Math.min(t, (inset - x) / ux);
    if (uy > 1e-12) t = Math.min(t, (v.h - inset - y) / uy); else if (uy < -1e-12) t = Math.min(t, (inset - y) / uy);
    return [x + ux * t, y + uy * t];
  }
  function poles(P, v, n, cur) {
    var out = [mechanism(P, S.views.poles, S.polesSpace, true, false)];
    if (!P.poles) return out.join("") + text(v.w / 2, v.h / 2, esc((P.msg || []).join("; ") || "no poles at this pose"), "msg");
    var shown = {}, key, p, j;
    for (key in P.poles) if (n === null || P.poles[key].o <= n) shown[key] = 1;
    var now = cur && cur.level === "poles" ? cur.key : null;
    var cx = v.w / 2, cy = v.h / 2;
    function place(k) {   // a pole's SVG place, or null (at infinity, or undefined)
      var q = P.poles[k];
      return q && q.p ? [X(v, q.p[0]), Y(v, q.p[1])] : null;
    }
    // Kennedy lines of the poles found so far: each through the two poles of its triple, to the pole
    for (key in shown) {
      p = P.poles[key];
      if (p.o <= 0) continue;
      var at = place(key);
      for (j = 0; j < p.ln.length; j++) {
        var L = p.ln[j], bx = X(v, L[0]), by = Y(v, L[1]), dx = L[2], dy = -L[3];
        var ts = [0];
        if (at) ts.push((at[0] - bx) * dx + (at[1] - by) * dy);
        var through = String(L[4]).match(/P_([^ ]+) P_([^ ]+)/);
        if (through) for (var t2 = 1; t2 <= 2; t2++) { var o = place(through[t2]); if (o) ts.push((o[0] - bx) * dx + (o[1] - by) * dy); }
        var lo = Math.min.apply(null, ts) - 25, hi = Math.max.apply(null, ts) + 25;
        lo = Math.max(lo, -3 * v.w); hi = Math.min(hi, 3 * v.w);
        out.push('<g data-tip="' + esc(L[4].replace(/P_([0-9A-Za-z]+)-([0-9A-Za-z]+)/g, "P$1$2")) + '">' +
          line(bx + dx * lo, by + dy * lo, bx + dx * hi, by + dy * hi, "kl" + (key === now ? " now" : "")) + "</g>");
      }
    }
    for (key in shown) {
      p = P.poles[key];
      var name = poleName(key), how = p.o > 0 ? "found " + p.o + ": " + p.s : "by inspection (" + p.how + ")";
      if (p.p) {
        var sx = X(v, p.p[0]), sy = Y(v, p.p[1]);
        var tip = name.replace("_", "") + " = (" + fmt(p.p[0]) + ", " + fmt(p.p[1]) + ") " + S.units + "\n" + how;
        var inside = sx >= 0 && sx <= v.w && sy >= 0 && sy <= v.h;
        var attrs = dataAttrs(key, p.p[0], p.p[1], sx, sy, ' data-order="' + p.o + '" data-tip="' + esc(tip) + '"');
        if (inside) {
          out.push('<circle cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="' + (p.o > 0 ? 5 : 3.6) + '" class="' + (p.o > 0 ? "pole-found" : "pole-known") + (key === now ? " now" : "") + '"/>');
          out.push('<circle class="hit pole" cx="' + n2(sx) + '" cy="' + n2(sy) + '" r="10"' + attrs + "/>");
          out.push(labelAt(sx, sy, sx - cx + 0.01, sy - cy, svgLabel(name), "lab", 9));
        } else {   // off the panel: an arrow at the border pointing to it
          var ux = sx - cx, uy = sy - cy, Lu = Math.hypot(ux, uy);
          var e = clipToView(v, cx, cy, ux / Lu, uy / Lu, 10);
          out.push(arrow(e[0] - ux / Lu * 30, e[1] - uy / Lu * 30, e[0], e[1], "relative", key === now));
          out.push('<circle class="hit pole" cx="' + n2(e[0]) + '" cy="' + n2(e[1]) + '" r="12"' + attrs + ' data-outside="1"/>');
          out.push(labelAt(e[0] - ux / Lu * 30, e[1] - uy / Lu * 30, -ux, -uy, svgLabel(name), "lab", 6));
        }
      } else if (p.d !== null && p.d !== undefined) {   // at infinity: an arrow along its direction
        var d = p.d * Math.PI / 180, e2 = clipToView(v, cx, cy, Math.cos(d), -Math.sin(d), 10);
        var tip2 = name.replace("_", "") + " at infinity, direction " + fmt(p.d) + "\u00b0\n" + how;
        out.push('<g class="pole" data-key="' + esc(key) + '" data-direction="' + p.d + '" data-order="' + p.o + '" data-tip="' + esc(tip2) + '">' +
          arrow(e2[0] - Math.cos(d) * 30, e2[1] + Math.sin(d) * 30, e2[0], e2[1], "relative", key === now) +
          labelAt(e2[0] - Math.cos(d) * 30, e2[1] + Math.sin(d) * 30, -Math.cos(d), Math.sin(d), svgLabel(name) + " \u221e", "lab", 6) +
          '<circle class="hit" cx="' + n2(e2[0]) + '" cy="' + n2(e2[1]) + '" r="12"/></g>');
      }
    }
    return out.join("");
  }
  function kennedy(P, n, cur) {
    var links = S.links, m = links.length, R = 150, c = [240, 200], pos = {}, out = [], j;
    out.push('<circle cx="' + c[0] + '" cy="' + c[1] + '" r="' + R + '" class="kc"/>');
    for (j = 0; j < m; j++) {
      var a = (90 - 360 * j / m) * Math.PI / 180;
      pos[links[j]] = [c[0] + R * Math.cos(a), c[1] - R * Math.sin(a)];
    }
    var now = cur && cur.level === "poles" ? cur.key : null;
    if (P.poles) for (var key in P.poles) {
      var p = P.poles[key], ij = key.split("-");
      if (n !== null && p.o > n) continue;
      if (p.how === "undefined") continue;
      var A = pos[ij[0]], B = pos[ij[1]];
      if (!A || !B) continue;
      out.push('<g data-tip="' + esc(poleName(key).replace("_", "") + (p.o > 0 ? ": found " + p.o : ": known by inspection")) + '">' +
        line(A[0], A[1], B[0], B[1], "chord" + (p.o > 0 ? " found" : "") + (key === now ? " now" : "")) + "</g>");
      if (p.o > 0) {
        var mx = A[0] + (B[0] - A[0]) * 0.42, my = A[1] + (B[1] - A[1]) * 0.42;
        out.push('<circle cx="' + n2(mx) + '" cy="' + n2(my) + '" r="9" class="pin"/>' + text(mx, my, String(p.o), "num"));
      }
    }
    for (j = 0; j < m; j++) {
      var q = pos[links[j]];
      out.push('<circle cx="' + n2(q[0]) + '" cy="' + n2(q[1]) + '" r="13" class="knode"/>' + text(q[0], q[1], esc(links[j]), "num", ' style="font-size:15px"'));
    }
    return out.join("");
  }

  // -- tables ---------------------------------------------------------------------------------------
  function dev(g, a, scale) {
    if (g === null || g === undefined || a === null || a === undefined) return "\u2013";
    var d = Array.isArray(g) ? Math.hypot(g[0] - a[0], g[1] - a[1]) : Math.abs(g - a);
    var r = d / (scale || 1);
    return r < 1e-12 ? "&lt; 10<sup>\u221212</sup>" : tens(r.toExponential(1));
  }
  // The size of each kind (omega, alpha, speed, acceleration) at a pose, as compare.kind_scales: the
  // largest |omega|, |alpha| (at least omega^2), speed and acceleration (at least speed^2 / size). A
  // graphical value's deviation is relative to its kind's; below a billionth of it (at most 1e-9) a
  // value is rounding noise and prints 0 (compare.kind_floor), as in velpoly solve's tables.
  function kindScales(P) {
    var wmax = 0, amax = 0, vmax = 0, aamax = 0, lk, key;
    for (lk in P.w) wmax = Math.max(wmax, Math.abs(P.w[lk] || 0));
    if (P.al) for (lk in P.al) amax = Math.max(amax, Math.abs(P.al[lk] || 0));
    for (key in P.V) if (P.V[key]) vmax = Math.max(vmax, Math.hypot(P.V[key][0], P.V[key][1]));
    if (P.A) for (key in P.A) if (P.A[key]) aamax = Math.max(aamax, Math.hypot(P.A[key][0], P.A[key][1]));
    var om = wmax || 1, sp = vmax || S.size * om;
    return [om, Math.max(amax, om * om), sp, Math.max(aamax, sp * sp / S.size)];
  }
  function results(P) {
    var rows = [], lk, key, j, k = kindScales(P);
    var z = k.map(function (x) { return Math.min(1e-9, 1e-9 * x) || 1e-9; });
    function row(q, unit, g, a, scale, vec, zk) {
      rows.push("<tr><td>" + q + (unit ? " (" + esc(unit) + ")" : "") + "</td><td>" + (vec ? polar(g, zk) : fmt(g, 0, zk)) +
        "</td><td>" + (vec ? polar(a, zk) : fmt(a, 0, zk)) + "</td><td>" + dev(g, a, scale) + "</td></tr>");
    }
    for (j = 0; j < S.moving.length; j++) {
      lk = S.moving[j];
      row("<i>\u03c9</i>" + sub(lk), "rad/s", P.vp ? P.vp.r[lk] : null, P.w[lk], k[0], false, z[0]);
    }
    if (P.al) for (j = 0; j < S.moving.length; j++) {
      lk = S.moving[j];
      row("<i>\u03b1</i>" + sub(lk), "rad/s\u00b2", P.ap ? P.ap.r[lk] : null, P.al[lk], k[1], false, z[1]);
    }
    for (key in P.V) if (P.V[key] && Math.hypot(P.V[key][0], P.V[key][1]) > 0)
      row("<i>V</i>" + subKey(key), unitsOf(1), P.vp ? P.vp.img[key] : null, P.V[key], k[2], true, z[2]);
    if (P.A) for (key in P.A) if (P.A[key] && Math.hypot(P.A[key][0], P.A[key][1]) > 0)
      row("<i>A</i>" + subKey(key), unitsOf(2), P.ap ? P.ap.img[key] : null, P.A[key], k[3], true, z[3]);
    return '<table id="results-table"><caption>Results at ' + angleText(state.i) +
      ": graphical construction against the analytic solve</caption><thead><tr><th>quantity</th><th>graphical</th><th>analytic</th><th>deviation</th></tr></thead><tbody>" +
      rows.join("") + "</tbody></table>";
  }
  function reference() {
    var R = S.reference;
    if (!R || !R.rows.length) return "";
    var rows = R.rows.map(function (r) {
      function show(x, z) {   // z: the computed value's floor (printed values as given)
        if (!Array.isArray(x)) return fmt(x, 0, z);
        if (x.length === 2 && /^(V|A|R|\|)/.test(r.key)) return fmt(x[0], 0, z) + " \u2220 " + fmt(x[1]) + "\u00b0";
        return "(" + x.map(function (c) { return fmt(c, 0, z); }).join(", ") + ")";
      }
      var d = r.dev !== null && r.dev !== undefined ? (r.dev * 100 < 0.001 ? "&lt; 0.001 %" : fmt(r.dev * 100, 3) + " %") :
        (r.angle !== null && r.angle !== undefined ? fmt(r.angle, 3) + "\u00b0" : "\u2013");
      return "<tr><td>" + eqHtml(r.key) + "</td><td>" + show(r.printed) + "</td><td>" + show(r.value, r.z) + "</td><td>" + d + '</td><td class="note">' + esc(r.note || "") + "</td></tr>";
    });
    return "<table><caption>Book values at the drawn pose (" + angleText(S.start) + ")" + (R.source ? ": " + esc(R.source) : "") +
      "</caption><thead><tr><th>quantity</th><th>book</th><th>analytic</th><th>deviation</th><th>note</th></tr></thead><tbody>" + rows.join("") + "</tbody></table>";
  }

  // -- the whole page -------------------------------------------------------------------------------
  function setView(id, v) {
    var el = document.getElementById(id);
    el.setAttribute("viewBox", "0 0 " + v.w + " " + v.h);
    return el;
  }
  function scaleText(v, power) {
    return "(1 cm = " + withUnit(CM / v.k, power) + ")";
  }
  function draw() {
    var P = pose(state.i), steps = stepList(P);
    if (state.step > steps.length) state.step = steps.length;
    var u = upto(steps, state.step), V = S.views;
    setView("space", V.space).innerHTML = mechanism(P, V.space, S.space, false, true) + scaleBar(V.space, 0);
    document.getElementById("scale-space").textContent = scaleText(V.space, 0);
    var vv = polyView(P.vp), va = polyView(P.ap);
    setView("velocity", vv).innerHTML = polygon(P, "velocity", vv, u.velocity, u.cur);
    document.getElementById("scale-velocity").textContent = scaleText(vv, 1);
    if (S.accelerations) {
      setView("acceleration", va).innerHTML = polygon(P, "acceleration", va, u.acceleration, u.cur);
      document.getElementById("scale-acceleration").textContent = scaleText(va, 2);
    } else document.getElementById("acc-figure").hidden = true;
    setView("poles", V.poles).innerHTML = poles(P, V.poles, u.poles, u.cur);
    var k = document.getElementById("kennedy");
    k.setAttribute("viewBox", "0 0 480 400");
    k.innerHTML = kennedy(P, u.poles, u.cur);
    document.getElementById("results").innerHTML = results(P);
    // controls and the caption
    document.getElementById("angle").value = state.i;
    document.getElementById("angle-text").innerHTML = angleText(state.i);
    document.getElementById("step-text").textContent = state.step ? "step " + state.step + " of " + steps.length : "all " + steps.length + " steps";
    var cap = document.getElementById("caption");
    if (!state.step) {
      cap.innerHTML = "The whole construction. " + (P.msg && P.msg.length ? "<b>" + esc(P.msg.join("; ")) + "</b> " : "") +
        "Walk through it step by step with \u2193 or +.";
      cap.removeAttribute("data-equation");
      cap.dataset.level = "";
    } else {
      var c = u.cur, s = c.s, where = { velocity: "Velocity polygon", acceleration: "Acceleration polygon", poles: "Instant centres" }[c.level];
      var html = "<b>Step " + state.step + "</b> (" + where + ", step " + c.n + "): ";
      // the step's caption, word for word the caption of its frame in `velpoly draw --steps`
      var words = c.level === "poles" ? s.s : s.cap;
      html += c.level === "poles" ? eqHtml(words) : '<span class="now">' + eqHtml(words) + "</span>";
      cap.innerHTML = html;
      cap.dataset.equation = c.level === "poles" ? s.s : s.eq;
      cap.dataset.caption = words;
      cap.dataset.level = c.level;
    }
    document.getElementById("foot").textContent = "Pose " + (state.i + 1) + " of " + N + (S.limited ? " (the range this linkage reaches on its drawn branch)" : "") +
      ". Drawn by velpoly from " + (S.source || "the mechanism") + ".";
    var b = document.body;
    b.dataset.poseIndex = state.i;
    b.dataset.angle = S.angles[state.i];
    b.dataset.step = state.step;
    b.dataset.steps = steps.length;
    b.dataset.rendered = S.driver.slider ? String(S.angles[state.i]) : String(wrap(S.angles[state.i]));
    writeHash();
  }

  // -- control -----------------------------------------------------------------------------------
  function go(i) { state.i = ((i % N) + N) % N; if (S.limited || S.driver.slider) state.i = Math.max(0, Math.min(N - 1, i)); draw(); }
  function setStep(k) { var n = stepList(pose(state.i)).length; state.step = Math.max(0, Math.min(n, k)); draw(); }
  function play(on) {
    state.playing = on;
    var btn = document.getElementById("play");
    btn.innerHTML = on ? "&#10074;&#10074;" : "&#9654;";
    btn.setAttribute("aria-label", on ? "pause" : "play");
    if (state.timer) { clearInterval(state.timer); state.timer = null; }
    if (on) {
      var dir = 1;
      state.timer = setInterval(function () {
        if (S.limited || S.driver.slider) {   // to and fro over the reachable range
          if (state.i + dir >= N || state.i + dir < 0) dir = -dir;
          go(state.i + dir);
        } else go(state.i + 1);
      }, Math.max(15, 12000 / N));
    }
  }
  function nearest(value) {
    var best = 0, bd = Infinity;
    for (var j = 0; j < N; j++) {
      var d = S.driver.slider ? Math.abs(S.angles[j] - value) : Math.abs(wrap(S.angles[j] - value));
      if (d < bd) { bd = d; best = j; }
    }
    return best;
  }
  var hashLock = false;
  function readHash() {
    var h = (location.hash || "").replace(/^#/, ""), a = null, st = null;
    h.split("&").forEach(function (kv) {
      var p = kv.split("=");
      if (p[0] === "angle" && p[1] !== undefined && p[1] !== "" && isFinite(+p[1])) a = +p[1];
      if (p[0] === "step" && p[1] !== undefined && isFinite(+p[1])) st = Math.max(0, Math.floor(+p[1]));
    });
    // the address says it all: no angle is the drawn pose, no step the whole construction
    state.i = a !== null ? nearest(a) : S.start;
    state.step = st !== null ? st : 0;
  }
  function writeHash() {
    if (hashLock) return;
    var a = S.driver.slider ? S.angles[state.i] : wrap(S.angles[state.i]);
    var h = "#angle=" + (Math.round(a * 1e6) / 1e6) + (state.step ? "&step=" + state.step : "");
    if (location.hash !== h) {
      try { history.replaceState(null, "", h); } catch (e) { /* a sandboxed frame: no address to write */ }
    }
  }
  function keys(e) {
    if (e.altKey || e.ctrlKey || e.metaKey) return;
    var big = e.shiftKey ? 10 : 1, used = true;
    switch (e.key) {
      case "ArrowRight": play(false); go(state.i + big); break;
      case "ArrowLeft": play(false); go(state.i - big); break;
      case "ArrowDown": case "+": case "n": case "PageDown": setStep(state.step + 1); break;
      case "ArrowUp": case "-": case "p": case "PageUp": setStep(state.step - 1); break;
      case "Home": setStep(0); break;
      case "End": setStep(1e9); break;
      case " ": case "k": play(!state.playing); break;
      default: used = false;
    }
    if (used) e.preventDefault();
  }
  // the tooltip: hover, or tap (a tap pins it until the next tap)
  function tipFor(el) { while (el && el !== document && !(el.dataset && el.dataset.tip)) el = el.parentNode; return el && el !== document ? el : null; }
  function showTip(el, x, y) {
    var tip = document.getElementById("tip");
    if (!el) { tip.hidden = true; return; }
    tip.textContent = "";
    el.dataset.tip.split("\n").forEach(function (ln, j) { if (j) tip.appendChild(document.createElement("br")); tip.appendChild(document.createTextNode(ln)); });
    tip.hidden = false;
    var w = tip.offsetWidth, h = tip.offsetHeight;
    tip.style.left = Math.max(4, Math.min(window.innerWidth - w - 4, x + 14)) + "px";
    tip.style.top = Math.max(4, y + 16 + h > window.innerHeight ? y - h - 12 : y + 16) + "px";
  }
  function legend() {
    var kinds = [["absolute", "absolute velocity or acceleration"], ["relative", "relative (one link)"], ["normal", "normal component A\u207f"],
      ["tangential", "tangential component A\u1d57"], ["coriolis", "Coriolis 2\u03c9 \u00d7 V"], ["slip", "slip along the path"]];
    var html = kinds.map(function (k) {
      return '<svg viewBox="0 0 60 16" aria-hidden="true">' + arrow(2, 8, 58, 8, k[0]) + "</svg><span>" + k[1] + "</span>";
    });
    html.push('<svg viewBox="0 0 60 16" aria-hidden="true">' + line(2, 8, 58, 8, "cl") + "</svg><span>construction line</span>");
    html.push('<svg viewBox="0 0 60 16" aria-hidden="true">' + line(2, 8, 58, 8, "cl now") + "</svg><span>the current step</span>");
    document.getElementById("legend").innerHTML = html.join("");
  }

  function init() {
    var r = document.getElementById("angle");
    r.max = N - 1;
    r.addEventListener("input", function () { play(false); go(+r.value); });
    document.getElementById("play").addEventListener("click", function () { play(!state.playing); });
    document.getElementById("prev").addEventListener("click", function () { play(false); go(state.i - 1); });
    document.getElementById("next").addEventListener("click", function () { play(false); go(state.i + 1); });
    document.getElementById("step-first").addEventListener("click", function () { setStep(0); });
    document.getElementById("step-prev").addEventListener("click", function () { setStep(state.step - 1); });
    document.getElementById("step-next").addEventListener("click", function () { setStep(state.step + 1); });
    document.addEventListener("keydown", keys);
    document.addEventListener("pointermove", function (e) {
      if (state.pinned) return;
      var el = tipFor(e.target);
      showTip(el, e.clientX, e.clientY);
    });
    document.addEventListener("click", function (e) {
      var el = tipFor(e.target);
      if (state.pinned && state.pinned.classList) state.pinned.classList.remove("pinned");
      state.pinned = el;
      if (el && el.classList) el.classList.add("pinned");
      showTip(el, e.clientX, e.clientY);
    });
    window.addEventListener("hashchange", function () { readHash(); hashLock = true; draw(); hashLock = false; });
    legend();
    document.getElementById("title").innerHTML = eqHtml(S.title);   // omega_2 -> ω2, 30 deg -> 30°
    document.getElementById("reference").innerHTML = reference();
    readHash();
    hashLock = true;
    draw();
    hashLock = false;
  }
  init();
})();
