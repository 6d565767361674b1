/* Touchdown trajectory viewer: plays the landing of one or more engines of one lander, from a
 * trajectory document (touchdown.trajectory/1, docs/outputs.md) embedded in the page in
 * <script id="trajectory"> or opened by the user ("Open trajectory…").
 *
 * Positions in the document are in the surface frame S (X-Y on the sloped surface, Z up its
 * normal); the views draw in the gravity frame G (Z up against gravity), r_G = M · r_S with
 * M = surface.surface_to_gravity, so a slope shows as a tilted ground. The 3D views are a
 * Canvas 2D with a perspective projection of their own; the time plots are uPlot.
 *
 * At time t every engine shows its frames interpolated linearly between the last frame with
 * t_s <= t and the next one (positions, attitude, forces); the stability distances are those of
 * the last frame at or before t. A footpad's contact state is that of its last contact event at
 * or before t (the document's `events` list every change exactly; frames keep only some), and
 * before its first event that of the first frame. Before its first frame an engine shows its
 * first frame, after its last frame its last one.
 *
 * Automation API, window.touchdownView:
 *   ready            true once the trajectory is drawn (false while an opened file loads)
 *   time()           the current time, s
 *   setTime(t_s)     goes to time t_s (clamped to timeRange()) and draws at once
 *   timeRange()      [first, last] time of the trajectory, s
 *   mode()           the layout: "overlay" (one 3D view, every engine) or "side-by-side"
 *                    (one 3D view per engine); mode(m) sets it and draws at once
 *   play(), pause(), playing()
 *   scenarioName()   the scenario's name shown in the heading
 *   camera(e)        for engine index e (order of the document's engines): {canvasId, matrix,
 *                    width, height, devicePixelRatio}, the 3D canvas that draws engine e and
 *                    its camera. matrix: 16 numbers, a row-major 4x4 taking [x, y, z, 1] of a
 *                    surface-frame point r_S (the surface-to-gravity rotation included) to clip
 *                    coordinates [xc, yc, zc, wc]; the point is drawn, when wc > 0, at CSS pixel
 *                    ((xc/wc + 1)/2 · width, (1 − yc/wc)/2 · height) from the canvas's top left
 *                    corner, and at canvas (backing store) pixel CSS pixel · devicePixelRatio.
 *   contactColours   the footpad disc's fill by contact state, "#rrggbb":
 *                    [never touched, in contact, left the surface]
 *   load(doc)        replaces the trajectory by doc (a parsed trajectory document), as the file
 *                    picker does; throws on a document that is not a trajectory
 */
"use strict";

