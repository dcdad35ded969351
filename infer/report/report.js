// lc2wf-eval --html: summary tables, the sortable per-building table and the 3D viewer. Geometry blocks
// (<script type="text/plain" id="g<i>">, base64, layout in infer/report_geometry.h) are decoded only when a
// building is opened, so a large report stays quick to open.
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const S = data.summary;
  const rows = data.rows;
  const vT = S.options.vertex_thresholds_m;
  const eT = S.options.edge_thresholds_m;
  const $ = (id) => document.getElementById(id);
  const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
  const pct = (x) => (100 * x).toFixed(1);
  const num = (x) => (Math.abs(x) < 10 ? x.toFixed(3) : Math.abs(x) < 100 ? x.toFixed(2) : x.toFixed(1));
  const state = { eta: Math.min(1, vT.length - 1, eT.length - 1), sortKey: 'wd', sortDir: -1, order: [], current: -1, filter: '' };

  // ---------- summary tables ----------
  function table(head, body) {
    return '<table><thead><tr>' + head.map((h) => '<th>' + h + '</th>').join('') + '</tr></thead><tbody>' +
      body.map((r) => '<tr>' + r.map((c) => '<td>' + c + '</td>').join('') + '</tr>').join('') + '</tbody></table>';
  }
  function renderSummary() {
    const all = [S].concat(data.compare || []);
    const head = ['method'].concat(vT.map((t) => 'v η=' + t.toFixed(2)), ['v avg.'], eT.map((t) => 's η=' + t.toFixed(2)), ['s avg.']);
    const apRow = (m) => [esc(m.method)].concat(m.vertex.map((v) => pct(v.ap) + '/' + pct(v.recall)),
      [pct(m.vertex_avg.ap) + '/' + pct(m.vertex_avg.recall)], m.edge.map((e) => pct(e.ap) + '/' + pct(e.recall)),
      [pct(m.edge_avg.ap) + '/' + pct(m.edge_avg.recall)]);
    const w = (a, b) => num(a) + ' / ' + num(b);
    const wedRow = (m) => [esc(m.method), w(m.wed.add_vertex, m.wed.move), w(m.wed.add_edge, m.wed.add_edge_length),
      w(m.wed.del_edge, m.wed.del_edge_length), w(m.wed.total_num, m.wed.total_dist)];
    let h = '<h2>(a) vAP / vRecall and sAP / sRecall (%)</h2>' + table(head, all.map(apRow));
    h += '<h2>(b) WED, mean per building (Num / Dist m)</h2>' +
      table(['method', '+vertex', '+edge', '−edge', 'total'], all.map(wedRow)) +
      '<p class="note">Release WED: the +vertex Dist is the move cost Σ √(raw distance)/' + S.options.raw_per_metre +
      '; spurious edges and extra vertices are free.</p>';
    const strict = all.filter((m) => m.wed_strict);
    if (strict.length) {
      h += '<h2>(b′) Strict WED, mean per building (Num / Dist m)</h2>' +
        table(['method', '+vertex (move)', '−vertex', '+edge', '−edge', 'total'], strict.map((m) => [esc(m.method),
          w(m.wed_strict.add_vertex, m.wed_strict.move), num(m.wed_strict.del_vertex),
          w(m.wed_strict.add_edge, m.wed_strict.add_edge_length), w(m.wed_strict.del_edge, m.wed_strict.del_edge_length),
          w(m.wed_strict.total_num, m.wed_strict.total_dist)]));
    }
    const b3 = all.filter((m) => m.building3d);
    if (b3.length) {
      const b = S.building3d || b3[0].building3d;
      h += '<h2>(c) Building3D-style metrics (%; ACO in m)</h2>' +
        table(['method', 'CP', 'CR', 'CF1', 'EP', 'ER', 'EF1', 'ACO', 'B3D-nWED'], b3.map((m) => {
          const x = m.building3d;
          return [esc(m.method), pct(x.cp), pct(x.cr), pct(x.cf1), pct(x.ep), pct(x.er), pct(x.ef1), x.aco_m.toFixed(3), x.nwed.toFixed(3)];
        })) +
        '<p class="note">Frame: ' + esc(b.frame) + ' (mean radius ' + b.mean_frame_radius_m.toFixed(2) + ' m); threshold ' +
        b.distance_threshold + ' normalised; confidence cut: edges with score &gt; ' + b.confidence_threshold +
        '; variant: ' + esc(b.variant) + '. B3D-nWED is normalised by the GT edge length and is not the paper\'s WED.</p>';
    }
    const fc = all.filter((m) => m.faces);
    if (fc.length) {
      const scored = fc[0].faces.gt_has_faces;
      h += '<h2>(d) Faces: LoD2 surfaces from the predicted wireframes (%)</h2>' + (scored
        ? table(['method', 'roof P', 'roof R', 'labels', 'valid closed solids', 'roof area error', 'ms per building'], fc.map((m) => {
          const x = m.faces;
          return [esc(m.method), pct(x.roof_precision), pct(x.roof_recall), pct(x.label_accuracy),
            pct(x.closed_share) + ' (' + x.closed_solids + ' of ' + x.buildings + ')', pct(x.roof_area_error), x.surfaces_ms_mean.toFixed(2)];
        }))
        : table(['method', 'valid closed solids', 'ms per building'], fc.map((m) => [esc(m.method),
          pct(m.faces.closed_share) + ' (' + m.faces.closed_solids + ' of ' + m.faces.buildings + ')', m.faces.surfaces_ms_mean.toFixed(2)])) +
          '<p class="note">Face scores need a ground truth with faces (Roof-Image meshes); this one has none.</p>') +
        '<p class="note">A predicted roof facet matches a GT facet when the planes agree within 10° and 0.2 m and the polygons overlap with IoU ≥ 0.5 (one-to-one).</p>';
    }
    $('summary').innerHTML = h;
    $('method').textContent = S.method;
    const missing = S.missing_predictions.length;
    $('subtitle').textContent = S.buildings + ' buildings' + (missing ? ' (' + missing + ' without a prediction, scored as empty)' : '') +
      '. Distances in metres. Ties: ' + S.options.ties + '.';
    document.title = 'lc2wf evaluation: ' + S.method;
    // The headline numbers above the buildings; the full tables follow below them.
    const items = [['vAP avg.', pct(S.vertex_avg.ap) + ' %'], ['sAP avg.', pct(S.edge_avg.ap) + ' %'],
      ['WED total', num(S.wed.total_num) + ' / ' + num(S.wed.total_dist) + ' m']];
    if (S.building3d) items.push(['CF1', pct(S.building3d.cf1) + ' %'], ['EF1', pct(S.building3d.ef1) + ' %']);
    $('headline').innerHTML = items.map(([k, v]) => '<span>' + k + ' <b>' + v + '</b></span>').join('') +
      '<span><a href="#summary">all tables ↓</a></span>';
    if (data.plots && data.plots.length) {
      $('plots').hidden = false;
      $('plots').innerHTML = '<h2>Plots</h2>' + data.plots.map((p) =>
        '<figure><a href="' + esc(p.href) + '"><img src="' + esc(p.href) + '" alt="' + esc(p.title) + '"></a><figcaption>' +
        esc(p.title) + '</figcaption></figure>').join('');
    }
  }

  // ---------- per-building table ----------
  const ratio = (a, b) => (b > 0 ? a / b : 0);
  const f1 = (p, r) => (p + r > 0 ? 2 * p * r / (p + r) : 0);
  const m = {
    vP: (r) => ratio(r.vtp[state.eta], r.pv), vR: (r) => ratio(r.vtp[state.eta], r.gv),
    sP: (r) => ratio(r.etp[state.eta], r.pe), sR: (r) => ratio(r.etp[state.eta], r.ge),
  };
  // dir: -1 when larger is worse (first click sorts descending), +1 when smaller is worse.
  const columns = [
    { key: 'n', label: 'building', get: (r) => r.n, dir: 1, fmt: (v) => esc(v), cls: 'name' },
    { key: 'ge', label: 'GT e', title: 'ground-truth edges', get: (r) => r.ge, dir: -1, fmt: String },
    { key: 'pe', label: 'pred e', title: 'predicted edges', get: (r) => r.pe, dir: -1, fmt: String },
    { key: 'vP', label: 'v P', title: 'vertex precision at η', get: m.vP, dir: 1, fmt: pct },
    { key: 'vR', label: 'v R', title: 'vertex recall at η', get: m.vR, dir: 1, fmt: pct },
    { key: 'sP', label: 's P', title: 'edge precision at η', get: m.sP, dir: 1, fmt: pct },
    { key: 'sR', label: 's R', title: 'edge recall at η', get: m.sR, dir: 1, fmt: pct },
    { key: 'sF', label: 's F1', title: 'edge F1 at η', get: (r) => f1(m.sP(r), m.sR(r)), dir: 1, fmt: pct },
    { key: 'wn', label: 'WED #', title: 'release WED total Num', get: (r) => r.wn, dir: -1, fmt: String },
    { key: 'wd', label: 'WED m', title: 'release WED total Dist (m)', get: (r) => r.wd, dir: -1, fmt: num },
  ];
  if (rows.length && rows[0].cf1 !== undefined) {
    columns.push({ key: 'cf1', label: 'CF1', title: 'Building3D corner F1', get: (r) => r.cf1, dir: 1, fmt: pct },
      { key: 'ef1', label: 'EF1', title: 'Building3D edge F1', get: (r) => r.ef1, dir: 1, fmt: pct },
      { key: 'nw', label: 'nWED', title: 'B3D-nWED (GT-length normalised)', get: (r) => r.nw, dir: -1, fmt: (v) => v.toFixed(3) });
  }
  if (rows.length && rows[0].fp !== undefined) {
    columns.push({ key: 'fp', label: 'roof P', title: 'roof-facet precision', get: (r) => r.fp, dir: 1, fmt: pct },
      { key: 'fr', label: 'roof R', title: 'roof-facet recall', get: (r) => r.fr, dir: 1, fmt: pct },
      { key: 'fs', label: 'solid', title: 'the faces form a valid closed solid', get: (r) => (r.fs === 'closed_solid' ? 1 : 0), dir: 1,
        fmt: (v) => (v ? '✓' : '✗') });
  }
  function renderHead() {
    $('buildings').tHead.innerHTML = '<tr><th title="position in the current order">#</th>' + columns.map((c) =>
      '<th data-key="' + c.key + '" title="' + esc(c.title || c.label) + '"' + (c.key === state.sortKey ? ' class="sorted"' : '') + '>' +
      c.label + (c.key === state.sortKey ? (state.sortDir < 0 ? ' ▼' : ' ▲') : '') + '</th>').join('') + '</tr>';
  }
  function sortRows() {
    const col = columns.find((c) => c.key === state.sortKey);
    const idx = rows.map((_, i) => i).filter((i) => !state.filter || rows[i].n.toLowerCase().includes(state.filter));
    idx.sort((a, b) => {
      const x = col.get(rows[a]), y = col.get(rows[b]);
      const d = x < y ? -1 : x > y ? 1 : 0;
      return d * state.sortDir || a - b;
    });
    state.order = idx;
  }
  function renderBody() {
    sortRows();
    renderHead();
    const html = [];
    state.order.forEach((i, k) => {
      const r = rows[i];
      const cls = (i === state.current ? 'sel' : '') + (k < 10 ? ' worst' : '') + (r.miss ? ' missing' : '');
      html.push('<tr data-i="' + i + '" class="' + cls + '"' + (r.miss ? ' title="no prediction file: scored as empty"' : '') + '><td class="rank">' + (k + 1) + '</td>' +
        columns.map((c) => '<td' + (c.cls ? ' class="' + c.cls + '"' : '') + '>' + c.fmt(c.get(r)) + '</td>').join('') + '</tr>');
    });
    $('buildings').tBodies[0].innerHTML = html.join('');
    $('count').textContent = state.order.length + ' of ' + rows.length;
  }
  function setupTable() {
    $('eta').innerHTML = vT.map((t, k) => '<option value="' + k + '">v ' + t.toFixed(2) + ' / s ' + (eT[k] ?? eT[eT.length - 1]).toFixed(2) + ' m</option>').join('');
    $('eta').value = String(state.eta);
    $('eta').addEventListener('change', () => { state.eta = +$('eta').value; renderBody(); if (state.current >= 0) rebuildWireframes(); });
    $('buildings').tHead.addEventListener('click', (ev) => {
      const th = ev.target.closest('th[data-key]');
      if (!th) return;
      const col = columns.find((c) => c.key === th.dataset.key);
      state.sortDir = state.sortKey === col.key ? -state.sortDir : col.dir;
      state.sortKey = col.key;
      renderBody();
    });
    $('buildings').tBodies[0].addEventListener('click', (ev) => {
      const tr = ev.target.closest('tr[data-i]');
      if (tr) open(+tr.dataset.i);
    });
    $('filter').addEventListener('input', () => { state.filter = $('filter').value.trim().toLowerCase(); renderBody(); });
    const step = (d) => {
      const k = state.order.indexOf(state.current);
      const next = state.order[Math.max(0, Math.min(state.order.length - 1, (k < 0 ? 0 : k + d)))];
      if (next !== undefined) open(next);
    };
    $('prev').addEventListener('click', () => step(-1));
    $('next').addEventListener('click', () => step(1));
    document.addEventListener('keydown', (ev) => {
      if (ev.target.tagName === 'INPUT' || ev.target.tagName === 'SELECT') return;
      if (ev.key === 'j') step(1);
      if (ev.key === 'k') step(-1);
    });
  }

  // ---------- geometry blocks ----------
  function decode(i) {
    const bin = atob(document.getElementById('g' + i).textContent.trim());
    const u8 = new Uint8Array(bin.length);
    for (let k = 0; k < bin.length; ++k) u8[k] = bin.charCodeAt(k);
    const buf = u8.buffer;
    const head = new Float32Array(buf, 0, 4);
    const n = new Uint32Array(buf, 16, 7);
    let off = 44;
    const take16 = (Ctor, count) => { const a = new Ctor(buf, off, count); off += 2 * count; return a; };
    const take8 = (count) => { const a = new Uint8Array(buf, off, count); off += count; return a; };
    const g = { origin: [head[0], head[1], head[2]], step: head[3], nc: n[0], npj: n[1], npe: n[2], ngj: n[3], nge: n[4] };
    g.cloud = take16(Int16Array, 6 * g.nc); g.pj = take16(Int16Array, 3 * g.npj); g.gj = take16(Int16Array, 3 * g.ngj);
    g.pe = take16(Uint16Array, 2 * g.npe); g.ge = take16(Uint16Array, 2 * g.nge);
    g.pjs = take8(g.npj); g.pes = take8(g.npe);
    g.pjb = take8(g.npj); g.gjb = take8(g.ngj); g.peb = take8(g.npe); g.geb = take8(g.nge);
    return g;
  }
  const metres = (g, q) => { const out = new Float32Array(q.length); for (let k = 0; k < q.length; ++k) out[k] = g.origin[k % 3] + q[k] * g.step; return out; };

  // ---------- 3D viewer ----------
  const FACE = [0xe8702a, 0x5b8def, 0x8c6d46];  // roof, wall, ground (translucent)
  const FACE_NAMES = ['roof', 'wall', 'ground'];
  const C = { cloud: 0x8c959f, pred: 0xd62728, predFp: 0xd62728, gt: 0x2ca02c, gtMiss: 0x1a7f37, junFp: 0xff8c00 };
  const RAMP = [[0x44, 0x01, 0x54], [0x3b, 0x52, 0x8b], [0x21, 0x91, 0x8c], [0x5e, 0xc9, 0x62], [0xfd, 0xe7, 0x25]];
  function ramp(t) {
    const x = Math.max(0, Math.min(1, t)) * (RAMP.length - 1), k = Math.min(RAMP.length - 2, Math.floor(x)), f = x - k;
    return RAMP[k].map((c, j) => (c + f * (RAMP[k + 1][j] - c)) / 255);
  }
  let renderer = null, scene, camera, controls, geo = null, layers = {}, size = 1;
  function initViewer() {
    const el = $('view3d');
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xffffff, 1);
    el.appendChild(renderer.domElement);
    scene = new THREE.Scene();
    camera = new THREE.PerspectiveCamera(40, 1, 0.05, 5000);
    camera.up.set(0, 0, 1);
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.screenSpacePanning = true;
    controls.addEventListener('change', render);
    new ResizeObserver(resize).observe(el);
    resize();
    for (const id of ['show-cloud', 'show-pred', 'show-gt', 'show-faces']) $(id).addEventListener('change', applyVisibility);
    $('by-score').addEventListener('change', () => { rebuildWireframes(); renderLegend(); });
    $('reset').addEventListener('click', fitCamera);
  }
  function resize() {
    const el = $('view3d');
    const w = Math.max(1, el.clientWidth), h = Math.max(1, el.clientHeight);
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  }
  function render() { if (renderer) renderer.render(scene, camera); }
  function dispose(obj) {
    if (!obj) return;
    scene.remove(obj);
    obj.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
  }
  function segments(positions, pairs, pick, material, colours) {
    const out = [];
    const cols = [];
    for (let e = 0; e < pairs.length / 2; ++e) {
      if (!pick(e)) continue;
      for (const j of [pairs[2 * e], pairs[2 * e + 1]]) {
        out.push(positions[3 * j], positions[3 * j + 1], positions[3 * j + 2]);
        if (colours) cols.push(...colours(e));
      }
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(out, 3));
    if (colours) g.setAttribute('color', new THREE.Float32BufferAttribute(cols, 3));
    const line = new THREE.LineSegments(g, material);
    if (material.isLineDashedMaterial) line.computeLineDistances();
    return line;
  }
  function points(positions, pick, colour, px) {
    const out = [];
    for (let j = 0; j < positions.length / 3; ++j) if (pick(j)) out.push(positions[3 * j], positions[3 * j + 1], positions[3 * j + 2]);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(out, 3));
    return new THREE.Points(g, new THREE.PointsMaterial({ color: colour, size: px, sizeAttenuation: false }));
  }
  function rebuildWireframes() {
    if (!geo) return;
    dispose(layers.pred); dispose(layers.gt);
    const bit = 1 << state.eta;
    const dash = { dashSize: size / 40, gapSize: size / 60 };
    const byScore = $('by-score').checked;
    const scoreColour = byScore ? (e) => ramp(geo.pes[e] / 255) : null;
    const solid = (c) => new THREE.LineBasicMaterial(byScore ? { vertexColors: THREE.VertexColors } : { color: c });
    const dashed = (c) => new THREE.LineDashedMaterial(Object.assign(byScore ? { vertexColors: THREE.VertexColors } : { color: c }, dash));
    const pred = new THREE.Group();
    pred.add(segments(geo.pjm, geo.pe, (e) => geo.peb[e] & bit, solid(C.pred), scoreColour));
    pred.add(segments(geo.pjm, geo.pe, (e) => !(geo.peb[e] & bit), dashed(C.predFp), scoreColour));
    pred.add(points(geo.pjm, (j) => geo.pjb[j] & bit, C.pred, 5));
    pred.add(points(geo.pjm, (j) => !(geo.pjb[j] & bit), C.junFp, 6));
    const gt = new THREE.Group();
    gt.add(segments(geo.gjm, geo.ge, (e) => geo.geb[e] & bit, new THREE.LineBasicMaterial({ color: C.gt }), null));
    gt.add(segments(geo.gjm, geo.ge, (e) => !(geo.geb[e] & bit), new THREE.LineDashedMaterial(Object.assign({ color: C.gtMiss }, dash)), null));
    gt.add(points(geo.gjm, (j) => geo.gjb[j] & bit, C.gt, 5));
    gt.add(points(geo.gjm, (j) => !(geo.gjb[j] & bit), C.gtMiss, 8));
    layers.pred = pred; layers.gt = gt;
    scene.add(gt); scene.add(pred);
    applyVisibility();
    renderInfo();
  }
  // Face polygons in 2D (the plane's dominant axis dropped) triangulated by three.js, one mesh per label.
  function buildFaces() {
    dispose(layers.faces);
    layers.faces = null;
    document.body.dataset.faces = '0';
    if (!geo.faces) return;
    const F = geo.faces, v = (k) => new THREE.Vector3(F.v[3 * k] / 1000, F.v[3 * k + 1] / 1000, F.v[3 * k + 2] / 1000);
    const tris = [[], [], []];
    let drawn = 0;
    F.f.forEach((ring, i) => {
      const pts = ring.map(v);
      const n = new THREE.Vector3();
      for (let k = 0; k < pts.length; ++k) n.add(new THREE.Vector3().crossVectors(pts[k], pts[(k + 1) % pts.length]));
      const a = Math.abs(n.x) >= Math.abs(n.y) && Math.abs(n.x) >= Math.abs(n.z) ? 0 : Math.abs(n.y) >= Math.abs(n.z) ? 1 : 2;
      const flat = pts.map((p) => { const c = p.toArray(); c.splice(a, 1); return new THREE.Vector2(c[0], c[1]); });
      const t = THREE.ShapeUtils.triangulateShape(flat, []);
      if (!t.length) return;
      ++drawn;
      for (const [x, y, z] of t) for (const k of [x, y, z]) tris[F.l[i]].push(pts[k].x, pts[k].y, pts[k].z);
    });
    const group = new THREE.Group();
    tris.forEach((pos, label) => {
      if (!pos.length) return;
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
      group.add(new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: FACE[label], transparent: true, opacity: 0.35,
        side: THREE.DoubleSide, depthWrite: false })));
    });
    layers.faces = group;
    scene.add(group);
    document.body.dataset.faces = String(drawn);
  }
  function applyVisibility() {
    if (layers.faces) layers.faces.visible = $('show-faces').checked;
    if (layers.cloud) layers.cloud.visible = $('show-cloud').checked;
    if (layers.pred) layers.pred.visible = $('show-pred').checked;
    if (layers.gt) layers.gt.visible = $('show-gt').checked;
    render();
  }
  function fitCamera() {
    const box = new THREE.Box3();
    for (const arr of [geo.cm, geo.pjm, geo.gjm])
      for (let k = 0; k + 2 < arr.length; k += 3) box.expandByPoint(new THREE.Vector3(arr[k], arr[k + 1], arr[k + 2]));
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(0.5, box.getSize(new THREE.Vector3()).length() / 2);
    size = radius;
    const dir = new THREE.Vector3(1.0, -1.3, 0.9).normalize();
    // Fit the bounding sphere in the narrower of the vertical and horizontal fields of view.
    const vHalf = (camera.fov * Math.PI) / 360, hHalf = Math.atan(Math.tan(vHalf) * camera.aspect);
    camera.position.copy(centre).addScaledVector(dir, radius / Math.sin(Math.min(vHalf, hHalf)) * 1.02);
    camera.near = radius / 100; camera.far = radius * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
    if (layers.grid) dispose(layers.grid);
    const grid = new THREE.GridHelper(radius * 2.4, 12, 0xd0d7de, 0xeaeef2);
    grid.rotation.x = Math.PI / 2;
    grid.position.set(centre.x, centre.y, box.min.z);
    layers.grid = grid;
    scene.add(grid);
    render();
  }
  function renderInfo() {
    const r = rows[state.current];
    const t = state.eta;
    $('bname').textContent = r.n;
    $('binfo').textContent = 'GT ' + r.gv + ' v / ' + r.ge + ' e · pred ' + r.pv + ' v / ' + r.pe + ' e · edges matched ' +
      r.etp[t] + ' (η ' + eT[Math.min(t, eT.length - 1)].toFixed(2) + ' m) · WED ' + r.wn + ' / ' + num(r.wd) + ' m' +
      (r.cloud > r.shown ? ' · cloud: ' + r.shown + ' of ' + r.cloud + ' segments shown' : '') +
      (geo && geo.faces ? ' · faces ' + geo.faces.f.length + ' (' + geo.faces.s.replace('_', ' ') + ')' : '');
  }
  function renderLegend() {
    const line = (c, dashed, w) => '<svg width="28" height="8"><line x1="1" y1="4" x2="27" y2="4" stroke="' + c + '" stroke-width="' + (w || 2) +
      '"' + (dashed ? ' stroke-dasharray="5 3"' : '') + '/></svg>';
    const dot = (c) => '<svg width="10" height="10"><circle cx="5" cy="5" r="3.5" fill="' + c + '"/></svg>';
    const byScore = $('by-score').checked;
    $('legend').innerHTML = [
      line('#8c959f', false, 1) + ' line cloud',
      byScore ? 'prediction by edge score: 0 <span class="ramp"></span> 1 (solid: matched, dashed: spurious)'
        : line('#d62728') + ' predicted, matched', byScore ? '' : line('#d62728', true) + ' predicted, spurious',
      line('#2ca02c') + ' GT, matched', line('#1a7f37', true) + ' GT, missed',
      dot('#ff8c00') + ' unmatched predicted junction', dot('#1a7f37') + ' missed GT junction (larger)',
      ...FACE.map((c, k) => '<svg width="14" height="10"><rect width="14" height="10" fill="#' + c.toString(16).padStart(6, '0') +
        '" fill-opacity="0.5"/></svg> ' + FACE_NAMES[k] + ' face'),
    ].filter(Boolean).map((s) => '<span>' + s + '</span>').join('');
  }
  function open(i) {
    if (i < 0 || i >= rows.length) return;
    if (!renderer) initViewer();
    state.current = i;
    geo = decode(i);
    geo.cm = metres(geo, geo.cloud); geo.pjm = metres(geo, geo.pj); geo.gjm = metres(geo, geo.gj);
    dispose(layers.cloud);
    const cg = new THREE.BufferGeometry();
    cg.setAttribute('position', new THREE.Float32BufferAttribute(geo.cm, 3));
    layers.cloud = new THREE.LineSegments(cg, new THREE.LineBasicMaterial({ color: C.cloud, transparent: true, opacity: 0.45 }));
    scene.add(layers.cloud);
    const fb = document.getElementById('f' + i);
    geo.faces = fb ? JSON.parse(fb.textContent) : null;
    buildFaces();
    fitCamera();
    rebuildWireframes();
    for (const tr of $('buildings').tBodies[0].rows) tr.classList.toggle('sel', +tr.dataset.i === i);
    render();
    document.body.dataset.rendered = rows[i].n;
    if (api.firstRenderMs === null) api.firstRenderMs = performance.now();
  }

  // For tests and scripting: open a building, read the table order.
  const api = { open, firstRenderMs: null, order: () => state.order.map((i) => rows[i].n), sortKey: () => state.sortKey + (state.sortDir < 0 ? ' desc' : ' asc') };
  window.lc2wfReport = api;

  renderSummary();
  setupTable();
  renderBody();
  renderLegend();
  if (state.order.length) open(state.order[0]);
})();
