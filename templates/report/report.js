// marm-setup report: draws the robot with MeshCat's viewer (the global `MeshCat`, inlined above)
// and wires the side panel (poses, groups, trajectories, findings, matrix) to it. Everything it
// shows comes from the JSON in #report-data; names are only ever set as text, never as markup.
"use strict";
(function () {
  const data = JSON.parse(document.getElementById("report-data").textContent);
  const THREE = MeshCat.THREE;
  const COLORS = { base: 0x8797ab, group: 0xf0a030, contact: 0xe31a1c, pair: 0x8e44ad };
  const viewer = new MeshCat.Viewer(document.getElementById("viewer"));
  viewer.set_property(["Axes"], "visible", false); // the virtual joint's frame is drawn instead
  viewer.set_property(["Background"], "top_color", [0.98, 0.98, 0.99]);
  viewer.set_property(["Background"], "bottom_color", [0.78, 0.81, 0.86]);

  // -- decoding ---------------------------------------------------------------------------
  function bytes(b64) {
    const text = atob(b64);
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
    return out.buffer;
  }
  const floats = (b64) => new Float32Array(bytes(b64));
  const uints = (b64) => new Uint32Array(bytes(b64));
  function matrix34(values, offset) {
    const v = values, k = offset || 0;
    return new THREE.Matrix4().set(
      v[k], v[k + 1], v[k + 2], v[k + 3],
      v[k + 4], v[k + 5], v[k + 6], v[k + 7],
      v[k + 8], v[k + 9], v[k + 10], v[k + 11],
      0, 0, 0, 1);
  }
  function el(tag, attrs, text) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs || {})) node.setAttribute(key, value);
    if (text !== undefined) node.textContent = text;
    return node;
  }
  function breakable(tag, attrs, text) { // `text` that may wrap after each _ / or . (a <wbr>; copying it is unchanged)
    const node = el(tag, attrs);
    for (const part of String(text).split(/(?<=[_\/.])/)) node.append(part, el("wbr"));
    return node;
  }
  function button(text, onClick, extra) {
    const b = el("button", { type: "button", class: "pick" + (extra ? " " + extra : "") }, text);
    b.addEventListener("click", onClick);
    return b;
  }

  // -- the robot --------------------------------------------------------------------------
  const materials = new Map(); // link -> its material
  function meshGeometry(mesh) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(floats(mesh.positions), 3));
    g.setIndex(new THREE.BufferAttribute(uints(mesh.indices), 1));
    g.computeVertexNormals();
    return g;
  }
  function shapeGeometry(shape, meshes) {
    if (shape.kind === "box") return new THREE.BoxGeometry(shape.size[0], shape.size[1], shape.size[2]);
    if (shape.kind === "sphere") return new THREE.SphereGeometry(shape.size[0], 32, 16);
    if (shape.kind === "cylinder") { // URDF cylinders lie along z, three.js ones along y
      const g = new THREE.CylinderGeometry(shape.size[0], shape.size[0], shape.size[1], 32);
      g.rotateX(Math.PI / 2);
      return g;
    }
    return meshes[shape.mesh];
  }
  // MeshCat's scene tree keeps children in a plain object: a link named `constructor`,
  // `__proto__` or `toString` would find Object's own property there. Its paths are keys we make.
  const nodeKeys = new Map(); // link name -> its scene tree key
  function node(name) {
    if (!nodeKeys.has(name)) nodeKeys.set(name, "link " + nodeKeys.size);
    return nodeKeys.get(name);
  }
  function buildRobot() {
    const meshes = data.geometry.meshes.map(meshGeometry);
    for (const link of data.geometry.links) {
      const material = new THREE.MeshPhongMaterial({ color: COLORS.base, flatShading: true, side: THREE.DoubleSide });
      materials.set(link.name, material);
      const body = new THREE.Group();
      for (const shape of link.shapes) {
        const mesh = new THREE.Mesh(shapeGeometry(shape, meshes), material);
        mesh.matrixAutoUpdate = false;
        mesh.matrix.copy(matrix34(shape.origin));
        body.add(mesh);
      }
      viewer.set_object(["robot", node(link.name)], body);
    }
  }
  function placeLinks(frames, offset, which) { // `which`: indices into data.links (all when absent)
    (which || data.links.map((_, i) => i)).forEach((link, i) => {
      viewer.set_transform(["robot", node(data.links[link])], matrix34(frames, offset + 12 * i).elements);
    });
    viewer.set_dirty();
  }

  // -- frames and labels ------------------------------------------------------------------
  function label(text, size) {
    const canvas = document.createElement("canvas");
    const ctx = canvas.getContext("2d");
    ctx.font = "48px sans-serif";
    canvas.width = Math.ceil(ctx.measureText(text).width) + 24;
    canvas.height = 64;
    ctx.font = "48px sans-serif";
    ctx.fillStyle = "rgba(255,255,255,0.85)";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.fillStyle = "#111";
    ctx.fillText(text, 12, 48);
    const texture = new THREE.CanvasTexture(canvas);
    const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false }));
    sprite.scale.set(size * canvas.width / canvas.height, size, 1);
    sprite.renderOrder = 10;
    return sprite;
  }
  function frameMarker(text, size) {
    const marker = new THREE.Group();
    marker.add(new THREE.AxesHelper(size));
    const tag = label(text, size * 0.3);
    tag.position.set(0, 0, size * 1.2);
    tag.center.set(0, 0); // text starts at the frame, beside the z axis
    marker.add(tag);
    return marker;
  }
  const markers = [];
  function drawFrames(size) {
    const add = (link, name, marker) => {
      viewer.set_object(["robot", node(link), "frame " + markers.length], marker);
      markers.push(marker);
    };
    for (const vj of data.virtual_joints) {
      const at = data.links.includes(vj.child_link) ? vj.child_link : data.links[0];
      const text = `virtual joint ${vj.name} (${vj.type}): ${vj.parent_frame} → ${vj.child_link}`;
      if (at !== undefined) add(at, "virtual joint " + vj.name, frameMarker(text, size * 1.5));
    }
    for (const ee of data.end_effectors) {
      if (!data.links.includes(ee.parent_link)) continue;
      add(ee.parent_link, "end effector " + ee.name, frameMarker(`end effector ${ee.name} (group ${ee.group})`, size));
    }
  }
  function showMarkers(visible) {
    for (const marker of markers) marker.visible = visible;
    viewer.set_dirty();
  }
  function niceStep(length) { // 1, 2 or 5 times a power of ten, at most `length`
    const p = Math.pow(10, Math.floor(Math.log10(length)));
    return length >= 5 * p ? 5 * p : length >= 2 * p ? 2 * p : p;
  }
  // MeshCat turns its scene so that robot z (up) is three.js y (up): boxes measured in three.js
  // world coordinates and the camera (which sits in that frame) use y as up.
  function drawGrid(floor, radius) { // a floor grid the robot's size (MeshCat's is 20 m wide)
    const step = niceStep(radius / 4);
    const cells = 2 * Math.ceil(2 * radius / step);
    const grid = new THREE.GridHelper(cells * step, cells, 0x888888, 0xbbbbbb);
    grid.rotateX(Math.PI / 2);
    grid.position.z = floor;
    viewer.set_object(["Grid"], grid);
  }
  function fitCamera() {
    const box = new THREE.Box3().setFromObject(viewer.scene_tree.find(["robot"]).object);
    if (box.isEmpty()) return 0.5;
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.05);
    drawGrid(Math.min(box.min.y, 0), radius);
    const view = new THREE.Vector3(1.0, 0.5, -0.8).normalize(); // from +x, +y (robot), above
    viewer.camera.position.copy(center.clone().addScaledVector(view, radius * 2.3));
    viewer.controls.target.copy(center);
    viewer.camera.near = radius / 100;
    viewer.camera.far = radius * 100;
    viewer.controls.update();
    viewer.set_dirty();
    return radius;
  }

  // -- what is shown ----------------------------------------------------------------------
  const states = new Map(data.states.map((s) => [s.key, s]));
  const groups = new Map(data.groups.map((g) => [g.name, g]));
  const shown = { state: null, group: null, pair: null, motion: null };
  const buttons = { state: new Map(), group: new Map(), motion: new Map() };

  function contactsNow() {
    if (shown.motion !== null) return [];
    return shown.state === null ? [] : states.get(shown.state).contacts;
  }
  function paint() {
    const red = new Set(contactsNow().flat());
    const pair = new Set(shown.pair || []);
    const lit = new Set(shown.group === null ? [] : groups.get(shown.group).links);
    const focus = pair.size > 0 || lit.size > 0 || red.size > 0; // the rest fades: a contact behind a link shows
    for (const [name, material] of materials) {
      const color = red.has(name) ? COLORS.contact : pair.has(name) ? COLORS.pair : lit.has(name) ? COLORS.group : COLORS.base;
      const strong = red.has(name) || pair.has(name) || lit.has(name) || !focus;
      material.color.setHex(color);
      material.transparent = !strong;
      material.opacity = strong ? 1.0 : 0.35;
    }
    for (const [kind, map] of Object.entries(buttons)) {
      const current = kind === "state" && shown.motion !== null ? null : shown[kind];
      for (const [key, b] of map) b.classList.toggle("active", current === key);
    }
    viewer.set_dirty();
    describe();
  }
  function describe() {
    const title = document.getElementById("state-title");
    const detail = document.getElementById("state-detail");
    const lines = [];
    if (shown.motion !== null) {
      const m = data.motions[shown.motion];
      title.textContent = `trajectory ${m.group}: ${m.start} → ${m.goal}`;
      if (m.problem) lines.push(m.problem);
    } else if (shown.state !== null) {
      const s = states.get(shown.state);
      title.textContent = s.group ? `pose ${s.title} (group ${s.group})` : s.title;
      if (s.note) lines.push(s.note);
      for (const [a, b] of s.contacts) lines.push(`in contact: ${a} – ${b}`);
      if (s.key.startsWith("pose:") && s.contacts.length === 0) lines.push("no contact among the pairs MoveIt checks");
    }
    if (shown.group !== null) lines.push(`group ${shown.group}: ${groups.get(shown.group).links.length} links lit`);
    if (shown.pair !== null) lines.push(`pair ${shown.pair[0]} – ${shown.pair[1]}`);
    detail.textContent = lines.join("\n");
  }
  function showState(key) {
    stopMotion();
    shown.state = key;
    shown.motion = null;
    document.getElementById("player").hidden = true;
    placeLinks(floats(states.get(key).frames), 0);
    paint();
  }
  function highlightGroup(name) {
    shown.group = shown.group === name ? null : name;
    shown.pair = null;
    paint();
  }
  function highlightPair(a, b) {
    shown.pair = [a, b];
    shown.group = null;
    paint();
  }

  // -- trajectories -----------------------------------------------------------------------
  const player = { frames: null, times: null, moving: [], start: 0, at: 0, running: false };
  function showMotionAt(t) {
    const times = player.times;
    let k = 0;
    while (k + 1 < times.length && times[k + 1] <= t) k++;
    player.at = t;
    placeLinks(player.frames, k * 12 * player.moving.length, player.moving);
    const duration = times[times.length - 1] || 0;
    document.getElementById("clock").textContent = `${t.toFixed(2)} / ${duration.toFixed(2)} s`;
    document.getElementById("scrub").value = duration > 0 ? Math.round(1000 * t / duration) : 1000;
  }
  function tick(now) {
    if (!player.running) return;
    const duration = player.times[player.times.length - 1] || 0;
    const t = Math.min((now - player.start) / 1000, duration);
    showMotionAt(t);
    if (t >= duration) stopMotion(); else requestAnimationFrame(tick);
  }
  function playMotion(index) {
    const m = data.motions[index];
    if (m.moving === undefined || !m.times) return;
    stopMotion();
    shown.motion = index;
    shown.group = m.group;
    shown.pair = null;
    placeLinks(floats(m.still), 0);
    player.frames = floats(m.frames);
    player.times = floats(m.times);
    player.moving = m.moving;
    document.getElementById("player").hidden = false;
    paint();
    player.running = true;
    player.start = performance.now();
    document.getElementById("play").textContent = "pause";
    requestAnimationFrame(tick);
  }
  function stopMotion() {
    player.running = false;
    document.getElementById("play").textContent = "play";
  }
  document.getElementById("play").addEventListener("click", () => {
    if (player.running) { stopMotion(); return; }
    const duration = player.times[player.times.length - 1] || 0;
    const from = player.at >= duration ? 0 : player.at;
    player.running = true;
    player.start = performance.now() - 1000 * from;
    document.getElementById("play").textContent = "pause";
    requestAnimationFrame(tick);
  });
  document.getElementById("scrub").addEventListener("input", (event) => {
    stopMotion();
    const duration = player.times[player.times.length - 1] || 0;
    showMotionAt(duration * Number(event.target.value) / 1000);
  });

  // -- the side panel ---------------------------------------------------------------------
  function fillHead() {
    const head = document.getElementById("head");
    const s = data.summary;
    head.append(el("h1", {}, `${data.robot} — ${s.package}`));
    head.append(el("div", { class: "meta" }, s.validated));
    if (s.not_drawn) head.append(el("div", { class: "meta warning" }, s.not_drawn));
    const counts = el("div", { class: "counts" });
    counts.append(el("span", { class: s.errors ? "error" : "ok" }, `${s.errors} error${s.errors === 1 ? "" : "s"}`), ", ");
    counts.append(el("span", { class: s.warnings ? "warning" : "ok" }, `${s.warnings} warning${s.warnings === 1 ? "" : "s"}`));
    head.append(counts);
    const legend = document.getElementById("legend");
    for (const [name, color] of [["in contact", COLORS.contact], ["group", COLORS.group], ["pair", COLORS.pair], ["link", COLORS.base]]) {
      const item = el("span");
      const swatch = el("i");
      swatch.style.background = "#" + color.toString(16).padStart(6, "0");
      item.append(swatch, name);
      legend.append(item);
    }
  }
  function stateButton(state, text) {
    const b = button(text, () => showState(state.key), state.contacts.length ? "collides" : "");
    b.title = state.contacts.map(([a, c]) => `in contact: ${a} – ${c}`).join("\n") || "no contact";
    buttons.state.set(state.key, b);
    return b;
  }
  function fillStates() {
    const box = document.getElementById("states");
    const whole = el("div", { class: "row" });
    for (const s of data.states.filter((s) => s.key === "default" || s.key === "start")) whole.append(stateButton(s, s.title));
    box.append(whole);
    for (const g of data.groups) {
      const poses = data.states.filter((s) => s.group === g.name);
      if (poses.length === 0) continue;
      const row = el("div", { class: "row" });
      row.append(el("strong", {}, g.name + ": "));
      for (const s of poses) row.append(stateButton(s, s.title));
      box.append(row);
    }
    for (const [prefix, heading] of [["finding:", "States the findings name"], ["witness:", "Disabled pairs a proof found in contact"]]) {
      const shownStates = data.states.filter((s) => s.key.startsWith(prefix));
      if (!shownStates.length) continue;
      box.append(el("h3", {}, heading));
      for (const s of shownStates) {
        const row = el("div", { class: "row" });
        row.append(stateButton(s, s.title));
        box.append(row);
      }
    }
  }
  function fillGroups() {
    const box = document.getElementById("groups");
    for (const g of data.groups) {
      const b = button(g.name, () => highlightGroup(g.name));
      b.title = g.links.join(", ") || "no links";
      buttons.group.set(g.name, b);
      box.append(b);
    }
    const frames = document.getElementById("frames");
    for (const ee of data.end_effectors) {
      frames.append(el("div", { class: "row" }, `end effector ${ee.name}: group ${ee.group} on ${ee.parent_link}` + (ee.parent_group ? ` (parent group ${ee.parent_group})` : "")));
    }
    for (const vj of data.virtual_joints) {
      frames.append(el("div", { class: "row" }, `virtual joint ${vj.name} (${vj.type}): ${vj.parent_frame} → ${vj.child_link}`));
    }
  }
  function fillMotions() {
    const box = document.getElementById("motions");
    if (data.motions.length === 0) box.append(el("div", { class: "meta" }, "none planned (runtime checks skipped, or no group has two usable poses)"));
    data.motions.forEach((m, index) => {
      const row = el("div", { class: "row" });
      const b = button(`${m.group}: ${m.start} → ${m.goal}`, () => playMotion(index), m.problem ? "collides" : "");
      if (!m.times) b.disabled = true;
      buttons.motion.set(index, b);
      row.append(b, el("span", { class: m.problem ? "problem" : "ok" }, m.problem || `${m.duration.toFixed(2)} s`));
      box.append(row);
    });
  }
  function findingTarget(f) {
    if (f.state) return () => showState(f.state);
    let m = /^group_state\[(.+)\]$/.exec(f.element);
    if (m) {
      const pose = data.states.find((s) => s.key.startsWith("pose:") && s.title === m[1]);
      if (pose) return () => showState(pose.key);
    }
    m = /^group\[([^\]]+)\]/.exec(f.element);
    if (m && groups.has(m[1])) return () => highlightGroup(m[1]);
    m = /^disable_collisions\[(\S+) (\S+)\]$/.exec(f.element);
    if (m && materials.has(m[1]) && materials.has(m[2])) return () => highlightPair(m[1], m[2]);
    return null;
  }
  function fillFindings() {
    const box = document.getElementById("findings");
    if (data.findings.length === 0) { box.append(el("div", { class: "ok" }, "no findings")); return; }
    const table = el("table");
    const top = el("tr");
    top.append(el("th", {}, "severity"), el("th", {}, "where"), el("th", {}, "what"));
    table.append(top);
    for (const f of data.findings) {
      const row = el("tr", { class: f.severity });
      const where = el("td");
      where.append(breakable("div", {}, f.file), breakable("div", { class: "meta" }, f.element));
      const what = el("td");
      what.append(el("div", {}, f.message), el("div", { class: "meta" }, f.rule));
      if (f.hint) what.append(el("div", { class: "hint" }, "hint: " + f.hint));
      where.classList.add("name");
      row.append(el("td", { class: "sev" }, f.severity), where, what);
      const target = findingTarget(f);
      if (target) { row.classList.add("clickable"); row.title = "show it"; row.addEventListener("click", target); }
      table.append(row);
    }
    const scroll = el("div", { class: "scroll" }); // its header row sticks inside it, never over the next section
    scroll.append(table);
    box.append(scroll);
  }
  function proofText(p) {
    if (p.proof === "unproved") return `unproved (${(100 * p.proved_fraction).toFixed(1)} %)`;
    return p.proof || "";
  }
  function pairRow(p) {
    const row = el("tr", { class: "clickable" });
    const hits = p.samples ? `${p.hits}/${p.samples}` : "";
    const closest = p.min_distance === null ? "" : (1000 * p.min_distance).toFixed(1);
    const seen = p.seen_colliding === null ? "" : p.seen_colliding ? "yes" : "no";
    row.append(breakable("td", { class: "name" }, p.link1), breakable("td", { class: "name" }, p.link2), el("td", {}, p.reason || "enabled"),
      el("td", { class: "num" }, hits), el("td", { class: "num" }, seen), el("td", { class: "num" }, closest),
      el("td", {}, proofText(p)));
    row.dataset.reason = p.reason || "enabled";
    row.dataset.proof = p.proof || "none";
    row.dataset.names = `${p.link1} ${p.link2}`.toLowerCase();
    const witness = `witness:${p.link1}:${p.link2}`;
    if (states.has(witness)) { row.title = "show the state a proof found it in contact at"; row.addEventListener("click", () => showState(witness)); }
    else if (materials.has(p.link1) && materials.has(p.link2)) row.addEventListener("click", () => highlightPair(p.link1, p.link2));
    return row;
  }
  function fillMatrix() {
    const box = document.getElementById("matrix");
    const m = data.matrix;
    if (!m) { box.append(el("div", { class: "meta" }, "not computed (no robot or no SRDF)")); return; }
    const picture = el("div", { class: "picture" });
    picture.innerHTML = m.svg; // our own SVG (collision/matrix_heat_map.py), names escaped there
    picture.addEventListener("click", (event) => {
      const cell = event.target.closest("g");
      const title = cell && cell.querySelector("title");
      const names = title && /^(.+?) \/ (.+?):/.exec(title.textContent);
      if (names && materials.has(names[1]) && materials.has(names[2])) highlightPair(names[1], names[2]);
    });
    box.append(picture);
    box.append(el("div", { class: "meta" }, `reasons from the SRDF; hits/samples, seen colliding and closest distance [mm] from ${m.trials} random states (seed ${m.seed}): ${m.hit_counts}`));
    if (m.prove !== "off") {
      const p = m.proofs;
      box.append(el("div", { class: "meta" }, `proofs over each pair's whole joint range (--prove ${m.prove}): ${p.proved} proved collision-free, ${p.unproved} unproved (only sampled), ${p.collides} found in contact (a disabled one is drawn at its state)`));
    }
    const filters = el("div", { class: "filters" });
    const reason = el("select");
    for (const r of ["all", "enabled", "Adjacent", "Default", "Always", "Never", "User"]) reason.append(el("option", { value: r }, r));
    const proof = el("select");
    for (const r of ["any proof", "proved", "unproved", "collides"]) proof.append(el("option", { value: r }, r));
    const text = el("input", { type: "search", placeholder: "link name" });
    filters.append(reason, proof, text);
    box.append(filters);
    const table = el("table");
    const top = el("tr");
    top.append(...["link 1", "link 2", "reason", "hits", "seen", "closest mm", "proof"].map((h) => el("th", {}, h)));
    table.append(top);
    const rows = m.pairs.map(pairRow);
    table.append(...rows);
    const scroll = el("div", { class: "scroll" });
    scroll.append(table);
    box.append(scroll);
    const filter = () => {
      const want = reason.value, proved = proof.value, needle = text.value.toLowerCase();
      for (const row of rows) {
        row.hidden = (want !== "all" && row.dataset.reason !== want) || (proved !== "any proof" && row.dataset.proof !== proved)
          || !row.dataset.names.includes(needle);
      }
    };
    reason.addEventListener("change", filter);
    proof.addEventListener("change", filter);
    text.addEventListener("input", filter);
  }

  // -- start --------------------------------------------------------------------------------
  buildRobot();
  fillHead();
  fillStates();
  fillGroups();
  fillMotions();
  fillFindings();
  fillMatrix();
  if (states.size > 0) showState(states.has("start") ? "start" : data.states[0].key);
  else document.getElementById("state-title").textContent = "robot not drawn: its URDF or SRDF did not load (see the findings)";
  const radius = fitCamera();
  drawFrames(Math.max(radius * 0.2, 0.02));
  paint();
  window.report = { viewer, showState, highlightGroup, highlightPair, playMotion, stopMotion, showMotionAt, showMarkers, states: [...states.keys()] };
  document.body.dataset.ready = "true";
})();
