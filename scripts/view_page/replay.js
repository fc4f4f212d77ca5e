// The cranesim replay viewer, inlined by scripts/view.py into a page after three.js (r111),
// its OrbitControls and its Lut (colour map). The data (JSON in #cranesim-data) holds per frame
// the positions of all points (body origins, then joints) and the bodies' rotation matrices, as
// base64 float32; for a modes file the equilibrium and the mode shapes, for a plan file also the
// planned path. All 3-D math is three.js': cameras, controls, projection, quaternions, instance
// matrices, colour map.
//
// For people and tests, #status carries the state: data-state ("ready" or "error", then
// data-error), data-t, data-frame, data-load-world "x,y,z", data-load-px "x,y" (the load's
// position on the page, in CSS pixels from the page's top left, by Vector3.project),
// data-view-matrix and data-projection-matrix (column-major, as three.js stores them),
// data-canvas "left,top,width,height", data-force-range, data-planned-world, data-obstacles (the
// obstacle meshes' names), data-ready-ms,
// data-bench-fps; document.title starts with "cranesim replay: ready".
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("cranesim-data").textContent);
  var status = document.getElementById("status");

  function decode(text) {
    var binary = atob(text), bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return new Float32Array(bytes.buffer);
  }
  function fail(message) {
    throw new Error(message);
  }

  var times = decode(data.time);
  var frames = times.length, pointCount = data.point_count, bodyCount = data.body_names.length;
  var points = decode(data.points);                // frames × points × 3
  var rotations = decode(data.rotations);          // frames × bodies × 9, row-major
  var t0 = times[0], t1 = times[frames - 1];
  var size = data.size;
  var current = new Float32Array(pointCount * 3);  // the points at the shown time
  // A modes file: the equilibrium (as two equal frames) and the mode shapes, each scaled so
  // its largest joint displacement is 1; the time runs over one cycle of the chosen mode.
  var modes = data.kind === "modes" ? data.modes : null;
  var shapes = modes ? decode(modes.shapes) : null;
  var modeIndex = 0, amplitude = modes ? modes.amplitude : 0;

  // ---- scene, camera, renderer --------------------------------------------------------------
  var view = document.getElementById("view");
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (error) {
    fail("WebGL is not available in this browser: " + ((error && error.message) || error));
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xeef2f6);
  view.insertBefore(renderer.domElement, view.firstChild);

  var up = new THREE.Vector3().fromArray(data.up);
  THREE.Object3D.DefaultUp.copy(up);
  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(40, 1, size * 1e-3, size * 100);
  camera.up.copy(up);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;

  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 0.75));
  var sun = new THREE.DirectionalLight(0xffffff, 0.55);
  sun.position.copy(up).multiplyScalar(2).add(new THREE.Vector3(1, -0.7, 0)).multiplyScalar(size);
  scene.add(sun);

  var low = new THREE.Vector3().fromArray(data.bounds[0]);
  var high = new THREE.Vector3().fromArray(data.bounds[1]);
  var centre = low.clone().add(high).multiplyScalar(0.5);

  // Ground grid at the lowest point of the run (or the origin's level), spacing `grid_spacing`.
  var spacing = data.grid_spacing;
  var groundLevel = Math.min(0, low.dot(up));
  var extent = Math.max(high.x - low.x, high.y - low.y, high.z - low.z, spacing);
  var divisions = Math.max(2, 2 * Math.ceil(0.75 * extent / spacing));
  var grid = new THREE.GridHelper(divisions * spacing, divisions, 0x8896a8, 0xc4ccd6);
  grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
  var gridCentre = centre.clone().sub(up.clone().multiplyScalar(centre.dot(up)));
  gridCentre.set(Math.round(gridCentre.x / spacing) * spacing, Math.round(gridCentre.y / spacing) * spacing,
                 Math.round(gridCentre.z / spacing) * spacing);
  grid.position.copy(gridCentre).add(up.clone().multiplyScalar(groundLevel));
  scene.add(grid);
  var axes = new THREE.AxesHelper(spacing);  // at the origin
  scene.add(axes);
  document.getElementById("scale-line").textContent =
    "grid " + spacing + " m · axes at the origin: x red, y green, z blue, " + spacing + " m long";

  // ---- the mechanism ------------------------------------------------------------------------
  var bodyColours = [0x1f77b4, 0x2ca02c, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22,
                     0x7f7f7f];
  var unitY = new THREE.Vector3(0, 1, 0);
  var a = new THREE.Vector3(), b = new THREE.Vector3(), direction = new THREE.Vector3();
  var quaternion = new THREE.Quaternion(), scale = new THREE.Vector3();
  var matrix = new THREE.Matrix4();

  // A set of straight tubes between points, one instanced cylinder each.
  function TubeSet(ends, radii, colour) {
    var geometry = new THREE.CylinderBufferGeometry(1, 1, 1, 10, 1, false);
    var material = new THREE.MeshLambertMaterial({ color: colour });
    this.mesh = new THREE.InstancedMesh(geometry, material, ends.length);
    this.mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.mesh.frustumCulled = false;
    this.ends = ends;
    this.radii = radii;
    scene.add(this.mesh);
  }
  TubeSet.prototype.update = function () {
    for (var k = 0; k < this.ends.length; k++) {
      a.fromArray(current, 3 * this.ends[k][0]);
      b.fromArray(current, 3 * this.ends[k][1]);
      direction.subVectors(b, a);
      var length = direction.length();
      if (length > 0) quaternion.setFromUnitVectors(unitY, direction.divideScalar(length));
      scale.set(this.radii[k], Math.max(length, 1e-9), this.radii[k]);
      matrix.compose(a.add(b).multiplyScalar(0.5), quaternion, scale);
      this.mesh.setMatrixAt(k, matrix);
    }
    this.mesh.instanceMatrix.needsUpdate = true;
  };

  var tubeSets = [];
  // Bodies: their skeleton (origin → each joint), one colour per body.
  for (var body = 0; body < bodyCount; body++) {
    var ends = data.skeleton.filter(function (s) { return s[2] === body; });
    if (ends.length) {
      tubeSets.push(new TubeSet(ends, ends.map(function () { return 0.004 * size; }),
                                bodyColours[body % bodyColours.length]));
    }
  }
  // Ropes and strut ties may be coloured by the force at their ends (data.member_forces:
  // frames × members, N), through three.js' colour map (Lut) from its minimum to its maximum.
  var memberForces = data.member_forces || null, forceValues = null, lut = null;
  var forceNow = [], colourByForce = !!memberForces;
  var plainTube = new THREE.Color(0x6b7480), plainRope = new THREE.Color(0x202020);
  if (memberForces) {
    forceValues = decode(memberForces.values);
    lut = new THREE.Lut("rainbow", 256);
    var range = memberForces.range;
    lut.setMin(range[0]);
    lut.setMax(range[1] > range[0] ? range[1] : range[0] + 1);
  }
  function forceColour(member, plain) {
    return colourByForce && member >= 0 ? lut.getColor(forceNow[member]) : plain;
  }

  // Flexible members other than ropes: tubes of their section's radius (at least 0.15 % of the
  // scene, so a 10 cm tube on a 100 m crane stays visible); one set per coloured member.
  var memberTubeSets = [];
  var tubeGroups = {};
  data.tubes.forEach(function (s) { (tubeGroups[s[3]] = tubeGroups[s[3]] || []).push(s); });
  Object.keys(tubeGroups).forEach(function (key) {
    var group = tubeGroups[key];
    var set = new TubeSet(group, group.map(function (s) { return Math.max(s[2], 0.0015 * size); }),
                          0x6b7480);
    tubeSets.push(set);
    if (+key >= 0) memberTubeSets.push({ set: set, member: +key });
  });
  // Ropes: lines through their nodes.
  var ropePositions = new Float32Array(data.ropes.length * 6);
  var ropeColours = new Float32Array(data.ropes.length * 6);
  var ropeGeometry = new THREE.BufferGeometry();
  ropeGeometry.setAttribute("position",
                            new THREE.BufferAttribute(ropePositions, 3).setUsage(THREE.DynamicDrawUsage));
  ropeGeometry.setAttribute("color",
                            new THREE.BufferAttribute(ropeColours, 3).setUsage(THREE.DynamicDrawUsage));
  var ropes = new THREE.LineSegments(ropeGeometry,
                                     new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
  ropes.frustumCulled = false;
  scene.add(ropes);
  function colourMembers(frame, next, w) {
    if (memberForces) {
      var count = memberForces.members.length;
      for (var m = 0; m < count; m++) {
        forceNow[m] = (1 - w) * forceValues[frame * count + m] + w * forceValues[next * count + m];
      }
    }
    memberTubeSets.forEach(function (entry) {
      entry.set.mesh.material.color.copy(forceColour(entry.member, plainTube));
    });
    data.ropes.forEach(function (s, k) {
      var colour = forceColour(s[2], plainRope);
      colour.toArray(ropeColours, 6 * k);
      colour.toArray(ropeColours, 6 * k + 3);
    });
    ropeGeometry.attributes.color.needsUpdate = true;
  }

  // Ground joints: small dark blocks.
  var groundGeometry = new THREE.BoxBufferGeometry(1, 1, 1);
  var groundMaterial = new THREE.MeshLambertMaterial({ color: 0x5a4630 });
  var groundBlocks = data.ground_points.map(function (p) {
    var block = new THREE.Mesh(groundGeometry, groundMaterial);
    block.scale.setScalar(0.012 * size);
    scene.add(block);
    return { mesh: block, point: p };
  });

  // Inertia boxes: the uniform box of each body's mass and inertia, about its centroid.
  var boxes = [];
  data.boxes.forEach(function (box, i) {
    if (!box) return;
    var geometry = new THREE.BoxBufferGeometry(box.edges[0], box.edges[1], box.edges[2]);
    var placement = new THREE.Matrix4().set(
      box.axes[0][0], box.axes[0][1], box.axes[0][2], box.centroid[0],
      box.axes[1][0], box.axes[1][1], box.axes[1][2], box.centroid[1],
      box.axes[2][0], box.axes[2][1], box.axes[2][2], box.centroid[2],
      0, 0, 0, 1);
    geometry.applyMatrix(placement);
    var material = new THREE.MeshLambertMaterial({
      color: bodyColours[i % bodyColours.length], transparent: true, opacity: 0.35, depthWrite: false });
    var mesh = new THREE.Mesh(geometry, material);
    mesh.matrixAutoUpdate = false;
    scene.add(mesh);
    boxes.push({ mesh: mesh, body: i });
  });

  // The load: a marker drawn over everything, its whole path faint and its path so far strong.
  var load = data.load;
  var loadMarker = null, traceAll = null, tracePast = null;
  var loadColour = 0xe4572e, traceColour = 0x7a3db8;
  if (load >= 0) {
    loadMarker = new THREE.Mesh(new THREE.SphereBufferGeometry(0.012 * size, 20, 14),
                                new THREE.MeshBasicMaterial({ color: loadColour, depthTest: false }));
    loadMarker.renderOrder = 10;
    scene.add(loadMarker);
    var path = new Float32Array(frames * 3);
    for (var f = 0; f < frames; f++) {
      for (var c = 0; c < 3; c++) path[3 * f + c] = points[(f * pointCount + load) * 3 + c];
    }
    var pathAttribute = new THREE.BufferAttribute(path, 3);
    var allGeometry = new THREE.BufferGeometry();
    allGeometry.setAttribute("position", pathAttribute);
    traceAll = new THREE.Line(allGeometry, new THREE.LineBasicMaterial(
      { color: traceColour, transparent: true, opacity: 0.3 }));
    var pastGeometry = new THREE.BufferGeometry();
    pastGeometry.setAttribute("position", pathAttribute);
    tracePast = new THREE.Line(pastGeometry, new THREE.LineBasicMaterial({ color: traceColour }));
    scene.add(traceAll, tracePast);
  }

  // A plan: the planned end-point path (dashed), the simulated one (green), start (green block),
  // target (black block) and the planned end point now (a black marker drawn over everything).
  var plan = data.plan || null, plannedMarker = null, planned = null, obstacleMeshes = [];
  if (plan) {
    var pathLine = function (values, material) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.BufferAttribute(decode(values), 3));
      var line = new THREE.Line(geometry, material);
      line.computeLineDistances();
      scene.add(line);
      return line;
    };
    pathLine(plan.planned_path, new THREE.LineDashedMaterial(
      { color: 0x000000, dashSize: 0.01 * size, gapSize: 0.006 * size }));
    pathLine(plan.simulated_path, new THREE.LineBasicMaterial({ color: 0x2ca02c }));
    [[plan.start, 0x2ca02c], [plan.target, 0x111111]].forEach(function (end) {
      var block = new THREE.Mesh(new THREE.BoxBufferGeometry(1, 1, 1),
                                 new THREE.MeshLambertMaterial({ color: end[1] }));
      block.scale.setScalar(0.012 * size);
      block.position.fromArray(end[0]);
      scene.add(block);
    });
    // The target's obstacles, translucent: red when the verified motion came closer than the
    // margin, orange the one it came closest to, grey the others.
    (plan.obstacles || []).forEach(function (o) {
      var geometry, zAxis = new THREE.Vector3(0, 0, 1);
      if (o.shape === "box") {
        geometry = new THREE.BoxBufferGeometry(o.size[0], o.size[1], o.size[2]);
        geometry.applyMatrix(new THREE.Matrix4().makeRotationZ(o.yaw));
        geometry.translate(o.centre[0], o.centre[1], o.centre[2]);
      } else if (o.shape === "cylinder") {
        geometry = new THREE.CylinderBufferGeometry(o.radius, o.radius, o.height, 48);
        geometry.applyMatrix(new THREE.Matrix4().makeRotationFromQuaternion(
          new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), zAxis)));
        geometry.translate(o.base[0], o.base[1], o.base[2] + 0.5 * o.height);
      } else {
        var outline = new THREE.Shape(o.footprint.map(function (p) { return new THREE.Vector2(p[0], p[1]); }));
        geometry = new THREE.ExtrudeBufferGeometry(outline, { depth: o.top - o.bottom, bevelEnabled: false });
        geometry.translate(0, 0, o.bottom);
      }
      var c = plan.clearance, colour = 0x8c8c8c;
      if (c && o.name === c.closest_obstacle) colour = c.status === "failed" ? 0xd62728 : 0xff7f0e;
      var mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial(
        { color: colour, transparent: true, opacity: 0.3, depthWrite: false }));
      mesh.name = "obstacle " + o.name;
      scene.add(mesh);
      obstacleMeshes.push(mesh);
    });
    planned = decode(plan.planned);
    plannedMarker = new THREE.Mesh(new THREE.SphereBufferGeometry(0.008 * size, 16, 12),
                                   new THREE.MeshBasicMaterial({ color: 0x111111, depthTest: false }));
    plannedMarker.renderOrder = 11;
    scene.add(plannedMarker);
  }

  // ---- the state at a time ------------------------------------------------------------------
  var state = { t: t0, frame: 0, playing: false, speed: 1, follow: false };
  var qa = new THREE.Quaternion(), qb = new THREE.Quaternion(), rotation = new THREE.Matrix4();
  var origin = new THREE.Vector3(), followed = new THREE.Vector3();

  function frameAt(t) {  // the frame at or before t, and the fraction to the next one
    var lo = 0, hi = frames - 1;
    if (t <= times[0]) return [0, 0];
    if (t >= times[hi]) return [hi, 0];
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    return [lo, (t - times[lo]) / (times[lo + 1] - times[lo])];
  }
  function bodyQuaternion(frame, i, target) {
    var r = rotations, o = (frame * bodyCount + i) * 9;
    rotation.set(r[o], r[o + 1], r[o + 2], 0, r[o + 3], r[o + 4], r[o + 5], 0,
                 r[o + 6], r[o + 7], r[o + 8], 0, 0, 0, 0, 1);
    return target.setFromRotationMatrix(rotation);
  }

  function setTime(t) {
    state.t = Math.min(Math.max(t, t0), t1);
    var at = frameAt(state.t), frame = at[0], w = at[1];
    var next = Math.min(frame + 1, frames - 1);
    state.frame = w < 0.5 ? frame : next;
    var base = frame * pointCount * 3, nextBase = next * pointCount * 3;
    for (var i = 0; i < pointCount * 3; i++) {
      current[i] = (1 - w) * points[base + i] + w * points[nextBase + i];
    }
    if (modes) {
      var deflection = amplitude * Math.sin(2 * Math.PI * (state.t - t0) / (t1 - t0));
      var offset = modeIndex * pointCount * 3;
      for (var j = 0; j < pointCount * 3; j++) current[j] += deflection * shapes[offset + j];
    }
    tubeSets.forEach(function (set) { set.update(); });
    data.ropes.forEach(function (s, k) {
      for (var c = 0; c < 3; c++) {
        ropePositions[6 * k + c] = current[3 * s[0] + c];
        ropePositions[6 * k + 3 + c] = current[3 * s[1] + c];
      }
    });
    ropeGeometry.attributes.position.needsUpdate = true;
    colourMembers(frame, next, w);
    groundBlocks.forEach(function (g) { g.mesh.position.fromArray(current, 3 * g.point); });
    if (plannedMarker) {
      a.fromArray(planned, 3 * frame);
      plannedMarker.position.fromArray(planned, 3 * next).sub(a).multiplyScalar(w).add(a);
    }
    boxes.forEach(function (box) {
      bodyQuaternion(frame, box.body, qa);
      bodyQuaternion(next, box.body, qb);
      qa.slerp(qb, w);
      origin.fromArray(current, 3 * box.body);
      box.mesh.matrix.compose(origin, qa, scale.set(1, 1, 1));
    });
    if (loadMarker) {
      var previous = followed.copy(loadMarker.position);
      loadMarker.position.fromArray(current, 3 * load);
      tracePast.geometry.setDrawRange(0, frame + 1);
      if (state.follow) {  // keep the camera's offset from the load
        var shift = loadMarker.position.clone().sub(previous);
        camera.position.add(shift);
        controls.target.add(shift);
        controls.update();
      }
    }
    slider.value = String(state.t);
    clock.textContent = modes ? "phase " + state.t.toFixed(2) + " of a cycle"
                              : "t = " + state.t.toFixed(2) + " s / " + t1.toFixed(2) + " s";
    plots.forEach(function (plot) { plot.cursor(state.t); });
    needsRender = true;
  }

  // ---- URL fragment: t, camera, follow, speed -----------------------------------------------
  function readHash() {
    var values = {};
    location.hash.replace(/^#/, "").split("&").forEach(function (pair) {
      var kv = pair.split("=");
      if (kv[0]) values[decodeURIComponent(kv[0])] = decodeURIComponent(kv[1] || "");
    });
    return values;
  }
  function writeHash() {
    var p = camera.position, q = controls.target;
    var numbers = [p.x, p.y, p.z, q.x, q.y, q.z].map(function (v) { return +v.toPrecision(6); });
    var hash = "#t=" + +state.t.toFixed(4) + "&cam=" + numbers.join(",");
    if (state.follow) hash += "&follow=1";
    if (modes) hash += "&mode=" + (modeIndex + 1) + "&amp=" + +amplitude.toPrecision(4);
    if (state.speed !== 1) hash += "&speed=" + state.speed;
    if (fixedSize) hash += "&size=" + fixedSize[1] + "x" + fixedSize[2];
    if (history.replaceState) history.replaceState(null, "", hash);
  }
  function defaultCamera() {
    var radius = Math.max(0.5 * size, 1e-6);
    var distance = radius / Math.sin(THREE.MathUtils ? THREE.MathUtils.degToRad(camera.fov / 2)
                                                     : THREE.Math.degToRad(camera.fov / 2));
    var side = new THREE.Vector3(0.55, -1, 0);  // from the front right, a little above
    if (Math.abs(up.z) < 0.99) side.sub(up.clone().multiplyScalar(side.dot(up)));
    side.normalize().add(up.clone().multiplyScalar(0.35)).normalize();
    camera.position.copy(centre).add(side.multiplyScalar(1.15 * distance));
    controls.target.copy(centre);
    controls.update();
  }
  function applyHash() {
    var values = readHash();
    var cam = (values.cam || "").split(",").map(Number);
    if (cam.length === 6 && cam.every(isFinite)) {
      camera.position.set(cam[0], cam[1], cam[2]);
      controls.target.set(cam[3], cam[4], cam[5]);
      controls.update();
    }
    state.follow = values.follow === "1";
    if (modes) {
      var mode = Math.round(+values.mode);
      if (mode >= 1 && mode <= modes.frequency.length) modeIndex = mode - 1;
      if (values.amp !== undefined && isFinite(+values.amp) && +values.amp >= 0) amplitude = +values.amp;
      showMode();
    }
    followBox.checked = state.follow;
    if (values.speed && isFinite(+values.speed) && +values.speed > 0) {
      state.speed = +values.speed;
      speedSelect.value = String(state.speed);
    }
    var following = state.follow;
    state.follow = false;               // a time from the link does not move the linked camera
    if (loadMarker) loadMarker.position.fromArray(points, 3 * load);
    setTime(values.t !== undefined && isFinite(+values.t) ? +values.t : t0);
    state.follow = following;
    if (state.follow && loadMarker && cam.length !== 6) centreOnLoad();
  }
  function centreOnLoad() {  // look at the load from where the camera looks now
    var shift = loadMarker.position.clone().sub(controls.target);
    camera.position.add(shift);
    controls.target.add(shift);
    controls.update();
  }

  // ---- side plots ---------------------------------------------------------------------------
  var plotColours = ["#d62728", "#2ca02c", "#1f77b4", "#9467bd", "#ff7f0e", "#8c564b"];
  function Plot(spec) {
    var heading = document.createElement("h2");
    heading.textContent = spec.title + " [" + spec.unit + "]";
    this.canvas = document.createElement("canvas");
    var ratio = window.devicePixelRatio || 1;
    this.ratio = ratio;
    this.curves = spec.curves.map(function (c, k) {
      return { label: c.label, values: decode(c.values), dashed: !!c.dashed,
               colour: plotColours[(c.colour !== undefined ? c.colour : k) % plotColours.length] };
    });
    // The legend below the time axis, in as many lines as its labels need.
    var measure = this.canvas.getContext("2d"), x = 58, line = 0;
    measure.font = "10px system-ui, sans-serif";
    this.curves.forEach(function (curve) {
      var width = measure.measureText(curve.label).width;
      if (x > 58 && x + width > 318) { x = 58; line++; }
      curve.legend = [x, line];
      x += width + 10;
    });
    var height = 160 + 14 * line;
    this.canvas.width = 320 * ratio;
    this.canvas.height = height * ratio;
    this.canvas.style.height = height + "px";
    document.getElementById("plots").append(heading, this.canvas);
    var lo = Infinity, hi = -Infinity;
    this.curves.forEach(function (c) {
      c.values.forEach(function (v) { if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
    });
    if (!(hi > lo)) { var mid = isFinite(lo) ? lo : 0; lo = mid - 1; hi = mid + 1; }
    var pad = 0.06 * (hi - lo);
    this.lo = lo - pad; this.hi = hi + pad;
    this.box = { left: 58, right: 312, top: 6, bottom: 128 };
    this.background = document.createElement("canvas");
    this.background.width = this.canvas.width;
    this.background.height = this.canvas.height;
    this.draw(this.background.getContext("2d"));
    var plot = this;
    this.canvas.addEventListener("click", function (event) {
      var rect = plot.canvas.getBoundingClientRect();
      var x = (event.clientX - rect.left) * 320 / rect.width;
      pause();
      setTime(t0 + (x - plot.box.left) / (plot.box.right - plot.box.left) * (t1 - t0));
      writeHash();
    });
  }
  Plot.prototype.x = function (t) {
    return this.box.left + (t - t0) / ((t1 - t0) || 1) * (this.box.right - this.box.left);
  };
  Plot.prototype.y = function (v) {
    return this.box.bottom - (v - this.lo) / (this.hi - this.lo) * (this.box.bottom - this.box.top);
  };
  Plot.prototype.draw = function (g) {
    var box = this.box, plot = this;
    g.setTransform(this.ratio, 0, 0, this.ratio, 0, 0);
    g.fillStyle = "#fff";
    g.fillRect(box.left, box.top, box.right - box.left, box.bottom - box.top);
    g.strokeStyle = "#999";
    g.strokeRect(box.left, box.top, box.right - box.left, box.bottom - box.top);
    g.fillStyle = "#444";
    g.font = "10px system-ui, sans-serif";
    g.textAlign = "right";
    [this.hi, (this.hi + this.lo) / 2, this.lo].forEach(function (v) {
      g.fillText(formatNumber(v), box.left - 4, plot.y(v) + 3);
    });
    g.textAlign = "center";
    g.fillText(formatNumber(t0) + " s", box.left, box.bottom + 12);
    g.fillText(formatNumber(t1) + " s", box.right - 8, box.bottom + 12);
    this.curves.forEach(function (curve) {
      g.strokeStyle = curve.colour;
      g.lineWidth = 1.3;
      g.setLineDash(curve.dashed ? [5, 3] : []);
      g.beginPath();
      for (var i = 0; i < frames; i++) {
        var px = plot.x(times[i]), py = plot.y(curve.values[i]);
        if (i === 0) g.moveTo(px, py); else g.lineTo(px, py);
      }
      g.stroke();
    });
    g.setLineDash([]);
    g.textAlign = "left";
    this.curves.forEach(function (curve) {
      g.fillStyle = curve.colour;
      g.fillText(curve.label, curve.legend[0], box.bottom + 26 + 14 * curve.legend[1]);
    });
  };
  Plot.prototype.cursor = function (t) {
    var g = this.canvas.getContext("2d");
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.clearRect(0, 0, this.canvas.width, this.canvas.height);
    g.drawImage(this.background, 0, 0);
    g.setTransform(this.ratio, 0, 0, this.ratio, 0, 0);
    g.strokeStyle = "#000";
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(this.x(t), this.box.top);
    g.lineTo(this.x(t), this.box.bottom);
    g.stroke();
  };
  function formatNumber(v) {
    var m = Math.abs(v);
    return m !== 0 && (m >= 1e5 || m < 1e-2) ? v.toExponential(2) : (+v.toPrecision(4)).toString();
  }

  // ---- controls -----------------------------------------------------------------------------
  var slider = document.getElementById("slider"), clock = document.getElementById("clock");
  var playButton = document.getElementById("play"), speedSelect = document.getElementById("speed");
  var followBox = document.getElementById("follow"), boxesBox = document.getElementById("boxes");
  var traceBox = document.getElementById("trace");
  var needsRender = true;
  slider.min = String(t0);
  slider.max = String(t1);
  slider.step = String((t1 - t0) / Math.max(1000, 4 * frames) || 1);
  var plots = data.series.map(function (spec) { return new Plot(spec); });

  // ---- modes: which mode, how large; a table of all modes ------------------------------------
  var modeSelect = null, amplitudeInput = null, amplitudeText = null, modeRows = [];
  function modeName(k) {
    var f = modes.frequency[k];
    return Math.abs(f) < 1e-9 || (modes.rigid_modes && k < modes.rigid_modes && Math.abs(f) < 1e-3)
      ? "rigid" : formatNumber(f) + " Hz";
  }
  function energyShares(k, limit) {  // "load 99.7 %, flexible members 0.3 %" (shares ≥ 0.05 %)
    var shares = modes.energy_shares ? modes.energy_shares[k] : null;
    if (!shares) return "";
    return shares.filter(function (part) { return part[1] >= 5e-4; }).slice(0, limit || 99)
      .map(function (part) {
        var name = limit && part[0] === "flexible members" ? "members" : part[0];  // table: short
        return name + " " + (100 * part[1]).toFixed(1) + " %";
      }).join(", ");
  }
  function showMode() {
    if (!modes) return;
    modeSelect.value = String(modeIndex);
    amplitudeInput.value = String(amplitude);
    amplitudeText.textContent = formatNumber(amplitude) + " m";
    modeRows.forEach(function (row, k) { row.style.background = k === modeIndex ? "#dde8f6" : ""; });
    var f = modes.frequency[modeIndex];
    document.getElementById("scale-line").textContent =
      "mode " + (modeIndex + 1) + ": " + modeName(modeIndex) +
      (f > 0 ? " (period " + formatNumber(1 / f) + " s)" : f < 0 ? " (unstable: ω² < 0)" : "") +
      " · one cycle per second at speed 1 · the joint that moves most moves " +
      formatNumber(amplitude) + " m · grid " + spacing + " m" +
      (modes.energy_shares ? " · kinetic energy: " + energyShares(modeIndex) : "");
    setTime(state.t);
  }
  if (modes) {
    var bar = document.getElementById("controls"), speedLabel = document.getElementById("speed").parentNode;
    var modeLabel = document.createElement("label");
    modeLabel.textContent = "mode ";
    modeSelect = document.createElement("select");
    modeSelect.id = "mode";
    modes.frequency.forEach(function (f, k) {
      var option = document.createElement("option");
      option.value = String(k);
      option.textContent = (k + 1) + ": " + modeName(k);
      modeSelect.append(option);
    });
    modeLabel.append(modeSelect);
    var amplitudeLabel = document.createElement("label");
    amplitudeLabel.textContent = "amplitude ";
    amplitudeInput = document.createElement("input");
    amplitudeInput.type = "range";
    amplitudeInput.id = "amplitude";
    amplitudeInput.min = "0";
    amplitudeInput.max = String(0.25 * size);
    amplitudeInput.step = String(0.0025 * size);
    amplitudeText = document.createElement("span");
    amplitudeLabel.append(amplitudeInput, " ", amplitudeText);
    bar.insertBefore(modeLabel, speedLabel);
    bar.insertBefore(amplitudeLabel, speedLabel);
    modeSelect.addEventListener("change", function () { modeIndex = +modeSelect.value; showMode(); writeHash(); });
    amplitudeInput.addEventListener("input", function () { amplitude = +amplitudeInput.value; showMode(); });
    amplitudeInput.addEventListener("change", writeHash);
    ["boxes", "trace"].forEach(function (id) { document.getElementById(id).parentNode.hidden = true; });
    if (traceAll) traceAll.visible = tracePast.visible = false;
    slider.setAttribute("aria-label", "phase");
    // The table of modes in the side panel.
    var heading = document.createElement("h2");
    heading.textContent = modes.frequency.length + " modes about the equilibrium (click one)";
    var table = document.createElement("table");
    table.style.cssText = "border-collapse:collapse;font-size:12px;width:100%";
    table.innerHTML = "<tr><th align=left>mode</th><th align=right>frequency</th><th align=right>period</th>" +
      (modes.energy_shares ? "<th align=left>&nbsp;kinetic energy</th>" : "") + "</tr>";
    modes.frequency.forEach(function (f, k) {
      var row = table.insertRow();
      row.style.cursor = "pointer";
      row.insertCell().textContent = String(k + 1);
      var cell = row.insertCell(); cell.align = "right"; cell.textContent = modeName(k);
      cell = row.insertCell(); cell.align = "right";
      cell.textContent = f > 0 && modeName(k) !== "rigid" ? formatNumber(1 / f) + " s" : "–";
      if (modes.energy_shares) {
        cell = row.insertCell();
        cell.textContent = "\u00a0" + energyShares(k, 1);
        cell.title = energyShares(k);
      }
      row.addEventListener("click", function () { modeIndex = k; showMode(); writeHash(); });
      modeRows.push(row);
    });
    document.getElementById("plots").append(heading, table);
  }

  function pause() { state.playing = false; playButton.textContent = "Play"; }
  function play() {
    if (state.t >= t1) setTime(t0);
    state.playing = true;
    playButton.textContent = "Pause";
    lastTick = null;
  }
  playButton.addEventListener("click", function () {
    if (state.playing) { pause(); writeHash(); } else play();
  });
  window.addEventListener("keydown", function (event) {
    if (event.key === " " && event.target.tagName !== "SELECT") {
      event.preventDefault();
      playButton.click();
    }
  });
  slider.addEventListener("input", function () { pause(); setTime(+slider.value); });
  slider.addEventListener("change", writeHash);
  speedSelect.addEventListener("change", function () { state.speed = +speedSelect.value; writeHash(); });
  followBox.addEventListener("change", function () {
    state.follow = followBox.checked;
    if (state.follow && loadMarker) centreOnLoad();
    needsRender = true;
    writeHash();
  });
  boxesBox.addEventListener("change", function () {
    boxes.forEach(function (box) { box.mesh.visible = boxesBox.checked; });
    needsRender = true;
  });
  traceBox.addEventListener("change", function () {
    if (traceAll) { traceAll.visible = tracePast.visible = traceBox.checked; }
    needsRender = true;
  });
  document.getElementById("reset").addEventListener("click", function () {
    defaultCamera();
    if (state.follow && loadMarker) centreOnLoad();
    writeHash();
    needsRender = true;
  });
  controls.addEventListener("change", function () { needsRender = true; });
  controls.addEventListener("end", writeHash);
  window.addEventListener("hashchange", function () {
    var values = readHash();
    if (values.t !== undefined && Math.abs(+values.t - state.t) > 1e-9) applyHash();
  });

  // ---- colour legend of the member forces ---------------------------------------------------
  if (memberForces) {
    var legend = document.createElement("div");
    legend.id = "force-legend";
    legend.style.cssText = "position:absolute;left:10px;bottom:10px;display:flex;gap:6px;" +
      "align-items:stretch;font-size:11px;background:rgba(255,255,255,0.8);padding:4px 6px";
    var bar = lut.createCanvas();
    bar.style.cssText = "width:12px;height:110px;border:1px solid #999";
    var labels = document.createElement("div");
    labels.style.cssText = "display:flex;flex-direction:column;justify-content:space-between";
    var top = document.createElement("span"), bottom = document.createElement("span");
    top.textContent = formatNumber(memberForces.range[1]) + " N";
    bottom.textContent = formatNumber(memberForces.range[0]) + " N";
    var title = document.createElement("span");
    title.textContent = "end force |F| of ropes and strut ties (" + memberForces.members.join(", ") + ")";
    title.style.maxWidth = "170px";
    labels.append(top, title, bottom);
    legend.append(bar, labels);
    view.append(legend);
    status.setAttribute("data-force-range", memberForces.range.join(","));
    var forceLabel = document.createElement("label"), forceBox = document.createElement("input");
    forceBox.type = "checkbox";
    forceBox.id = "colour-force";
    forceBox.checked = true;
    forceLabel.append(forceBox, " colour by force");
    document.getElementById("controls").insertBefore(forceLabel, document.getElementById("reset"));
    forceBox.addEventListener("change", function () {
      colourByForce = forceBox.checked;
      legend.hidden = !colourByForce;
      setTime(state.t);
    });
  }

  // ---- page text ----------------------------------------------------------------------------
  document.getElementById("scene-name").textContent = data.scene || data.file;
  document.getElementById("file-line").textContent = modes
    ? data.file + " · cranesim " + data.engine_version + " · vibration modes about the equilibrium" +
      (data.load_name ? " · load: " + data.load_name + " (red)" : "")
    : data.file + " · cranesim " + data.engine_version + " · " + data.frame_count + " frames of " +
      data.sample_count + " samples · t = " + t0.toFixed(2) + " … " + t1.toFixed(2) + " s" +
      (data.load_name ? " · load: " + data.load_name + " (red, its path purple)" : "");
  if (plan) {
    var v = plan.verification, planLine = document.createElement("div");
    planLine.textContent = "plan " + plan.file + (plan.name ? " (" + plan.name + ")" : "") +
      ": planned path dashed, planned end point now black, simulated path green, start green, " +
      "target black · verification " + (v.status || "?") + ": tracking error max " +
      formatNumber(v.max_error) + " m, rms " + formatNumber(v.rms_error) + " m; residual sway " +
      formatNumber(v.residual_sway) + " m; final error " + formatNumber(v.final_error) + " m";
    var c = plan.clearance;
    if (c) {
      planLine.textContent += " · obstacles (" + plan.obstacles.length + "): clearance " +
        formatNumber(c.distance) + " m, " + c.closest_part + " to " + c.closest_obstacle + " at t = " +
        formatNumber(c.t) + " s (" + (c.status === "failed" ? "closer than" : "at least") + " the margin " +
        formatNumber(c.margin) + " m; closest obstacle orange" + (c.status === "failed" ? ", red: failed" : "") + ")";
    }
    planLine.id = "plan-line";
    planLine.style.maxWidth = "640px";
    document.getElementById("info").insertBefore(planLine, document.getElementById("incomplete"));
  }
  if (data.status !== "complete") {
    var incomplete = document.getElementById("incomplete");
    incomplete.textContent = "Run " + data.status.toUpperCase() + (data.message ? ": " + data.message : "") +
      " (shown up to its last sample, t = " + t1.toFixed(3) + " s" +
      (data.t_end_requested != null ? " of " + data.t_end_requested + " s" : "") + ")";
    incomplete.hidden = false;
  }
  document.getElementById("legend-note").textContent = modes
    ? "Each mode shape (the joints' displacements in the modes file) is scaled so the joint that " +
      "moves most moves by the amplitude. Bodies: skeleton from origin to joints; ropes: lines; " +
      "other members: tubes between their nodes (a full-member truss without its lacing). three.js r" +
      data.three_revision + "."
    : "Click a plot to go to that time. Bodies: skeleton from origin to joints" +
    (boxes.length ? ", and the box of equal mass and inertia" : "") +
    "; ropes: lines; other members: tubes between their nodes. three.js r" + data.three_revision + ".";

  // ---- drawing ------------------------------------------------------------------------------
  // #size=WxH fixes the 3-D view's size in CSS pixels (for screenshots and tests: a browser's
  // viewport may change between loading the page and taking its picture); else it fills the view.
  var fixedSize = (readHash().size || "").match(/^(\d+)x(\d+)$/);
  function resize() {
    var width = fixedSize ? +fixedSize[1] : view.clientWidth;
    var height = fixedSize ? +fixedSize[2] : view.clientHeight;
    renderer.setSize(width, height);
    camera.aspect = width / Math.max(height, 1);
    camera.updateProjectionMatrix();
    needsRender = true;
  }
  window.addEventListener("resize", resize);

  var projected = new THREE.Vector3();
  function render() {
    renderer.render(scene, camera);
    needsRender = false;
    var rect = renderer.domElement.getBoundingClientRect();
    status.setAttribute("data-t", String(state.t));
    status.setAttribute("data-frame", String(state.frame));
    status.setAttribute("data-canvas", [rect.left, rect.top, rect.width, rect.height].join(","));
    status.setAttribute("data-view-matrix", camera.matrixWorldInverse.elements.join(","));
    status.setAttribute("data-projection-matrix", camera.projectionMatrix.elements.join(","));
    if (plannedMarker) {
      status.setAttribute("data-planned-world", plannedMarker.position.toArray().join(","));
      status.setAttribute("data-obstacles", obstacleMeshes.map(function (m) { return m.name; }).join(","));
    }
    if (loadMarker) {
      projected.copy(loadMarker.position);
      status.setAttribute("data-load-world", projected.toArray().join(","));
      projected.project(camera);
      status.setAttribute("data-load-px", [
        rect.left + (projected.x + 1) / 2 * rect.width,
        rect.top + (1 - projected.y) / 2 * rect.height].join(","));
    }
  }

  var lastTick = null;
  function tick(now) {
    requestAnimationFrame(tick);
    if (state.playing) {
      if (lastTick !== null) {
        var t = state.t + (now - lastTick) / 1000 * state.speed;
        if (modes && t >= t1) t = t0 + (t - t0) % (t1 - t0);  // a mode cycles for ever
        setTime(t);
        if (t >= t1) { pause(); writeHash(); }
      }
      lastTick = now;
    }
    if (needsRender) render();
  }

  resize();
  defaultCamera();
  applyHash();
  render();

  // #bench=N: draw N frames spread over the run back to back, each finished (a pixel read back),
  // and report the frames per second in data-bench-fps.
  var bench = +readHash().bench;
  if (bench > 0) {
    var gl = renderer.getContext(), pixel = new Uint8Array(4);
    var start = performance.now();
    for (var k = 0; k < bench; k++) {
      setTime(t0 + (t1 - t0) * k / Math.max(bench - 1, 1));
      render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    }
    status.setAttribute("data-bench-fps", String(bench / ((performance.now() - start) / 1000)));
  }

  if (readHash().play === "1") play();  // #play=1: a link that starts playing

  if (!window.cranesimErrors.length) {
    status.setAttribute("data-ready-ms", String(performance.now()));  // since navigation start
    status.setAttribute("data-state", "ready");
    document.title = "cranesim replay: ready · t = " + state.t.toFixed(3) + " s · " + (data.scene || data.file);
  }
  requestAnimationFrame(tick);
})();
