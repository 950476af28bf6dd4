// viewer_shapes.js: helpers of viewer.js (three.js r111): base64 typed arrays, MuJoCo geoms as three.js objects,
// layer colours, and the search of sorted times. Sets window.waamViewerShapes.
(function () {
  'use strict';

  function decode(b64, Type) {
    var raw = atob(b64 || '');
    var bytes = new Uint8Array(raw.length);
    for (var i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
    return new Type(bytes.buffer);
  }

  function colour(rgba) { return new THREE.Color(rgba[0], rgba[1], rgba[2]); }

  // One three.js object for a MuJoCo geom (its frame: z is the axis of capsules and cylinders).
  function geomObject(g, material) {
    var s = g.size, obj;
    if (g.type === 'box') {
      obj = new THREE.Mesh(new THREE.BoxBufferGeometry(2 * s[0], 2 * s[1], 2 * s[2]), material);
    } else if (g.type === 'sphere') {
      obj = new THREE.Mesh(new THREE.SphereBufferGeometry(s[0], 24, 16), material);
    } else if (g.type === 'cylinder' || g.type === 'capsule') {
      var cyl = new THREE.CylinderBufferGeometry(s[0], s[0], 2 * s[1], 24);
      cyl.rotateX(Math.PI / 2);
      obj = new THREE.Group();
      obj.add(new THREE.Mesh(cyl, material));
      if (g.type === 'capsule') {
        [-1, 1].forEach(function (side) {
          var cap = new THREE.Mesh(new THREE.SphereBufferGeometry(s[0], 24, 12), material);
          cap.position.set(0, 0, side * s[1]);
          obj.add(cap);
        });
      }
    } else if (g.type === 'plane') {
      var w = s[0] > 0 ? 2 * s[0] : 4000, h = s[1] > 0 ? 2 * s[1] : 4000;
      obj = new THREE.Mesh(new THREE.PlaneBufferGeometry(w, h), material);
      var grid = new THREE.GridHelper(Math.max(w, h), 20, 0x999999, 0xbbbbbb);
      grid.rotation.x = Math.PI / 2;
      grid.position.z = 0.5;
      obj.add(grid);
    } else if (g.type === 'mesh' && g.vertices) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(decode(g.vertices, Float32Array), 3));
      geometry.setIndex(new THREE.BufferAttribute(decode(g.triangles, Uint32Array), 1));
      geometry.computeVertexNormals();
      obj = new THREE.Mesh(geometry, material);
    } else {
      return null;
    }
    var p = g.pose;
    obj.position.set(p[0], p[1], p[2]);
    obj.quaternion.set(p[3], p[4], p[5], p[6]);
    return obj;
  }

  function layerColour(layer, layers) {
    return new THREE.Color().setHSL(0.66 * (1 - layer / Math.max(1, layers - 1)), 0.75, 0.5);
  }

  // Largest index i with values[i] <= x (-1 when none).
  function upperIndex(values, x) {
    var lo = 0, hi = values.length;
    while (lo < hi) {
      var mid = (lo + hi) >> 1;
      if (values[mid] <= x) lo = mid + 1; else hi = mid;
    }
    return lo - 1;
  }

  window.waamViewerShapes = { decode: decode, colour: colour, geomObject: geomObject, layerColour: layerColour,
                              upperIndex: upperIndex };
})();
