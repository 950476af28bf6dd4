// viewer.js: the 3D view of viewer.html (three.js r111). Reads the JSON of #waam-data (arrays as base64 typed
// arrays, mm and s), draws the cell's bodies, the part frame's path, beads, target and violation markers (and the
// deposit and the temperatures a run adds), and plays the frames. Once loaded, <body> carries data-viewer-ready, data-frames, data-bodies, data-violations, data-errors.
(function () {
  'use strict';
  var body = document.body;
  var errors = window.waamErrors || [];
  var counts = { frames: 0, bodies: 0, violations: 0 };

  function showMessage(text, isError) {
    var box = document.getElementById('message');
    box.textContent = text;
    box.className = isError ? 'error' : '';
    box.style.display = 'block';
  }

  function finish() {
    body.setAttribute('data-frames', String(counts.frames));
    body.setAttribute('data-bodies', String(counts.bodies));
    body.setAttribute('data-violations', String(counts.violations));
    body.setAttribute('data-errors', String(errors.length));
    body.setAttribute('data-viewer-ready', '1');
    if (errors.length) showMessage('The viewer met errors while loading: ' + errors.join('; '), true);
  }

  var shapes = window.waamViewerShapes;
  var decode = shapes.decode, geomObject = shapes.geomObject, layerColour = shapes.layerColour,
      upperIndex = shapes.upperIndex, colour = shapes.colour;

  function start() {
    var data = JSON.parse(document.getElementById('waam-data').textContent);
    document.title = 'waam viewer: ' + data.scenario;
    document.getElementById('title').textContent = data.scenario;
    document.getElementById('sampling').textContent = 'Sampled: ' + data.sampling + '.';
    var nFrames = data.frames.count;
    if (nFrames === 0) {
      showMessage('The checked motion of "' + data.scenario + '" is empty (' + data.samples +
                  ' samples): there is nothing to show.', false);
      return;
    }
    if (typeof THREE === 'undefined') throw new Error('three.js did not load');

    var view = document.getElementById('view');
    var renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(view.clientWidth, view.clientHeight);
    renderer.setClearColor(0xf4f4f2);
    view.appendChild(renderer.domElement);
    var scene = new THREE.Scene();
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    var sun = new THREE.DirectionalLight(0xffffff, 0.6);
    sun.position.set(1500, -2500, 4000);
    scene.add(sun);

    // The cell's bodies, each a group posed per frame.
    var bodies = [], bodyByName = {};
    data.bodies.forEach(function (b) {
      var group = new THREE.Group();
      group.userData.materials = [];
      b.geoms.forEach(function (g) {
        var material = new THREE.MeshPhongMaterial({ color: colour(g.rgba), transparent: g.rgba[3] < 1,
                                                     opacity: g.rgba[3], side: THREE.DoubleSide });
        var obj = geomObject(g, material);
        if (obj) { group.add(obj); group.userData.materials.push(material); }
      });
      scene.add(group);
      bodies.push(group);
      bodyByName[b.name] = group;
    });
    counts.bodies = bodies.length;

    var frameT = decode(data.frames.t, Float32Array);
    var bodyPoses = decode(data.frames.body_poses, Float32Array);
    var partPoses = decode(data.frames.part_poses, Float32Array);
    var frameLayer = decode(data.frames.layer, Int32Array);
    var frameWeld = decode(data.frames.weld, Uint8Array);
    counts.frames = nFrames;

    // The part frame: path, beads, target and markers move with the positioner.
    var part = new THREE.Group();
    scene.add(part);
    var n = data.path.count, layers = Math.max(1, data.layers);
    var pP = decode(data.path.p_P, Float32Array), up = decode(data.path.up_P, Float32Array);
    var width = decode(data.path.width, Float32Array), height = decode(data.path.height, Float32Array);
    var pathT = decode(data.path.t, Float32Array), pathLayer = decode(data.path.layer, Int32Array);
    var weld = decode(data.path.weld, Uint8Array);

    var segments = new Float32Array(6 * Math.max(0, n - 1));
    var byWeld = new Float32Array(segments.length), byLayer = new Float32Array(segments.length);
    var travel = new THREE.Color(0x9aa4b0), welding = new THREE.Color(0xff7f0e);
    for (var i = 1; i < n; ++i) {
      var c = weld[i] ? welding : travel, cl = weld[i] ? layerColour(pathLayer[i], layers) : travel;
      for (var e = 0; e < 2; ++e) {
        var k = i - 1 + e, o = 6 * (i - 1) + 3 * e;
        segments[o] = pP[3 * k]; segments[o + 1] = pP[3 * k + 1]; segments[o + 2] = pP[3 * k + 2];
        byWeld[o] = c.r; byWeld[o + 1] = c.g; byWeld[o + 2] = c.b;
        byLayer[o] = cl.r; byLayer[o + 1] = cl.g; byLayer[o + 2] = cl.b;
      }
    }
    var pathGeometry = new THREE.BufferGeometry();
    pathGeometry.setAttribute('position', new THREE.BufferAttribute(segments, 3));
    pathGeometry.setAttribute('color', new THREE.BufferAttribute(byWeld, 3));
    var path = new THREE.LineSegments(pathGeometry, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
    part.add(path);

    // Planned beads: one box per weld move, one instanced mesh per layer, shown once the torch has laid them.
    var beadLayers = {}, box = new THREE.BoxBufferGeometry(1, 1, 1);
    box.translate(0.5, 0, 0.5);
    for (i = 1; i < n; ++i) {
      if (!weld[i] || pathLayer[i] !== pathLayer[i - 1]) continue;
      (beadLayers[pathLayer[i]] = beadLayers[pathLayer[i]] || []).push(i);
    }
    var beadMeshes = [], beads = new THREE.Group();
    var a = new THREE.Vector3(), b = new THREE.Vector3(), x = new THREE.Vector3(), y = new THREE.Vector3(),
        z = new THREE.Vector3(), m = new THREE.Matrix4();
    Object.keys(beadLayers).forEach(function (layer) {
      var list = beadLayers[layer];
      var mesh = new THREE.InstancedMesh(box, new THREE.MeshLambertMaterial({ color: layerColour(+layer, layers) }),
                                         list.length);
      var times = new Float32Array(list.length);
      list.forEach(function (j, slot) {
        a.fromArray(pP, 3 * (j - 1)); b.fromArray(pP, 3 * j);
        x.subVectors(b, a);
        var length = x.length();
        if (length < 1e-6) x.set(1, 0, 0); else x.divideScalar(length);
        z.fromArray(up, 3 * j);
        z.addScaledVector(x, -z.dot(x));
        if (z.lengthSq() < 1e-12) z.set(0, 0, 1).addScaledVector(x, -x.z);
        z.normalize();
        y.crossVectors(z, x);
        // The bead lies below the TCP: from a to b along x, its width along y, its height down from the TCP.
        m.makeBasis(x.clone().multiplyScalar(length), y.clone().multiplyScalar(width[j]),
                    z.clone().multiplyScalar(height[j]));
        m.setPosition(a.clone().addScaledVector(z, -height[j]));
        mesh.setMatrixAt(slot, m);
        times[slot] = pathT[j];
      });
      mesh.instanceMatrix.needsUpdate = true;
      mesh.userData.times = times;
      mesh.count = 0;
      beads.add(mesh);
      beadMeshes.push(mesh);
    });
    part.add(beads);

    var target = null;
    if (data.target) {
      var tg = new THREE.BufferGeometry();
      tg.setAttribute('position', new THREE.BufferAttribute(decode(data.target.vertices, Float32Array), 3));
      tg.setIndex(new THREE.BufferAttribute(decode(data.target.triangles, Uint32Array), 1));
      tg.computeVertexNormals();
      target = new THREE.Mesh(tg, new THREE.MeshLambertMaterial({ color: 0x4a90d9, transparent: true, opacity: 0.18,
                                                                  depthWrite: false, side: THREE.DoubleSide }));
      part.add(target);
    }

    // Each layer's welding span on this page's clock: [first weld move's start, last weld move's end], s.
    function layerWeldSpans() {
      var spans = {};
      for (var w = 1; w < n; ++w) {
        if (!weld[w]) continue;
        var span = spans[pathLayer[w]] = spans[pathLayer[w]] || [pathT[w - 1], pathT[w]];
        span[0] = Math.min(span[0], pathT[w - 1]); span[1] = Math.max(span[1], pathT[w]);
      }
      return spans;
    }

    // The deposited part of `waam simulate` (when the run had it): cubes grown on the check's clock. The twin has
    // its own clock: each layer's span of deposition times is mapped onto that layer's welding span here.
    var depositNode = document.getElementById('waam-deposit'), depositMeshes = [], deposit = new THREE.Group();
    var deviationGroup = null;
    if (depositNode) {
      var dep = JSON.parse(depositNode.textContent);
      var centres = decode(dep.centres, Float32Array), simT = decode(dep.time_s, Float32Array);
      var depLayer = decode(dep.layer, Int32Array);
      var weldSpan = layerWeldSpans(), simSpan = {};
      var byLayerCells = {};
      for (i = 0; i < dep.count; ++i) {
        var ss = simSpan[depLayer[i]] = simSpan[depLayer[i]] || [simT[i], simT[i]];
        ss[0] = Math.min(ss[0], simT[i]); ss[1] = Math.max(ss[1], simT[i]);
        (byLayerCells[depLayer[i]] = byLayerCells[depLayer[i]] || []).push(i);
      }
      var cube = new THREE.BoxBufferGeometry(dep.cell_mm, dep.cell_mm, dep.cell_mm);
      Object.keys(byLayerCells).forEach(function (layer) {
        var cells = byLayerCells[layer], span = simSpan[layer], to = weldSpan[layer] || [0, duration];
        var mesh = new THREE.InstancedMesh(cube, new THREE.MeshLambertMaterial({ color: layerColour(+layer, layers) }),
                                           cells.length);
        var times = new Float32Array(cells.length);
        cells.forEach(function (c, slot) {
          m.makeTranslation(centres[3 * c], centres[3 * c + 1], centres[3 * c + 2]);
          mesh.setMatrixAt(slot, m);
          var f = span[1] > span[0] ? (simT[c] - span[0]) / (span[1] - span[0]) : 1;
          times[slot] = to[0] + f * (to[1] - to[0]);
        });
        mesh.instanceMatrix.needsUpdate = true;
        mesh.userData.times = times;
        mesh.count = 0;
        deposit.add(mesh);
        depositMeshes.push(mesh);
        beadMeshes.push(mesh);
      });
      part.add(deposit);
      // The deviation from the target on the finished part: cubes binned by their surface deviation, blue
      // (shortfall) through white to red (excess), clipped at the 95th percentile of |deviation|.
      if (dep.deviation_mm) {
        var dev = decode(dep.deviation_mm, Float32Array), magnitudes = [];
        for (i = 0; i < dev.length; ++i) if (!isNaN(dev[i])) magnitudes.push(Math.abs(dev[i]));
        magnitudes.sort(function (p, q) { return p - q; });
        var range = Math.max(0.1, magnitudes.length ? magnitudes[Math.floor(0.95 * (magnitudes.length - 1))] : 0);
        var bins = 11, binned = [];
        for (i = 0; i <= bins; ++i) binned.push([]);
        for (i = 0; i < dep.count; ++i) {
          if (isNaN(dev[i])) { binned[bins].push(i); continue; }
          var u = Math.min(1, Math.max(0, 0.5 + 0.5 * dev[i] / range));
          binned[Math.min(bins - 1, Math.floor(u * bins))].push(i);
        }
        deviationGroup = new THREE.Group();
        binned.forEach(function (cells, bin) {
          if (!cells.length) return;
          var u = (bin + 0.5) / bins, c = bin === bins ? new THREE.Color(0xbbbbbb)
              : u < 0.5 ? new THREE.Color(1, 1, 1).lerp(new THREE.Color(0x2166ac), 1 - 2 * u)
                        : new THREE.Color(1, 1, 1).lerp(new THREE.Color(0xb2182b), 2 * u - 1);
          var mesh = new THREE.InstancedMesh(cube, new THREE.MeshLambertMaterial({ color: c }), cells.length);
          cells.forEach(function (cell, slot) {
            mesh.setMatrixAt(slot, m.makeTranslation(centres[3 * cell], centres[3 * cell + 1], centres[3 * cell + 2]));
          });
          mesh.instanceMatrix.needsUpdate = true;
          deviationGroup.add(mesh);
        });
        deviationGroup.visible = false;
        part.add(deviationGroup);
        document.getElementById('deviation-toggle').style.display = '';
        document.getElementById('deviation-scale').textContent = 'blue -' + range.toFixed(2) + ' mm, white 0, red +' +
            range.toFixed(2) + ' mm (rms ' + Number(dep.deviation_rms_mm).toFixed(2) + ' mm; the finished part)';
        document.getElementById('show-deviation').addEventListener('change', function (ev) {
          deviationGroup.visible = ev.target.checked;
          deposit.visible = !ev.target.checked && document.getElementById('show-deposit').checked;
        });
      }
      beads.visible = false;
      document.getElementById('show-beads').checked = false;
      document.getElementById('deposit-toggle').style.display = '';
      document.getElementById('show-deposit').addEventListener('change', function (ev) {
        deposit.visible = ev.target.checked;
      });
      document.getElementById('sampling').textContent += ' ' + dep.note + '.';
    }

    // The thermal model's temperatures (when the run had them): its grid's surface cells coloured by temperature at
    // the slider's time, interpolated between layer ends. A layer's end on the thermal timeline (which holds the
    // interpass waits) is mapped onto the end of that layer's welding on this page's clock; a layer's cells appear
    // when its welding starts.
    var thermalNode = document.getElementById('waam-thermal'), thermal = null;
    if (thermalNode) thermal = thermalView(JSON.parse(thermalNode.textContent));

    function thermalView(th) {
      var nc = th.count, ns = th.snapshots, centres = decode(th.centres, Float32Array);
      var levels = decode(th.levels, Uint8Array), snapLayer = decode(th.layer, Int32Array);
      var snapT = decode(th.time_s, Float32Array), spans = layerWeldSpans(), lastT = Math.max(snapT[ns - 1], 1e-9);
      var snapPage = new Float32Array(ns), startPage = new Float32Array(ns);
      for (var s = 0; s < ns; ++s) {
        var span = spans[snapLayer[s]];
        snapPage[s] = span ? span[1] : snapT[s] / lastT * frameT[nFrames - 1];
        startPage[s] = span ? span[0] : (s ? snapPage[s - 1] : 0);
      }
      // Cells in the order they appear (their first snapshot with metal).
      var first = new Int32Array(nc), order = [];
      for (var c = 0; c < nc; ++c) {
        for (s = 0; s < ns && levels[s * nc + c] === 255; ++s) {}
        first[c] = s;
        order.push(c);
      }
      order.sort(function (p, q) { return first[p] - first[q] || p - q; });
      var appear = new Float32Array(nc);
      var unit = new THREE.BoxBufferGeometry(th.cell_mm, th.cell_mm, th.cell_mm);
      var up = unit.attributes.position.array, un = unit.attributes.normal.array, ui = unit.index.array;
      var nv = up.length / 3, positions = new Float32Array(nc * up.length), normals = new Float32Array(nc * up.length);
      var colours = new Float32Array(nc * up.length), index = new Uint32Array(nc * ui.length);
      order.forEach(function (cell, slot) {
        appear[slot] = first[cell] < ns ? startPage[first[cell]] : Infinity;
        for (var v = 0; v < up.length; v += 3) {
          for (var a = 0; a < 3; ++a) {
            positions[slot * up.length + v + a] = up[v + a] + centres[3 * cell + a];
            normals[slot * up.length + v + a] = un[v + a];
          }
        }
        for (var k = 0; k < ui.length; ++k) index[slot * ui.length + k] = ui[k] + slot * nv;
      });
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
      geometry.setAttribute('normal', new THREE.BufferAttribute(normals, 3));
      geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
      geometry.setIndex(new THREE.BufferAttribute(index, 1));
      // Drawn in front of a coplanar table or plate of the cell.
      var mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors,
        polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -4 }));
      part.add(mesh);
      // Blue (ambient) through yellow to dark red (the hottest), 255 steps.
      var stops = [0x313695, 0x4575b4, 0x74add1, 0xfee090, 0xf46d43, 0xd73027, 0xa50026], lut = [];
      for (var l = 0; l <= 254; ++l) {
        var f = l / 254 * (stops.length - 1), j = Math.min(stops.length - 2, Math.floor(f));
        lut.push(new THREE.Color(stops[j]).lerp(new THREE.Color(stops[j + 1]), f - j));
      }
      var bar = stops.map(function (h, q) {
        return '#' + ('00000' + h.toString(16)).slice(-6) + ' ' + (100 * q / (stops.length - 1)).toFixed(0) + '%';
      });
      document.getElementById('thermal-bar').style.background = 'linear-gradient(to right, ' + bar.join(', ') + ')';
      document.getElementById('thermal-low').textContent = th.low_c.toFixed(0) + ' degC';
      document.getElementById('thermal-mid').textContent = (0.5 * (th.low_c + th.high_c)).toFixed(0) + ' degC';
      document.getElementById('thermal-high').textContent = th.high_c.toFixed(0) + ' degC';
      document.getElementById('thermal-scale').style.display = '';
      document.getElementById('thermal-toggle').style.display = '';
      document.getElementById('sampling').textContent += ' ' + th.note + '.';
      body.setAttribute('data-thermal-cells', String(nc));
      var view = { mesh: mesh, hottest: NaN };
      // Colours at page time t: between the snapshots around t (a cell not there yet at the earlier one takes the
      // later one's temperature).
      view.update = function (t) {
        var next = Math.min(ns - 1, upperIndex(snapPage, t) + 1), prev = next - 1;
        var alpha = prev < 0 ? 1 : Math.min(1, Math.max(0, (t - snapPage[prev]) / Math.max(1e-9, snapPage[next] -
                                                                                                 snapPage[prev])));
        var shown = upperIndex(appear, t) + 1, hottest = -1;
        for (var q = 0; q < shown; ++q) {
          var cell = order[q], b2 = levels[next * nc + cell], a2 = prev < 0 ? 255 : levels[prev * nc + cell];
          var level = a2 === 255 ? b2 : Math.round(a2 + alpha * (b2 - a2));
          if (level === 255) level = levels[first[cell] * nc + cell];
          hottest = Math.max(hottest, level);
          var colour = lut[level], o = q * up.length;
          for (var v = 0; v < up.length; v += 3) {
            colours[o + v] = colour.r; colours[o + v + 1] = colour.g; colours[o + v + 2] = colour.b;
          }
        }
        geometry.setDrawRange(0, shown * ui.length);
        geometry.attributes.color.needsUpdate = true;
        view.hottest = hottest < 0 ? NaN : th.low_c + hottest / 254 * (th.high_c - th.low_c);
        body.setAttribute('data-thermal-shown', String(shown));
      };
      return view;
    }

    // Violation markers and their list.
    var list = document.getElementById('violations'), markers = [], items = [];
    var markerGeometry = new THREE.SphereBufferGeometry(8, 16, 12);
    data.violations.forEach(function (v, index) {
      var marker = new THREE.Mesh(markerGeometry, new THREE.MeshBasicMaterial({ color: 0xd62728 }));
      marker.position.set(v.p_P[0], v.p_P[1], v.p_P[2]);
      part.add(marker);
      markers.push(marker);
      var li = document.createElement('li');
      var what = v.kind === 'collision' ? v.bodies.join(' / ') : v.joint;
      li.textContent = v.kind + (what ? ' ' + what : '') + ', layer ' + v.layer + ', point ' + v.point + ', ' +
                       v.unit + ' ' + Number(v.value).toFixed(2) + ', t = ' + Number(v.t_s).toFixed(1) + ' s';
      li.addEventListener('click', function () { jumpTo(index); });
      list.appendChild(li);
      items.push(li);
    });
    counts.violations = markers.length;
    document.getElementById('violation-count').textContent = '(' + markers.length + ')';
    if (!markers.length) list.innerHTML = '<li style="border:0;background:none">none</li>';

    var legend = document.getElementById('legend');
    legend.innerHTML = '<span style="background:#ff7f0e"></span>weld <span style="background:#9aa4b0"></span>' +
                       'travel <span style="background:#d62728"></span>violation' +
                       (target ? ' <span style="background:#4a90d9;opacity:.4"></span>target' : '');

    // The view: z up, looking at the cell's bodies from the front right.
    var camera = new THREE.PerspectiveCamera(40, view.clientWidth / view.clientHeight, 5, 200000);
    camera.up.set(0, 0, 1);
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    var duration = frameT[nFrames - 1];
    var time = 0, playing = false, speed = 100, highlighted = [];
    var requestRender = function () {};
    var qa = new THREE.Quaternion(), qb = new THREE.Quaternion();

    function pose(obj, array, offset, offset2, alpha) {
      obj.position.set(array[offset], array[offset + 1], array[offset + 2]);
      qa.set(array[offset + 3], array[offset + 4], array[offset + 5], array[offset + 6]);
      if (offset2 !== offset) {
        obj.position.lerp(b.set(array[offset2], array[offset2 + 1], array[offset2 + 2]), alpha);
        qb.set(array[offset2 + 3], array[offset2 + 4], array[offset2 + 5], array[offset2 + 6]);
        qa.slerp(qb, alpha);
      }
      obj.quaternion.copy(qa);
    }

    function setTime(t) {
      time = Math.min(Math.max(t, 0), duration);
      var f = Math.max(0, upperIndex(frameT, time)), f2 = Math.min(f + 1, nFrames - 1);
      var span = frameT[f2] - frameT[f], alpha = span > 0 ? (time - frameT[f]) / span : 0;
      var nb = bodies.length;
      for (var j = 0; j < nb; ++j) pose(bodies[j], bodyPoses, 7 * (f * nb + j), 7 * (f2 * nb + j), alpha);
      pose(part, partPoses, 7 * f, 7 * f2, alpha);
      beadMeshes.forEach(function (mesh) { mesh.count = upperIndex(mesh.userData.times, time) + 1; });
      if (thermal) thermal.update(time);
      document.getElementById('time').value = String(Math.round(1000 * time / Math.max(duration, 1e-9)));
      requestRender();
      document.getElementById('clock').textContent = 't = ' + time.toFixed(1) + ' s of ' + duration.toFixed(1) +
          ' s, layer ' + frameLayer[f] + ', ' + (frameWeld[f] ? 'welding' : 'travel') +
          (thermal && !isNaN(thermal.hottest) ? ', hottest ' + thermal.hottest.toFixed(0) + ' degC' : '');
    }

    function setHighlight(names) {
      highlighted.forEach(function (g) { g.userData.materials.forEach(function (mt) { mt.emissive.setHex(0); }); });
      highlighted = names.map(function (nm) { return bodyByName[nm]; }).filter(Boolean);
      highlighted.forEach(function (g) {
        g.userData.materials.forEach(function (mt) { mt.emissive.setHex(0xcc0000); });
      });
    }

    function jumpTo(index) {
      var v = data.violations[index];
      playing = false;
      document.getElementById('play').textContent = 'Play';
      items.forEach(function (li, j) { li.className = j === index ? 'active' : ''; });
      markers.forEach(function (mk, j) { mk.scale.setScalar(j === index ? 2.5 : 1); });
      setHighlight(v.highlight);
      body.setAttribute('data-highlighted', v.highlight.join(' '));
      setTime(v.t_s);
    }

    document.getElementById('play').addEventListener('click', function (ev) {
      playing = !playing;
      if (playing && time >= duration) setTime(0);
      ev.target.textContent = playing ? 'Pause' : 'Play';
    });
    document.getElementById('speed').addEventListener('change', function (ev) { speed = +ev.target.value; });
    document.getElementById('time').addEventListener('input', function (ev) {
      setTime(duration * ev.target.value / 1000);
    });
    document.getElementById('colour').addEventListener('change', function (ev) {
      pathGeometry.setAttribute('color', new THREE.BufferAttribute(ev.target.value === 'layer' ? byLayer : byWeld, 3));
    });
    document.getElementById('show-path').addEventListener('change', function (ev) { path.visible = ev.target.checked; });
    document.getElementById('show-beads').addEventListener('change', function (ev) {
      beads.visible = ev.target.checked;
    });
    if (thermal) {
      // The temperatures stand in for the beads and the deposit while shown.
      var showThermal = function (on) {
        thermal.mesh.visible = on;
        beads.visible = !on && document.getElementById('show-beads').checked;
        deposit.visible = !on && document.getElementById('show-deposit').checked;
      };
      document.getElementById('show-thermal').addEventListener('change', function (ev) {
        showThermal(ev.target.checked);
      });
      showThermal(true);
    }
    document.getElementById('show-target').addEventListener('change', function (ev) {
      if (target) target.visible = ev.target.checked;
    });
    window.addEventListener('resize', function () {
      camera.aspect = view.clientWidth / view.clientHeight;
      camera.updateProjectionMatrix();
      renderer.setSize(view.clientWidth, view.clientHeight);
    });

    // Start where the URL says (viewer.html#t=0.6&view=part: at 60 % of the build time, the part framed), else at
    // the start with the whole cell in view.
    var match = /t=([0-9.]+)/.exec(window.location.hash);
    setTime(match ? duration * Math.min(1, +match[1]) : 0);

    // Frame the cell (the floor left out) or the part (its path and target), from the front right.
    function frameOn(what) {
      scene.updateMatrixWorld(true);
      var bounds = new THREE.Box3();
      if (what === 'part') {
        bounds.expandByObject(path);
        if (target) bounds.expandByObject(target);
      } else {
        bodies.forEach(function (g, j) { if (data.bodies[j].name !== 'world') bounds.expandByObject(g); });
        bounds.expandByObject(part);
      }
      if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-1000, -1000, 0), new THREE.Vector3(1000, 1000, 1500));
      var centre = bounds.getCenter(new THREE.Vector3());
      var size = Math.max(bounds.getSize(new THREE.Vector3()).length(), 50) * (what === 'part' ? 1.6 : 1);
      camera.position.copy(centre).add(new THREE.Vector3(0.75, -1.05, 0.6).multiplyScalar(size));
      controls.target.copy(centre);
      controls.update();
    }
    document.getElementById('frame-cell').addEventListener('click', function () { frameOn('cell'); });
    document.getElementById('frame-part').addEventListener('click', function () { frameOn('part'); });
    frameOn(/view=part/.test(window.location.hash) ? 'part' : 'cell');
    // viewer.html#play: start playing (at the speed of #speed=<x>, default 100x).
    var speedMatch = /speed=([0-9.]+)/.exec(window.location.hash);
    if (speedMatch) speed = +speedMatch[1];
    playing = /play/.test(window.location.hash);
    if (playing) document.getElementById('play').textContent = 'Pause';
    // viewer.html#deviation: the deviation colours on (when the run has them).
    if (deviationGroup && /deviation/.test(window.location.hash)) {
      document.getElementById('show-deviation').checked = true;
      deviationGroup.visible = true;
      deposit.visible = false;
    }
    // viewer.html#violation=<i>: open at the i-th violation (from 0), as a click on it in the list does.
    var violationMatch = /violation=([0-9]+)/.exec(window.location.hash);
    if (violationMatch && +violationMatch[1] < markers.length) jumpTo(+violationMatch[1]);

    // Draw on demand (a change of time, view or settings; every frame while playing), so an idle page costs nothing.
    var last = null, pending = false;
    function frame(now) {
      pending = false;
      if (playing) {
        if (last !== null) setTime(time + speed * (now - last) / 1000);
        last = now;
        if (time >= duration) { playing = false; document.getElementById('play').textContent = 'Play'; }
      }
      if (playing) requestRender(); else last = null;
      renderer.render(scene, camera);
    }
    requestRender = function () {
      if (!pending) { pending = true; requestAnimationFrame(frame); }
    };
    controls.addEventListener('change', requestRender);
    ['play', 'speed', 'time', 'colour', 'show-path', 'show-beads', 'show-deposit', 'show-deviation', 'show-target',
     'show-thermal', 'frame-cell', 'frame-part']
        .forEach(function (id) {
          document.getElementById(id).addEventListener(id === 'time' ? 'input' : 'change', requestRender);
          document.getElementById(id).addEventListener('click', requestRender);
        });
    window.addEventListener('resize', requestRender);
    renderer.render(scene, camera);
    if (playing) requestRender();
  }

  try {
    start();
  } catch (e) {
    errors.push(String(e && e.message ? e.message : e));
  }
  finish();
})();