(function () {
  // ---------------------------------------------------------------- constants

  const ENGINE_COLOURS = { core: "#1f3b73", rapier: "#d95f02", mujoco: "#1b9e77" };
  const OTHER_ENGINE_COLOUR = "#555555";
  const CONTACT = [
    { label: "never touched", colour: "#ffffff" },
    { label: "in contact", colour: "#f2b701" },
    { label: "left the surface", colour: "#8e44ad" },
  ];
  // Diverging strut-force scale, tension positive: position in [-1, 1] of the full scale, RGB.
  // Positions are logarithmic in |force| (forcePosition): a landing's forces span decades (a
  // contact spike can be a hundred times the struts' crush loads), which a linear scale would
  // show as grey but for the spike.
  const FORCE_STOPS = [
    [-1, [33, 102, 172]],
    [-0.5, [103, 169, 207]],
    [0, [190, 190, 190]],
    [0.5, [239, 138, 98]],
    [1, [178, 24, 43]],
  ];
  const FORCE_LEVELS = 256;
  // The decades of |force| the scale spans below its full scale (linear below that).
  const FORCE_DECADES = 4;
  const FORCE_LOG_SPAN = Math.log10(1 + Math.pow(10, FORCE_DECADES));
  // Least distance between two ticks of the force legend, in scale positions.
  const FORCE_TICK_GAP = 0.16;
  const BACKGROUND = "#f4f5f7";
  const GROUND_FILL = "#ece8df";
  const GRID_STROKE = "#c9c1b0";
  const HOLE_FILL = "#b9ad95";
  const HOLE_STROKE = "#8a7d62";
  const OBSTACLE_STROKE = "#8c5a2b";
  const CURB_STROKE = "#4a3b2a";
  // Grid lines per scene radius, about (the step is a round length near radius / this).
  const GRID_LINES_PER_RADIUS = 4;
  const FOV_Y = (35 * Math.PI) / 180;
  const NEAR = 0.02;
  const FAR = 200;
  const DISC_SEGMENTS = 32;
  const LEG_DASHES = [[], [8, 4], [2, 3], [9, 3, 2, 3]];
  const COM_DASH = [5, 4];
  const NO_DASH = [];
  const SPEED_DEFAULT = 0.1;
  const PLOT_HEIGHT = 220;

  // ---------------------------------------------------------------- small vector algebra

  /** out = a · b, 4x4 row-major. */
  function mul4(out, a, b) {
    for (let r = 0; r < 4; r++) {
      for (let c = 0; c < 4; c++) {
        out[4 * r + c] =
          a[4 * r] * b[c] + a[4 * r + 1] * b[4 + c] + a[4 * r + 2] * b[8 + c] + a[4 * r + 3] * b[12 + c];
      }
    }
    return out;
  }

  /** The rotation matrix (row-major 3x3) of unit quaternion q = [w, x, y, z], into out. */
  function quatToMatrix(q, out) {
    const w = q[0], x = q[1], y = q[2], z = q[3];
    out[0] = 1 - 2 * (y * y + z * z); out[1] = 2 * (x * y - w * z); out[2] = 2 * (x * z + w * y);
    out[3] = 2 * (x * y + w * z); out[4] = 1 - 2 * (x * x + z * z); out[5] = 2 * (y * z - w * x);
    out[6] = 2 * (x * z - w * y); out[7] = 2 * (y * z + w * x); out[8] = 1 - 2 * (x * x + y * y);
  }

  /** out[o..o+3] = R · v[i..i+3] + p (R row-major 3x3): a body point into the surface frame. */
  function bodyToSurface(R, p, v, i, out, o) {
    const x = v[i], y = v[i + 1], z = v[i + 2];
    out[o] = R[0] * x + R[1] * y + R[2] * z + p[0];
    out[o + 1] = R[3] * x + R[4] * y + R[5] * z + p[1];
    out[o + 2] = R[6] * x + R[7] * y + R[8] * z + p[2];
  }

  /** Rows of nested [[x, y, z], ...] as one flat Float64Array. */
  function flatten(rows, width) {
    const out = new Float64Array(rows.length * width);
    for (let i = 0; i < rows.length; i++) {
      for (let k = 0; k < width; k++) out[width * i + k] = rows[i][k];
    }
    return out;
  }

  /** The convex hull (counter-clockwise) of 2D points [[x, y], ...], Andrew's monotone chain. */
  function convexHull(points) {
    const p = points.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const lower = [], upper = [];
    for (const q of p) {
      while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], q) <= 1e-12) lower.pop();
      lower.push(q);
    }
    for (let i = p.length - 1; i >= 0; i--) {
      const q = p[i];
      while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], q) <= 1e-12) upper.pop();
      upper.push(q);
    }
    return lower.slice(0, -1).concat(upper.slice(0, -1));
  }

  /** The largest index i with t[i] <= x (0 when x < t[0]). */
  function frameAt(t, x) {
    let lo = 0, hi = t.length - 1;
    if (x >= t[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (t[mid] <= x) lo = mid; else hi = mid;
    }
    return lo;
  }

  /** A "nice" number at or above x (1, 2, 2.5 or 5 times a power of ten). */
  function niceCeil(x) {
    if (!(x > 0)) return 1;
    const p = Math.pow(10, Math.floor(Math.log10(x)));
    for (const m of [1, 2, 2.5, 5, 10]) if (m * p >= x * (1 - 1e-9)) return m * p;
    return 10 * p;
  }

  function engineColour(name) {
    return ENGINE_COLOURS[name] || OTHER_ENGINE_COLOUR;
  }

  /** "#rrggbb" with alpha a as "rgba(...)". */
  function withAlpha(hex, a) {
    const n = parseInt(hex.slice(1), 16);
    return `rgba(${(n >> 16) & 255}, ${(n >> 8) & 255}, ${n & 255}, ${a})`;
  }

  // ---------------------------------------------------------------- the model, built on load

  /** Everything the views and plots need from a trajectory document, precomputed. */
  function buildModel(doc) {
    if (!doc || doc.schema !== "touchdown.trajectory/1") {
      const schema = doc && typeof doc.schema === "string" ? doc.schema : "missing";
      throw new Error(`not a trajectory this page reads: its schema field is ${schema}, expected touchdown.trajectory/1`);
    }
    if (!Array.isArray(doc.engines) || doc.engines.length === 0) throw new Error("the trajectory has no engine");
    const M = doc.surface.surface_to_gravity;
    const legs = doc.vehicle.legs;
    const nLegs = legs.length;
    const trunnions = new Float64Array(9 * nLegs); // B2, B3, B4 of each leg, body axes
    legs.forEach((leg, k) => {
      trunnions.set(leg.primary_trunnion_m, 9 * k);
      trunnions.set(leg.sec31_trunnion_m, 9 * k + 3);
      trunnions.set(leg.sec41_trunnion_m, 9 * k + 6);
    });
    const body = buildBody(legs);
    const engines = doc.engines.map((e, index) => buildEngine(e, index, nLegs, 2 * body.m));
    let t0 = Infinity, t1 = -Infinity, forceMax = 0;
    for (const e of engines) {
      t0 = Math.min(t0, e.t[0]);
      t1 = Math.max(t1, e.t[e.n - 1]);
      for (let i = 0; i < e.force.length; i++) forceMax = Math.max(forceMax, Math.abs(e.force[i]));
    }
    const model = {
      name: doc.scenario_name || (doc.scenario && doc.scenario.path) || "trajectory",
      M,
      // Up against gravity, in the surface frame: M's last row (M^T · e_z).
      upS: [M[2][0], M[2][1], M[2][2]],
      nLegs,
      padRadius: legs.map((l) => l.pad_radius_m),
      trunnions,
      body,
      ground: doc.surface.pads,
      engines,
      t0,
      t1,
      forceScale: niceCeil(forceMax),
    };
    model.extent = sceneExtent(model);
    model.padSites = padSites(model);
    model.grid = buildGrid(model.extent);
    model.wallHeight = wallHeight(model);
    model.forceLut = forceLut();
    return model;
  }

  /** One engine's frames as flat typed arrays, its colours, and its scratch state for drawing
   * (`now`, filled by sample(); the body prism has `bodyCorners` corners). */
  function buildEngine(e, index, nLegs, bodyCorners) {
    const f = e.frames;
    const n = f.t_s.length;
    const contact = new Uint8Array(nLegs * n);
    // Axial forces, tension positive (the primary's compression-positive force negated):
    // [frame][leg][primary, sec31, sec41].
    const force = new Float64Array(3 * nLegs * n);
    const pads = [], point1 = [];
    f.legs.forEach((leg, k) => {
      pads.push(flatten(leg.pad_m, 3));
      point1.push(flatten(leg.point1_m, 3));
      for (let i = 0; i < n; i++) {
        contact[k * n + i] = leg.contact[i];
        force[3 * (nLegs * i + k)] = -leg.primary_force_n[i];
        force[3 * (nLegs * i + k) + 1] = leg.sec31_force_n[i];
        force[3 * (nLegs * i + k) + 2] = leg.sec41_force_n[i];
      }
    });
    const walls = f.walls.map((w) => ({
      legs: w.legs,
      sd: Array.isArray(w.stability_distance_m)
        ? Float64Array.from(w.stability_distance_m, (v) => (v === null ? NaN : v))
        : null,
    }));
    const colour = engineColour(e.name);
    return {
      index,
      name: e.name,
      version: e.version,
      outcome: e.outcome,
      decisionTime: e.decision_time_s,
      pastCapacity: e.past_capacity || [],
      steps: e.steps,
      events: e.events || [],
      contactEvents: contactEvents(e.events || [], nLegs),
      curbs: e.curbs || [],
      colour,
      bodyFill: withAlpha(colour, 0.1),
      wallFill: withAlpha(colour, 0.04),
      wallFillNearest: withAlpha(colour, 0.12),
      wallStroke: withAlpha(colour, 0.3),
      frames: f,
      n,
      t: Float64Array.from(f.t_s),
      position: flatten(f.position_m, 3),
      attitude: flatten(f.attitude, 4),
      comProjection: flatten(f.com_projection_m, 3),
      pads,
      point1,
      contact,
      force,
      walls,
      now: {
        position: new Float64Array(3),
        attitude: new Float64Array(4),
        rotation: new Float64Array(9),
        comProjection: new Float64Array(3),
        pads: new Float64Array(3 * nLegs),
        point1: new Float64Array(3 * nLegs),
        trunnions: new Float64Array(9 * nLegs),
        contact: new Uint8Array(nLegs),
        force: new Float64Array(3 * nLegs),
        minSd: NaN,
        minSdWall: -1,
        body: new Float64Array(3 * bodyCorners),
      },
    };
  }

  /** Each leg's contact changes: times (s, increasing) and new states, from the document's
   * events. */
  function contactEvents(events, nLegs) {
    const byLeg = Array.from({ length: nLegs }, () => ({ t: [], state: [] }));
    for (const ev of events) {
      const leg = byLeg[ev.leg - 1];
      if (leg) {
        leg.t.push(ev.t_s);
        leg.state.push(ev.contact);
      }
    }
    return byLeg.map((leg) => ({ t: Float64Array.from(leg.t), state: Uint8Array.from(leg.state) }));
  }

  /** The body: a prism whose outline is the convex hull (seen along body Z) of every trunnion,
   * from the lowest to the highest trunnion; corners in body axes, bottom ring then top ring. */
  function buildBody(legs) {
    const xy = [];
    let zMin = Infinity, zMax = -Infinity;
    for (const leg of legs) {
      for (const p of [leg.primary_trunnion_m, leg.sec31_trunnion_m, leg.sec41_trunnion_m]) {
        xy.push([p[0], p[1]]);
        zMin = Math.min(zMin, p[2]);
        zMax = Math.max(zMax, p[2]);
      }
    }
    const hull = convexHull(xy);
    if (zMax - zMin < 0.05 * Math.hypot(hull[0][0], hull[0][1])) {
      const mid = 0.5 * (zMin + zMax), half = 0.05 * Math.hypot(hull[0][0], hull[0][1]);
      zMin = mid - half;
      zMax = mid + half;
    }
    const m = hull.length;
    const corners = new Float64Array(6 * m);
    hull.forEach((p, i) => {
      corners.set([p[0], p[1], zMin], 3 * i);
      corners.set([p[0], p[1], zMax], 3 * (m + i));
    });
    return { m, corners };
  }

  /** The region of the surface plane the landing covers (footpads and centre of mass, every
   * engine, every frame) and the radius of a sphere holding it, for the grid and the camera. */
  function sceneExtent(model) {
    let xMin = Infinity, xMax = -Infinity, yMin = Infinity, yMax = -Infinity, zMax = 0;
    const take = (a) => {
      for (let i = 0; i < a.length; i += 3) {
        xMin = Math.min(xMin, a[i]); xMax = Math.max(xMax, a[i]);
        yMin = Math.min(yMin, a[i + 1]); yMax = Math.max(yMax, a[i + 1]);
        zMax = Math.max(zMax, a[i + 2]);
      }
    };
    for (const e of model.engines) {
      take(e.position);
      e.pads.forEach(take);
      for (const c of e.curbs) take([c.point_m[0], c.point_m[1], 0]);
    }
    const pad = Math.max(...model.padRadius);
    const cx = 0.5 * (xMin + xMax), cy = 0.5 * (yMin + yMax);
    const radius = 0.5 * Math.hypot(xMax - xMin, yMax - yMin, zMax) + pad;
    const margin = Math.max(0.25 * radius, 4 * pad);
    return {
      x0: xMin - margin, x1: xMax + margin, y0: yMin - margin, y1: yMax + margin,
      centre: [cx, cy, 0.5 * zMax],
      radius,
    };
  }

  /** Where each footpad's local ground (hole, obstacle) is drawn: its footpad where it first
   * touched in the first engine that touched with it, else where it starts. */
  function padSites(model) {
    const sites = [];
    for (let k = 0; k < model.nLegs; k++) {
      let site = null;
      for (const e of model.engines) {
        const touch = e.events.find((ev) => ev.leg === k + 1 && ev.contact === 1);
        if (touch) {
          const i = frameAt(e.t, touch.t_s);
          site = [e.pads[k][3 * i], e.pads[k][3 * i + 1]];
          break;
        }
      }
      if (!site) site = [model.engines[0].pads[k][0], model.engines[0].pads[k][1]];
      sites.push(site);
    }
    return sites;
  }

  /** The ground grid on the surface plane Z_S = 0: its step (m, a round length scaled to the
   * scene, so that a model and a full-scale lander look alike) and its lines, [x0, y0, x1, y1]
   * each. */
  function buildGrid(ext) {
    const step = niceCeil(ext.radius / GRID_LINES_PER_RADIUS);
    const lines = [];
    const i0 = Math.ceil(ext.x0 / step), i1 = Math.floor(ext.x1 / step);
    const j0 = Math.ceil(ext.y0 / step), j1 = Math.floor(ext.y1 / step);
    for (let i = i0; i <= i1; i++) lines.push(i * step, ext.y0, i * step, ext.y1);
    for (let j = j0; j <= j1; j++) lines.push(ext.x0, j * step, ext.x1, j * step);
    return { step, lines: Float64Array.from(lines) };
  }

  /** The stability walls' height: above the highest centre of mass of the landing. */
  function wallHeight(model) {
    let h = 0;
    for (const e of model.engines) {
      for (let i = 0; i < e.position.length; i += 3) {
        const p = e.position;
        h = Math.max(h, p[i] * model.upS[0] + p[i + 1] * model.upS[1] + p[i + 2] * model.upS[2]);
      }
    }
    return 1.25 * h + 0.05 * model.extent.radius;
  }

  /** The force scale's position in [-1, 1] of axial force f (N) on a scale of ±full (N):
   * symmetric logarithmic, sign(f) · log10(1 + |f|/f0) / log10(1 + full/f0), f0 = full/10^4. */
  function forcePosition(f, full) {
    const a = Math.log10(1 + (Math.abs(f) * Math.pow(10, FORCE_DECADES)) / full) / FORCE_LOG_SPAN;
    return Math.sign(f) * Math.min(1, a);
  }

  /** CSS colours of the force scale, FORCE_LEVELS + 1 levels from -1 to +1 of the full scale. */
  function forceLut() {
    const lut = [];
    for (let i = 0; i <= FORCE_LEVELS; i++) lut.push(forceRgb(-1 + (2 * i) / FORCE_LEVELS));
    return lut;
  }

  /** The force scale's colour at s in [-1, 1], "rgb(...)". */
  function forceRgb(s) {
    let k = 0;
    while (k < FORCE_STOPS.length - 2 && s > FORCE_STOPS[k + 1][0]) k++;
    const [s0, c0] = FORCE_STOPS[k], [s1, c1] = FORCE_STOPS[k + 1];
    const a = Math.min(1, Math.max(0, (s - s0) / (s1 - s0)));
    const c = c0.map((v, i) => Math.round(v + a * (c1[i] - v)));
    return `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
  }

  // ---------------------------------------------------------------- state at time t

  /** Fills engine e's `now` with its state at time t. */
  function sample(e, t, model) {
    const now = e.now;
    const i = frameAt(e.t, t);
    const j = Math.min(i + 1, e.n - 1);
    const a = j > i && t > e.t[i] ? Math.min(1, (t - e.t[i]) / (e.t[j] - e.t[i])) : 0;
    lerp(e.position, 3, i, j, a, now.position, 0);
    lerp(e.comProjection, 3, i, j, a, now.comProjection, 0);
    // Attitude: normalised linear interpolation, on the same hemisphere.
    const q = e.attitude;
    const dot = q[4 * i] * q[4 * j] + q[4 * i + 1] * q[4 * j + 1] + q[4 * i + 2] * q[4 * j + 2] + q[4 * i + 3] * q[4 * j + 3];
    const sj = dot < 0 ? -a : a;
    let norm = 0;
    for (let k = 0; k < 4; k++) {
      now.attitude[k] = (1 - a) * q[4 * i + k] + sj * q[4 * j + k];
      norm += now.attitude[k] * now.attitude[k];
    }
    norm = Math.sqrt(norm);
    for (let k = 0; k < 4; k++) now.attitude[k] /= norm;
    quatToMatrix(now.attitude, now.rotation);
    for (let k = 0; k < model.nLegs; k++) {
      lerp(e.pads[k], 3, i, j, a, now.pads, 3 * k);
      lerp(e.point1[k], 3, i, j, a, now.point1, 3 * k);
      const ev = e.contactEvents[k];
      now.contact[k] = ev.t.length > 0 && t >= ev.t[0] ? ev.state[frameAt(ev.t, t)] : e.contact[k * e.n];
      for (let s = 0; s < 3; s++) bodyToSurface(now.rotation, now.position, model.trunnions, 9 * k + 3 * s, now.trunnions, 9 * k + 3 * s);
    }
    lerp(e.force, 3 * model.nLegs, i, j, a, now.force, 0);
    const b = model.body;
    for (let c = 0; c < 2 * b.m; c++) bodyToSurface(now.rotation, now.position, b.corners, 3 * c, now.body, 3 * c);
    // The smallest stability distance over the walls defined at this frame.
    now.minSd = NaN;
    now.minSdWall = -1;
    for (let k = 0; k < e.walls.length; k++) {
      const sd = e.walls[k].sd;
      if (sd && !Number.isNaN(sd[i]) && (now.minSdWall < 0 || sd[i] < now.minSd)) {
        now.minSd = sd[i];
        now.minSdWall = k;
      }
    }
  }

  /** out[o..o+w] = (1 − a) · src[i] + a · src[j], rows of width w. */
  function lerp(src, w, i, j, a, out, o) {
    for (let k = 0; k < w; k++) out[o + k] = src[w * i + k] + a * (src[w * j + k] - src[w * i + k]);
  }

  // ---------------------------------------------------------------- camera and projection

  /** The orbiting camera, shared by every view: around `target` (gravity frame). */
  const camera = { azimuth: 0, elevation: 0, distance: 1, target: [0, 0, 0] };

  /** Puts the camera where it starts: the whole landing in sight, looking across the slope's
   * fall line from a little above the ground. */
  function resetCamera() {
    const m = state.model;
    const c = m.extent.centre;
    const M = m.M;
    camera.target = [0, 1, 2].map((r) => M[r][0] * c[0] + M[r][1] * c[1] + M[r][2] * c[2]);
    // The surface normal's horizontal part points downhill (gravity frame).
    const nx = M[0][2], ny = M[1][2];
    const downhill = Math.hypot(nx, ny) > 1e-6 ? Math.atan2(ny, nx) : Math.PI / 2;
    camera.azimuth = downhill - Math.PI / 2 - (25 * Math.PI) / 180;
    camera.elevation = (18 * Math.PI) / 180;
    camera.distance = (1.05 * m.extent.radius) / Math.sin(FOV_Y / 2);
  }

  /** view.matrix = projection · look-at · surface-to-gravity, for the view's canvas size. */
  function updateMatrix(view) {
    const M = state.model.M;
    const ce = Math.cos(camera.elevation), se = Math.sin(camera.elevation);
    const ca = Math.cos(camera.azimuth), sa = Math.sin(camera.azimuth);
    const T = camera.target, d = camera.distance;
    const eye = [T[0] + d * ce * ca, T[1] + d * ce * sa, T[2] + d * se];
    // Camera axes: forward f (eye to target), right s = f × up, true up u = s × f.
    const f = [-ce * ca, -ce * sa, -se];
    const s = [f[1], -f[0], 0];
    const sn = Math.hypot(s[0], s[1]);
    s[0] /= sn; s[1] /= sn;
    const u = [s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const look = [
      s[0], s[1], s[2], -dot(s, eye),
      u[0], u[1], u[2], -dot(u, eye),
      -f[0], -f[1], -f[2], dot(f, eye),
      0, 0, 0, 1,
    ];
    // FOV_Y is the vertical field of view, or the horizontal one of a view taller than wide.
    const aspect = view.width / view.height, g = Math.min(1, aspect) / Math.tan(FOV_Y / 2);
    const projection = [
      g / aspect, 0, 0, 0,
      0, g, 0, 0,
      0, 0, (FAR + NEAR) / (NEAR - FAR), (2 * FAR * NEAR) / (NEAR - FAR),
      0, 0, -1, 0,
    ];
    const surfaceToGravity = [
      M[0][0], M[0][1], M[0][2], 0,
      M[1][0], M[1][1], M[1][2], 0,
      M[2][0], M[2][1], M[2][2], 0,
      0, 0, 0, 1,
    ];
    mul4(view.matrix, mul4(view.scratch, projection, look), surfaceToGravity);
    view.cameraRight = s;
    view.cameraUp = u;
  }

  // The projected point of project(): screen x, y (CSS px) and clip w.
  let px = 0, py = 0, pw = 0;

  /** Projects surface point (x, y, z) with view's matrix into px, py, pw; false when behind
   * the camera. */
  function project(view, x, y, z) {
    const m = view.matrix;
    const xc = m[0] * x + m[1] * y + m[2] * z + m[3];
    const yc = m[4] * x + m[5] * y + m[6] * z + m[7];
    pw = m[12] * x + m[13] * y + m[14] * z + m[15];
    if (pw <= NEAR) return false;
    px = (xc / pw + 1) * 0.5 * view.width;
    py = (1 - yc / pw) * 0.5 * view.height;
    return true;
  }

  /** Adds the segment a-b (surface frame) to the current path, cut at the near plane. */
  function segment(view, ctx, ax, ay, az, bx, by, bz) {
    const aIn = project(view, ax, ay, az);
    const aX = px, aY = py, aW = pw;
    const bIn = project(view, bx, by, bz);
    if (!aIn && !bIn) return;
    if (aIn && bIn) {
      ctx.moveTo(aX, aY);
      ctx.lineTo(px, py);
      return;
    }
    // One end behind the camera: cut where clip w reaches the near plane.
    const bW = pw;
    const s = (NEAR * 1.01 - aW) / (bW - aW);
    project(view, ax + s * (bx - ax), ay + s * (by - ay), az + s * (bz - az));
    const cX = px, cY = py;
    if (aIn) { ctx.moveTo(aX, aY); ctx.lineTo(cX, cY); } else { project(view, bx, by, bz); ctx.moveTo(cX, cY); ctx.lineTo(px, py); }
  }

  /** Adds the closed polygon of `count` surface points pts[o..] to the current path; false
   * (nothing added) when a corner is behind the camera. */
  function polygon(view, ctx, pts, o, count) {
    for (let c = 0; c < count; c++) if (!project(view, pts[o + 3 * c], pts[o + 3 * c + 1], pts[o + 3 * c + 2])) return false;
    for (let c = 0; c < count; c++) {
      project(view, pts[o + 3 * c], pts[o + 3 * c + 1], pts[o + 3 * c + 2]);
      if (c === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
    }
    ctx.closePath();
    return true;
  }

  // Scratch corners for quads and discs, reused by every draw.
  const quad = new Float64Array(12);
  const disc = new Float64Array(3 * DISC_SEGMENTS);
  const DISC_COS = Float64Array.from({ length: DISC_SEGMENTS }, (_, i) => Math.cos((2 * Math.PI * i) / DISC_SEGMENTS));
  const DISC_SIN = Float64Array.from({ length: DISC_SEGMENTS }, (_, i) => Math.sin((2 * Math.PI * i) / DISC_SEGMENTS));

  /** disc = the circle of radius r about (x, y, z), parallel to the surface plane. */
  function circle(x, y, z, r) {
    for (let i = 0; i < DISC_SEGMENTS; i++) {
      disc[3 * i] = x + r * DISC_COS[i];
      disc[3 * i + 1] = y + r * DISC_SIN[i];
      disc[3 * i + 2] = z;
    }
  }

  // ---------------------------------------------------------------- drawing, one function per element

  /** Draws one 3D view: the ground, then each of its engines (the first on top). */
  function drawView(view) {
    const ctx = view.ctx, model = state.model;
    ctx.setTransform(view.pixelRatio, 0, 0, view.pixelRatio, 0, 0);
    ctx.fillStyle = BACKGROUND;
    ctx.fillRect(0, 0, view.width, view.height);
    updateMatrix(view);
    drawGround(view, ctx, model);
    drawHoles(view, ctx, model);
    drawObstacles(view, ctx, model);
    const engines = view.engines;
    for (let n = engines.length - 1; n >= 0; n--) drawCurbs(view, ctx, model.engines[engines[n]]);
    // Overlaid engines' walls nearly coincide: together, as opaque as one engine's.
    ctx.globalAlpha = 1 / engines.length;
    for (let n = engines.length - 1; n >= 0; n--) drawWalls(view, ctx, model, model.engines[engines[n]]);
    ctx.globalAlpha = 1;
    for (let n = engines.length - 1; n >= 0; n--) {
      const e = model.engines[engines[n]];
      drawComProjection(view, ctx, e);
      drawBody(view, ctx, model, e);
      drawStruts(view, ctx, model, e);
      drawPads(view, ctx, model, e);
    }
    drawLegNumbers(view, ctx, model, model.engines[engines[0]]);
    drawGravityAxes(view, ctx, model);
  }

  /** The ground: the surface plane Z_S = 0 as a filled rectangle with a grid. */
  function drawGround(view, ctx, model) {
    const x = model.extent, g = model.grid.lines;
    quad.set([x.x0, x.y0, 0, x.x1, x.y0, 0, x.x1, x.y1, 0, x.x0, x.y1, 0]);
    ctx.beginPath();
    if (polygon(view, ctx, quad, 0, 4)) {
      ctx.fillStyle = GROUND_FILL;
      ctx.fill();
    }
    ctx.beginPath();
    for (let i = 0; i < g.length; i += 4) segment(view, ctx, g[i], g[i + 1], 0, g[i + 2], g[i + 3], 0);
    ctx.strokeStyle = GRID_STROKE;
    ctx.lineWidth = 1;
    ctx.setLineDash(NO_DASH);
    ctx.stroke();
  }

  /** Holes: under a footpad whose local ground is lowered (hole_m > 0), a patch of the lowered
   * plane Z_S = −hole_m around where the footpad touches, with its walls' edges up to Z_S = 0. */
  function drawHoles(view, ctx, model) {
    model.ground.forEach((ground, k) => {
      if (!(ground.hole_m > 0)) return;
      const [x, y] = model.padSites[k], h = 2.5 * model.padRadius[k], z = -ground.hole_m;
      quad.set([x - h, y - h, z, x + h, y - h, z, x + h, y + h, z, x - h, y + h, z]);
      ctx.beginPath();
      if (polygon(view, ctx, quad, 0, 4)) {
        ctx.fillStyle = HOLE_FILL;
        ctx.fill();
      }
      ctx.beginPath();
      polygon(view, ctx, quad, 0, 4);
      for (let c = 0; c < 4; c++) segment(view, ctx, quad[3 * c], quad[3 * c + 1], z, quad[3 * c], quad[3 * c + 1], 0);
      ctx.strokeStyle = HOLE_STROKE;
      ctx.lineWidth = 1;
      ctx.setLineDash(NO_DASH);
      ctx.stroke();
    });
  }

  /** Obstacles and spikes: a footpad held laterally once it touches (obstacle_m > 0, or
   * spike_depth_m > 0), marked by a ring on its local ground around where it touches, with
   * short teeth (their height is a mark, not the obstacle's nor the spikes': the legend gives
   * that). */
  function drawObstacles(view, ctx, model) {
    model.ground.forEach((ground, k) => {
      if (!(ground.obstacle_m > 0) && !(ground.spike_depth_m > 0)) return;
      const [x, y] = model.padSites[k], r = 1.5 * model.padRadius[k];
      const z = -Math.max(ground.hole_m, 0), tooth = 0.4 * model.padRadius[k];
      ctx.beginPath();
      circle(x, y, z, r);
      polygon(view, ctx, disc, 0, DISC_SEGMENTS);
      for (let i = 0; i < DISC_SEGMENTS; i += 2) {
        segment(view, ctx, disc[3 * i], disc[3 * i + 1], z, disc[3 * i], disc[3 * i + 1], z + tooth);
      }
      ctx.strokeStyle = OBSTACLE_STROKE;
      ctx.lineWidth = 1.5;
      ctx.setLineDash(NO_DASH);
      ctx.stroke();
    });
  }

  /** Curbs of engine e: a line of the surface plane through point_m along `along`, with ticks
   * on the curb's side (`toward`, from the footpad to the curb). */
  function drawCurbs(view, ctx, e) {
    if (e.curbs.length === 0) return;
    const half = 0.3, tick = 0.04, every = 0.06;
    ctx.beginPath();
    for (const c of e.curbs) {
      const [x, y] = c.point_m, [bx, by] = c.along, [ax, ay] = c.toward;
      segment(view, ctx, x - half * bx, y - half * by, 0, x + half * bx, y + half * by, 0);
      for (let s = -half; s <= half + 1e-9; s += every) {
        segment(view, ctx, x + s * bx, y + s * by, 0, x + s * bx + tick * ax, y + s * by + tick * ay, 0);
      }
    }
    ctx.strokeStyle = CURB_STROKE;
    ctx.lineWidth = 2.5;
    ctx.setLineDash(NO_DASH);
    ctx.stroke();
  }

  /** Stability walls of engine e: translucent vertical (along gravity) quads through the
   * footpads of adjacent legs; the wall nearest the centre of mass (the minimum stability
   * distance) darker. */
  function drawWalls(view, ctx, model, e) {
    const now = e.now, up = model.upS, h = model.wallHeight;
    e.walls.forEach((w, k) => {
      const a = 3 * (w.legs[0] - 1), b = 3 * (w.legs[1] - 1), p = now.pads;
      quad.set([
        p[a], p[a + 1], p[a + 2],
        p[b], p[b + 1], p[b + 2],
        p[b] + h * up[0], p[b + 1] + h * up[1], p[b + 2] + h * up[2],
        p[a] + h * up[0], p[a + 1] + h * up[1], p[a + 2] + h * up[2],
      ]);
      ctx.beginPath();
      if (!polygon(view, ctx, quad, 0, 4)) return;
      const nearest = k === now.minSdWall;
      ctx.fillStyle = nearest ? e.wallFillNearest : e.wallFill;
      ctx.fill();
      ctx.strokeStyle = e.wallStroke;
      ctx.lineWidth = 1;
      ctx.setLineDash(NO_DASH);
      ctx.stroke();
    });
  }

  /** Centre of mass of engine e: a dot, a dashed line along gravity down to its projection on
   * the surface plane, and a cross at the projection. */
  function drawComProjection(view, ctx, e) {
    const c = e.now.position, g = e.now.comProjection;
    ctx.strokeStyle = e.colour;
    ctx.lineWidth = 1.5;
    ctx.setLineDash(COM_DASH);
    ctx.beginPath();
    segment(view, ctx, c[0], c[1], c[2], g[0], g[1], g[2]);
    ctx.stroke();
    ctx.setLineDash(NO_DASH);
    if (project(view, g[0], g[1], g[2])) {
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(px - 6, py - 6); ctx.lineTo(px + 6, py + 6);
      ctx.moveTo(px - 6, py + 6); ctx.lineTo(px + 6, py - 6);
      ctx.stroke();
    }
    if (project(view, c[0], c[1], c[2])) {
      ctx.fillStyle = e.colour;
      ctx.beginPath();
      ctx.arc(px, py, 4, 0, 2 * Math.PI);
      ctx.fill();
    }
  }

  /** The vehicle body of engine e: the trunnions' prism, translucent faces, edges in the
   * engine's colour. */
  function drawBody(view, ctx, model, e) {
    const b = e.now.body, m = model.body.m;
    ctx.fillStyle = e.bodyFill;
    ctx.strokeStyle = e.colour;
    ctx.lineWidth = 2;
    ctx.setLineDash(NO_DASH);
    // Side faces.
    for (let i = 0; i < m; i++) {
      const j = (i + 1) % m;
      quad.set([b[3 * i], b[3 * i + 1], b[3 * i + 2], b[3 * j], b[3 * j + 1], b[3 * j + 2]], 0);
      quad.set([b[3 * (m + j)], b[3 * (m + j) + 1], b[3 * (m + j) + 2], b[3 * (m + i)], b[3 * (m + i) + 1], b[3 * (m + i) + 2]], 6);
      ctx.beginPath();
      if (polygon(view, ctx, quad, 0, 4)) ctx.fill();
    }
    // Bottom and top rings, and the vertical edges.
    ctx.beginPath();
    polygon(view, ctx, b, 0, m);
    polygon(view, ctx, b, 3 * m, m);
    for (let i = 0; i < m; i++) {
      segment(view, ctx, b[3 * i], b[3 * i + 1], b[3 * i + 2], b[3 * (m + i)], b[3 * (m + i) + 1], b[3 * (m + i) + 2]);
    }
    ctx.stroke();
  }

  /** Struts of engine e along their axes, coloured by axial force (tension positive): each
   * primary from its trunnion B2 to the footpad, each secondary from B3 or B4 to point 1. */
  function drawStruts(view, ctx, model, e) {
    const now = e.now, tr = now.trunnions;
    ctx.lineWidth = 4;
    ctx.lineCap = "round";
    ctx.setLineDash(NO_DASH);
    for (let k = 0; k < model.nLegs; k++) {
      const p = 3 * k;
      strut(view, ctx, model, tr, 9 * k, now.pads, p, now.force[3 * k]);
      strut(view, ctx, model, tr, 9 * k + 3, now.point1, p, now.force[3 * k + 1]);
      strut(view, ctx, model, tr, 9 * k + 6, now.point1, p, now.force[3 * k + 2]);
    }
    ctx.lineCap = "butt";
  }

  /** One strut from a[i..] to b[j..] in the force scale's colour of `force` (N). */
  function strut(view, ctx, model, a, i, b, j, force) {
    const s = forcePosition(force, model.forceScale);
    ctx.strokeStyle = model.forceLut[Math.round(((s + 1) / 2) * FORCE_LEVELS)];
    ctx.beginPath();
    segment(view, ctx, a[i], a[i + 1], a[i + 2], b[j], b[j + 1], b[j + 2]);
    ctx.stroke();
  }

  /** Footpads of engine e: discs of the pad radius parallel to the surface, filled by contact
   * state, outlined in the engine's colour. */
  function drawPads(view, ctx, model, e) {
    const now = e.now;
    ctx.strokeStyle = e.colour;
    ctx.lineWidth = 2;
    ctx.setLineDash(NO_DASH);
    for (let k = 0; k < model.nLegs; k++) {
      circle(now.pads[3 * k], now.pads[3 * k + 1], now.pads[3 * k + 2], model.padRadius[k]);
      ctx.beginPath();
      if (!polygon(view, ctx, disc, 0, DISC_SEGMENTS)) continue;
      ctx.fillStyle = CONTACT[now.contact[k]].colour;
      ctx.fill();
      ctx.stroke();
    }
  }

  /** Leg numbers (1-based) beside engine e's footpads, away from its centre of mass. */
  function drawLegNumbers(view, ctx, model, e) {
    const now = e.now, c = now.comProjection;
    if (!project(view, c[0], c[1], c[2])) return;
    const cx = px, cy = py;
    ctx.font = "600 13px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    ctx.fillStyle = "#222";
    for (let k = 0; k < model.nLegs; k++) {
      const p = now.pads;
      if (!project(view, p[3 * k], p[3 * k + 1], p[3 * k + 2])) continue;
      const x = px, y = py;
      // The disc's largest radius on screen, from two points of its rim.
      let r = 0;
      if (project(view, p[3 * k] + model.padRadius[k], p[3 * k + 1], p[3 * k + 2])) r = Math.hypot(px - x, py - y);
      if (project(view, p[3 * k], p[3 * k + 1] + model.padRadius[k], p[3 * k + 2])) r = Math.max(r, Math.hypot(px - x, py - y));
      const dx = x - cx, dy = y - cy, d = Math.hypot(dx, dy) || 1;
      ctx.fillText(String(k + 1), x + (dx / d) * (r + 14), y + (dy / d) * (r + 14));
    }
  }

  /** Axes in the bottom left corner: the surface's X and Y (the slope's plane) and gravity. */
  function drawGravityAxes(view, ctx, model) {
    const ox = 44, oy = view.height - 40, len = 26;
    const M = model.M, s = view.cameraRight, u = view.cameraUp;
    const arrow = (gx, gy, gz, label, colour) => {
      const x = ox + len * (s[0] * gx + s[1] * gy + s[2] * gz);
      const y = oy - len * (u[0] * gx + u[1] * gy + u[2] * gz);
      ctx.strokeStyle = colour;
      ctx.fillStyle = colour;
      ctx.beginPath();
      ctx.moveTo(ox, oy);
      ctx.lineTo(x, y);
      ctx.stroke();
      const d = Math.hypot(x - ox, y - oy) || 1;
      ctx.fillText(label, ox + ((x - ox) * (d + 9)) / d, oy + ((y - oy) * (d + 9)) / d);
    };
    ctx.lineWidth = 1.5;
    ctx.setLineDash(NO_DASH);
    ctx.font = "12px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    arrow(M[0][0], M[1][0], M[2][0], "x", "#666");
    arrow(M[0][1], M[1][1], M[2][1], "y", "#666");
    arrow(0, 0, -1, "g", "#000");
  }

  // ---------------------------------------------------------------- the views (3D canvases)

  const state = {
    model: null,
    time: 0,
    mode: "overlay",
    speed: SPEED_DEFAULT,
    playing: false,
    lastTick: 0,
    views: [],
    plots: [],
    secondaryLeg: 0,
    ready: false,
  };

  const $ = (id) => document.getElementById(id);

  /** Rebuilds the 3D canvases for the layout: one for every engine, or one per engine. */
  function buildViews() {
    const box = $("views");
    box.replaceChildren();
    const engines = state.model.engines;
    const groups = state.mode === "overlay" ? [engines.map((e) => e.index)] : engines.map((e) => [e.index]);
    state.views = groups.map((members, i) => {
      const wrap = document.createElement("div");
      wrap.className = "view";
      const label = document.createElement("div");
      label.className = "view-label";
      label.textContent = members.map((k) => engines[k].name).join(" · ");
      label.style.color = members.length === 1 ? engines[members[0]].colour : "";
      const canvas = document.createElement("canvas");
      canvas.id = `view-${i}`;
      canvas.setAttribute("aria-label", `3D view: ${label.textContent}`);
      wrap.append(label, canvas);
      box.append(wrap);
      const view = {
        canvas,
        ctx: canvas.getContext("2d"),
        engines: members,
        width: 1,
        height: 1,
        pixelRatio: 1,
        matrix: new Float64Array(16),
        scratch: new Float64Array(16),
        cameraRight: [1, 0, 0],
        cameraUp: [0, 0, 1],
      };
      attachOrbit(view);
      resizer.observe(canvas);
      return view;
    });
    // Side by side, each view is narrow: a lower row keeps the landers from floating in space.
    box.classList.toggle("side-by-side", groups.length > 1);
    sizeViews();
  }

  /** Matches each canvas's backing store to its CSS size and the device's pixel ratio. */
  function sizeViews() {
    const ratio = window.devicePixelRatio || 1;
    for (const v of state.views) {
      v.width = Math.max(1, v.canvas.clientWidth);
      v.height = Math.max(1, v.canvas.clientHeight);
      v.pixelRatio = ratio;
      v.canvas.width = Math.round(v.width * ratio);
      v.canvas.height = Math.round(v.height * ratio);
    }
  }

  /** Drag to orbit (azimuth, elevation), wheel to zoom, on a view's canvas. */
  function attachOrbit(view) {
    let dragging = null;
    view.canvas.addEventListener("pointerdown", (ev) => {
      dragging = { x: ev.clientX, y: ev.clientY };
      view.canvas.setPointerCapture(ev.pointerId);
    });
    view.canvas.addEventListener("pointermove", (ev) => {
      if (!dragging) return;
      camera.azimuth -= 0.008 * (ev.clientX - dragging.x);
      camera.elevation = Math.max(-0.1, Math.min(1.55, camera.elevation + 0.008 * (ev.clientY - dragging.y)));
      dragging = { x: ev.clientX, y: ev.clientY };
      requestDraw();
    });
    const stop = () => { dragging = null; };
    view.canvas.addEventListener("pointerup", stop);
    view.canvas.addEventListener("pointercancel", stop);
    view.canvas.addEventListener("wheel", (ev) => {
      ev.preventDefault();
      const radius = state.model.extent.radius;
      camera.distance = Math.max(0.3 * radius, Math.min(40 * radius, camera.distance * Math.exp(0.0012 * ev.deltaY)));
      requestDraw();
    }, { passive: false });
  }

  /** Draws every view and updates the clock, the panel and the plots' time lines, now. */
  function render() {
    const model = state.model;
    for (const e of model.engines) sample(e, state.time, model);
    for (const v of state.views) drawView(v);
    updateClock();
    updatePanel();
    updatePlotCursors();
    state.ready = true;
  }

  let drawRequested = false;
  /** Draws at the next animation frame (for camera moves). */
  function requestDraw() {
    if (drawRequested) return;
    drawRequested = true;
    requestAnimationFrame(() => {
      drawRequested = false;
      render();
    });
  }

  // ---------------------------------------------------------------- time, playback

  function setTime(t) {
    const m = state.model;
    state.time = Math.min(m.t1, Math.max(m.t0, Number(t)));
    $("slider").value = String(state.time);
    render();
  }

  function play() {
    if (state.playing) return;
    if (state.time >= state.model.t1) state.time = state.model.t0;
    state.playing = true;
    state.lastTick = performance.now();
    updatePlayButton();
    requestAnimationFrame(tick);
  }

  function pause() {
    state.playing = false;
    updatePlayButton();
  }

  /** One animation frame of playback: time moves at `speed` times real time. */
  function tick(now) {
    if (!state.playing) return;
    const dt = Math.max(0, now - state.lastTick) / 1000;
    state.lastTick = now;
    setTime(state.time + dt * state.speed);
    if (state.time >= state.model.t1) pause();
    else requestAnimationFrame(tick);
  }

  function updatePlayButton() {
    const b = $("play");
    b.textContent = state.playing ? "❚❚ Pause" : "▶ Play";
    b.setAttribute("aria-label", state.playing ? "Pause" : "Play");
  }

  function updateClock() {
    $("clock").textContent = `t = ${state.time.toFixed(4)} s / ${state.model.t1.toFixed(4)} s`;
  }

  // ---------------------------------------------------------------- side panel and legends

  /** The engines' table rows (built on load; cells updated by updatePanel). */
  function buildPanel() {
    const body = $("engines-now").tBodies[0];
    body.replaceChildren();
    for (const e of state.model.engines) {
      const row = body.insertRow();
      const name = row.insertCell();
      name.className = "engine-name";
      const sw = document.createElement("span");
      sw.className = "swatch";
      sw.style.background = e.colour;
      name.append(sw, e.name);
      name.title = `${e.name} ${e.version}: ${e.steps} steps, ${e.n} frames`;
      const outcome = row.insertCell();
      outcome.textContent = e.outcome + (e.decisionTime !== undefined ? ` at ${e.decisionTime.toFixed(3)} s` : "");
      if (e.pastCapacity.length > 0) {
        // A strut past its capacity is on its end stop, an estimated law: never simply stable.
        const past = document.createElement("div");
        past.className = "past-capacity";
        const n = e.pastCapacity.length;
        past.textContent = `${n} strut${n > 1 ? "s" : ""} past capacity`;
        past.title = e.pastCapacity
          .map((p) => `${p.strut}: ${(100 * p.stroke_of_capacity).toFixed(1)} % of its capacity, ` +
            `${(1e3 * p.past_capacity_m).toFixed(1)} mm past, stop ${(p.peak_stop_force_n / 1e3).toFixed(1)} kN`)
          .join("\n");
        outcome.append(past);
      }
      e.sdCell = row.insertCell();
      const pads = row.insertCell();
      const box = document.createElement("div");
      box.className = "pads";
      e.padCells = state.model.padRadius.map((_, k) => {
        const p = document.createElement("span");
        p.className = "pad-state";
        p.textContent = String(k + 1);
        box.append(p);
        return p;
      });
      pads.append(box);
    }
  }

  /** The panel at the current time: each engine's minimum stability distance and pad states. */
  function updatePanel() {
    for (const e of state.model.engines) {
      const now = e.now;
      if (now.minSdWall < 0) {
        e.sdCell.textContent = "—";
      } else {
        const w = e.walls[now.minSdWall].legs;
        e.sdCell.textContent = `${now.minSd.toFixed(3)} m (wall ${w[0]}–${w[1]})`;
      }
      for (let k = 0; k < e.padCells.length; k++) {
        const c = CONTACT[now.contact[k]];
        e.padCells[k].style.background = c.colour;
        e.padCells[k].title = `leg ${k + 1}: ${c.label}`;
      }
    }
  }

  /** The legends: force scale (unit and ticks from the file's largest force), contact states,
   * engines. */
  function buildLegends() {
    const model = state.model;
    const kn = model.forceScale >= 1000;
    const unit = kn ? 1000 : 1;
    $("force-unit").textContent = kn ? "kN" : "N";
    $("force-bar").style.background = `linear-gradient(to right, ${FORCE_STOPS.map(([s, c]) => `rgb(${c}) ${50 + 50 * s}%`).join(", ")})`;
    // Ticks: the full scale, and the powers of ten far enough from it and from each other.
    const magnitudes = [model.forceScale];
    for (let p = Math.pow(10, Math.floor(Math.log10(model.forceScale))); p >= model.forceScale / 1000; p /= 10) {
      const s = forcePosition(p, model.forceScale);
      if (s < 1 - FORCE_TICK_GAP && s > FORCE_TICK_GAP && s < forcePosition(magnitudes[magnitudes.length - 1], model.forceScale) - FORCE_TICK_GAP) {
        magnitudes.push(p);
      }
    }
    const ticks = $("force-ticks");
    ticks.replaceChildren();
    for (const f of [...magnitudes.map((m) => -m), 0, ...magnitudes.slice().reverse()]) {
      const span = document.createElement("span");
      span.style.left = `${50 + 50 * forcePosition(f, model.forceScale)}%`;
      span.textContent = formatTick(Math.abs(f) / unit);
      ticks.append(span);
    }
    const contact = $("contact-legend");
    contact.replaceChildren(...CONTACT.map((c) => swatchItem(c.colour, c.label, "disc")));
    $("engine-legend").replaceChildren(...model.engines.map((e) => swatchItem(e.colour, `${e.name} ${e.version}`, "")));
    // The ground's marks, those of this trajectory only, with their legs and sizes.
    const legsWith = (key) => model.ground.map((g, k) => [k + 1, g[key]]).filter(([, v]) => v > 0);
    const sizes = (list) => {
      const legsBySize = new Map();
      for (const [k, v] of list) {
        const cm = (100 * v).toFixed(1);
        legsBySize.set(cm, (legsBySize.get(cm) || []).concat(k));
      }
      return [...legsBySize].map(([cm, legs]) => `${legs.length > 1 ? "legs" : "leg"} ${legs.join(", ")}: ${cm} cm`).join("; ");
    };
    const step = model.grid.step;
    $("legend-grid").lastChild.textContent = `ground, grid lines every ${step >= 1 ? `${formatTick(step)} m` : `${formatTick(100 * step)} cm`}`;
    const holes = legsWith("hole_m"), obstacles = legsWith("obstacle_m"), spikes = legsWith("spike_depth_m");
    const curbs = model.engines.flatMap((e) => e.curbs.map((c) => c.leg));
    $("legend-hole").hidden = holes.length === 0;
    $("legend-hole").lastChild.textContent = `hole, local ground lowered (${sizes(holes)} deep)`;
    $("legend-obstacle").hidden = obstacles.length === 0;
    $("legend-obstacle").lastChild.textContent = `obstacle, locks the footpad once it touches (${sizes(obstacles)} high)`;
    $("legend-spikes").hidden = spikes.length === 0;
    $("legend-spikes").lastChild.textContent = `spikes, hold the footpad while they are in the ground (${sizes(spikes)} deep)`;
    $("legend-curb").hidden = curbs.length === 0;
    const curbLegs = [...new Set(curbs)].sort((a, b) => a - b);
    $("legend-curb").lastChild.textContent = `curb, ticks on its side (${curbLegs.length > 1 ? "legs" : "leg"} ${curbLegs.join(", ")})`;
  }

  function formatTick(v) {
    return Number.isInteger(v) ? String(v) : v.toPrecision(3).replace(/\.?0+$/, "");
  }

  function swatchItem(colour, label, kind) {
    const li = document.createElement("li");
    const sw = document.createElement("span");
    sw.className = `swatch ${kind}`;
    sw.style.background = colour;
    li.append(sw, label);
    return li;
  }

  // ---------------------------------------------------------------- linked plots (uPlot)

  /** The three plots: primary strokes of every leg, secondary strokes of one leg, pitch rate;
   * one series per engine (and leg), engines by colour, legs by dash. */
  function buildPlots() {
    for (const p of state.plots) p.destroy();
    const model = state.model;
    const legSelect = $("secondary-leg");
    legSelect.replaceChildren(...model.padRadius.map((_, k) => new Option(String(k + 1), String(k))));
    state.secondaryLeg = Math.min(state.secondaryLeg, model.nLegs - 1);
    legSelect.value = String(state.secondaryLeg);
    state.plots = [
      makePlot($("plot-primary"), "stroke (mm)", primarySeries(model)),
      makePlot($("plot-secondary"), "stroke (mm)", secondarySeries(model, state.secondaryLeg)),
      makePlot($("plot-pitch"), "pitch rate (rad/s)", pitchSeries(model)),
    ];
  }

  /** Primary strokes, mm, per engine per leg. */
  function primarySeries(model) {
    return model.engines.map((e) => ({
      engine: e,
      columns: e.frames.legs.map((leg, k) => ({
        label: `${e.name} leg ${k + 1}`,
        dash: LEG_DASHES[k % LEG_DASHES.length],
        values: leg.primary_stroke_m.map((v) => 1000 * v),
      })),
    }));
  }

  /** The two secondary strokes of leg k, mm, per engine. */
  function secondarySeries(model, k) {
    return model.engines.map((e) => ({
      engine: e,
      columns: [
        { label: `${e.name} sec. 31`, dash: LEG_DASHES[0], values: e.frames.legs[k].sec31_stroke_m.map((v) => 1000 * v) },
        { label: `${e.name} sec. 41`, dash: LEG_DASHES[1], values: e.frames.legs[k].sec41_stroke_m.map((v) => 1000 * v) },
      ],
    }));
  }

  /** Pitch rate, rad/s (the unit of the summary and history.csv), per engine. */
  function pitchSeries(model) {
    return model.engines.map((e) => ({
      engine: e,
      columns: [{ label: e.name, dash: LEG_DASHES[0], values: e.frames.pitch_rate_rad_s }],
    }));
  }

  /** A uPlot chart in `box` of `groups` (per engine: its columns over its own times, joined on
   * one time axis), with a line at the current time; a click goes to the clicked time. */
  function makePlot(box, yLabel, groups) {
    box.replaceChildren();
    const model = state.model;
    const data = uPlot.join(groups.map((g) => [Array.from(g.engine.t), ...g.columns.map((c) => c.values)]));
    const series = [{ label: "t (s)", value: (u, v) => (v == null ? "–" : v.toFixed(4)) }];
    for (const g of groups) {
      for (const c of g.columns) {
        series.push({
          label: c.label,
          stroke: g.engine.colour,
          width: 1.5,
          dash: c.dash,
          spanGaps: true,
          points: { show: false },
          value: (u, v) => (v == null ? "–" : v.toFixed(2)),
        });
      }
    }
    resizer.observe(box);
    const plot = new uPlot({
      width: plotWidth(box),
      height: PLOT_HEIGHT,
      scales: { x: { time: false, range: () => [model.t0, model.t1] } },
      axes: [{ label: "t (s)" }, { label: yLabel }],
      series,
      cursor: { sync: { key: "touchdown" }, drag: { x: false, y: false } },
      legend: { live: true },
    }, data, box);
    const line = document.createElement("div");
    line.className = "now-line";
    plot.over.append(line);
    plot.nowLine = line;
    plot.over.addEventListener("click", (ev) => {
      const x = ev.clientX - plot.over.getBoundingClientRect().left;
      pause();
      setTime(plot.posToVal(x, "x"));
    });
    return plot;
  }

  function plotWidth(box) {
    return Math.max(240, box.clientWidth);
  }

  /** Moves every plot's time line to the current time. */
  function updatePlotCursors() {
    for (const p of state.plots) {
      p.nowLine.style.transform = `translateX(${p.valToPos(state.time, "x")}px)`;
    }
  }

  // ---------------------------------------------------------------- loading

  /** Replaces the trajectory by `doc` and draws it at its first time. */
  function load(doc) {
    const model = buildModel(doc);
    state.ready = false;
    pause();
    state.model = model;
    $("scenario-name").textContent = model.name;
    document.title = `${model.name} — Touchdown`;
    const sc = doc.scenario || {};
    $("source").textContent = [
      sc.path,
      `${model.engines.length} engine${model.engines.length > 1 ? "s" : ""}`,
      `slope ${((doc.surface.slope_rad * 180) / Math.PI).toFixed(1)}°`,
      doc.surface.soil ? "soil" : "rigid ground",
      doc.touchdown_version && `touchdown ${doc.touchdown_version}`,
    ].filter(Boolean).join(" · ");
    const slider = $("slider");
    slider.min = String(model.t0);
    slider.max = String(model.t1);
    buildViews();
    resetCamera();
    buildPanel();
    buildLegends();
    buildPlots();
    setTime(model.t0);
  }

  /** The file picker: reads the chosen file and loads it; a bad file is reported in the page. */
  async function openFile(file) {
    const status = $("status");
    status.textContent = `Reading ${file.name}…`;
    state.ready = false;
    try {
      load(JSON.parse(await file.text()));
      status.textContent = "";
    } catch (err) {
      status.textContent = `Could not open ${file.name}: ${err.message}`;
      state.ready = state.model !== null;
    }
  }

  // ---------------------------------------------------------------- controls

  function attachControls() {
    $("play").addEventListener("click", () => (state.playing ? pause() : play()));
    $("slider").addEventListener("input", (ev) => {
      pause();
      setTime(parseFloat(ev.target.value));
    });
    $("speed").addEventListener("change", (ev) => {
      state.speed = parseFloat(ev.target.value);
    });
    for (const radio of document.querySelectorAll('input[name="layout"]')) {
      radio.addEventListener("change", (ev) => setMode(ev.target.value));
    }
    $("reset-camera").addEventListener("click", () => {
      resetCamera();
      render();
    });
    $("open-file").addEventListener("change", (ev) => {
      const file = ev.target.files[0];
      ev.target.value = "";
      if (file) openFile(file);
    });
    $("secondary-leg").addEventListener("change", (ev) => {
      state.secondaryLeg = Number(ev.target.value);
      state.plots[1].destroy();
      state.plots[1] = makePlot($("plot-secondary"), "stroke (mm)", secondarySeries(state.model, state.secondaryLeg));
      updatePlotCursors();
    });
  }

  /** Canvases and plots follow their boxes' sizes (the window's, a scroll bar's). */
  const resizer = new ResizeObserver(() => {
    const stale = state.views.some((v) => v.canvas.clientWidth !== v.width || v.canvas.clientHeight !== v.height);
    if (stale) sizeViews();
    for (const p of state.plots) {
      const width = plotWidth(p.root.parentElement);
      if (width !== p.width) p.setSize({ width, height: PLOT_HEIGHT });
    }
    if (stale) render();
  });

  function setMode(m) {
    if (m !== "overlay" && m !== "side-by-side") throw new Error(`mode: "overlay" or "side-by-side", not ${m}`);
    state.mode = m;
    for (const radio of document.querySelectorAll('input[name="layout"]')) radio.checked = radio.value === m;
    buildViews();
    render();
  }

  // ---------------------------------------------------------------- automation API

  window.touchdownView = {
    get ready() { return state.ready; },
    time: () => state.time,
    setTime,
    timeRange: () => [state.model.t0, state.model.t1],
    mode(m) {
      if (m !== undefined) setMode(m);
      return state.mode;
    },
    play,
    pause,
    playing: () => state.playing,
    scenarioName: () => state.model.name,
    camera(e) {
      const view = state.views.find((v) => v.engines.includes(e));
      if (!view) throw new Error(`no engine ${e}`);
      updateMatrix(view);
      return {
        canvasId: view.canvas.id,
        matrix: Array.from(view.matrix),
        width: view.width,
        height: view.height,
        devicePixelRatio: view.pixelRatio,
      };
    },
    contactColours: CONTACT.map((c) => c.colour),
    load,
  };

  attachControls();
  load(JSON.parse($("trajectory").textContent));
})();
