/* geargen design review: the assembly (GEARGEN_MODEL, a GLB as base64) with the build's check
   numbers and report tables (GEARGEN_REVIEW), all loaded as classic scripts so the page opens
   from file:// without a server. THREE is the vendored bundle (three-bundle.min.js).
   The page's state is on <body>: data-loaded="true" and data-parts="N" once the model is shown,
   data-error="..." if it cannot be. */
(function () {
  "use strict";

  var data = window.GEARGEN_REVIEW;
  var body = document.body;
  var unit = data.length_unit;
  var perUnit = data.mm_per_unit;

  // geargen's assembly frame (mm, z up) in the glTF scene (m, y up): the GLB's root node turns
  // (x, y, z) mm into (x, z, -y) / 1000, so a design axis is this world direction
  var AXES = { x: [1, 0, 0], y: [0, 0, -1], z: [0, 1, 0] };

  function el(tag, attrs, text) {
    var e = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) { e.setAttribute(k, attrs[k]); });
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function length(mm) {
    return (mm === null || mm === undefined) ? "-" : Number((mm / perUnit).toPrecision(5)).toString();
  }

  function fail(message) {
    body.setAttribute("data-error", message);
    var box = document.getElementById("viewport");
    box.textContent = "";
    box.appendChild(el("p", { "class": "error" }, "The model cannot be shown: " + message));
  }

  // ------------------------------------------------------------------ side panel: report tables

  function reportTables() {
    var panel = document.getElementById("tables");
    data.sections.forEach(function (section) {
      var d = el("details");
      if (section.open) d.open = true;
      d.appendChild(el("summary", {}, section.title));
      section.blocks.forEach(function (b) {
        if (b.kind === "table") {
          var t = el("table");
          var tr = el("tr");
          b.header.forEach(function (h) { tr.appendChild(el("th", {}, h)); });
          t.appendChild(tr);
          b.rows.forEach(function (r) {
            var row = el("tr");
            r.forEach(function (c) { row.appendChild(el("td", {}, c)); });
            t.appendChild(row);
          });
          d.appendChild(t);
        } else if (b.kind === "pre") {
          d.appendChild(el("pre", {}, b.text));
        } else if (b.kind === "list") {
          var ul = el("ul");
          b.items.forEach(function (i) { ul.appendChild(el("li", {}, i)); });
          d.appendChild(ul);
        } else {
          d.appendChild(el("p", {}, b.text));
        }
      });
      panel.appendChild(d);
    });
  }

  // ------------------------------------------------------------------ mesh numbers

  function meshesOf(part) {
    return data.meshes.filter(function (m) { return m.gear1 === part || m.gear2 === part; });
  }

  function meshVerdict(m) {
    if (!m.engaged) return "disengaged";
    return m.failures && m.failures.length ? "FAIL: " + m.failures.join("; ") : "ok";
  }

  function meshTable(m) {
    var t = el("table", { "class": "mesh" });
    function row(label, value) {
      var tr = el("tr");
      tr.appendChild(el("th", {}, label));
      tr.appendChild(el("td", {}, value));
      t.appendChild(tr);
    }
    row("mesh", m.mesh + " (" + m.gear1 + " / " + m.gear2 + ")");
    row("verdict", meshVerdict(m));
    row("design backlash (" + unit + ")", length(m.design_min) + " to " + length(m.design_max));
    if (m.engaged) {
      row("backlash, exact outlines (" + unit + ")", length(m.backlash_min) + " to " + length(m.backlash_max));
      row("backlash, solids' sections (" + unit + ")", m.path2_backlash_min === undefined ? "not run"
        : length(m.path2_backlash_min) + " to " + length(m.path2_backlash_max));
      row("min tip clearance (" + unit + ")", length(m.min_tip_clearance));
      row("interference depth, max (" + unit + ")", length(m.interference_depth_max));
      row("contact ratio", m.contact_ratio === undefined || m.contact_ratio === null ? "-"
        : Number(m.contact_ratio.toPrecision(4)).toString());
    } else {
      row("axial clearance (" + unit + ")", length(m.axial_clearance));
    }
    row("centre distance (" + unit + ")", length(m.centre_distance));
    var tol = data.tolerances.filter(function (x) { return x.mesh === m.mesh; })[0];
    if (tol) {
      row("worst-case min backlash (" + unit + ")", length(tol.worst_case_min_backlash));
    }
    t.classList.add(m.engaged && m.failures && m.failures.length ? "failing" : "passing");
    return t;
  }

  function partInfo(name) {
    var p = data.parts.filter(function (x) { return x.name === name; })[0];
    var box = el("div");
    box.appendChild(el("h3", {}, name));
    if (p) box.appendChild(el("p", {}, p.kind + " in " + p.group + (p.description ? ": " + p.description : "")));
    meshesOf(name).forEach(function (m) { box.appendChild(meshTable(m)); });
    return box;
  }

  function showInfo(node) {
    var info = document.getElementById("info");
    info.textContent = "";
    if (node) info.appendChild(node);
  }

  // ------------------------------------------------------------------ the 3-D view

  if (typeof THREE === "undefined" || !window.GEARGEN_MODEL) {
    fail("the viewer library or the model did not load (three-bundle.min.js, model.js)");
    reportTables();
    return;
  }

  var viewport = document.getElementById("viewport");
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    fail("this browser gives no WebGL (" + e.message + ")");
    reportTables();
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xf4f5f7, 1);
  viewport.appendChild(renderer.domElement);

  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(35, 1, 0.001, 10);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.6));
  var key = new THREE.DirectionalLight(0xffffff, 2.2);
  key.position.set(-0.35, 0.45, 1.0);  // from the viewer's upper left, as the report's rendered view
  camera.add(key);
  scene.add(camera);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);

  var parts = {};      // part name -> its object in the scene
  var partMeshes = []; // every mesh that belongs to a part (for picking)
  var model = null;
  var selected = [];
  var hovered = null;
  var sectionPlane = new THREE.Plane(new THREE.Vector3(1, 0, 0), 0);

  function render() { renderer.render(scene, camera); }

  function resize() {
    var w = viewport.clientWidth || 800, h = viewport.clientHeight || 600;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  }

  function visibleBox() {
    var box = new THREE.Box3();
    Object.keys(parts).forEach(function (n) { if (parts[n].visible) box.expandByObject(parts[n]); });
    return box.isEmpty() ? new THREE.Box3().setFromObject(model) : box;
  }

  // the report's view: azimuth -60 deg from +x towards +y, elevation 30 deg, z up (design frame)
  function frame() {
    var sphere = visibleBox().getBoundingSphere(new THREE.Sphere());
    var az = -60 * Math.PI / 180, elv = 30 * Math.PI / 180;
    var d = [Math.cos(elv) * Math.cos(az), Math.cos(elv) * Math.sin(az), Math.sin(elv)];
    var dir = new THREE.Vector3(d[0], d[2], -d[1]);
    var half = camera.fov * Math.PI / 360;
    var fit = Math.min(Math.tan(half), Math.tan(half) * camera.aspect);
    var dist = sphere.radius / Math.sin(Math.atan(fit)) * 1.05;
    camera.up.set(0, 1, 0);
    camera.position.copy(sphere.center).addScaledVector(dir, dist);
    camera.near = dist / 100;
    camera.far = dist * 10;
    camera.updateProjectionMatrix();
    controls.target.copy(sphere.center);
    controls.update();
    render();
  }

  function setHighlight(obj, colour) {
    obj.traverse(function (o) { if (o.isMesh) o.material.emissive.setHex(colour); });
  }

  function refreshHighlights() {
    Object.keys(parts).forEach(function (n) { setHighlight(parts[n], 0x000000); });
    if (hovered) setHighlight(hovered, 0x2a2a2a);
    selected.forEach(function (n) { setHighlight(parts[n], 0xc06a00); });
    document.querySelectorAll("#tree .part").forEach(function (row) {
      row.classList.toggle("selected", selected.indexOf(row.getAttribute("data-part")) >= 0);
    });
    render();
  }

  function select(names, info) {
    selected = names.filter(function (n) { return parts[n]; });
    showInfo(info);
    refreshHighlights();
  }

  function setVisible(name, on) {
    parts[name].visible = on;
    var box = document.querySelector('#tree .part[data-part="' + CSS.escape(name) + '"] input');
    if (box) box.checked = on;
  }

  function isolate(names) {
    Object.keys(parts).forEach(function (n) { setVisible(n, names.indexOf(n) >= 0); });
    syncGroups();
    render();
  }

  function syncGroups() {
    document.querySelectorAll("#tree .group").forEach(function (g) {
      var boxes = g.querySelectorAll(".part input");
      var on = Array.prototype.filter.call(boxes, function (b) { return b.checked; }).length;
      var head = g.querySelector("summary input");
      head.checked = on === boxes.length;
      head.indeterminate = on > 0 && on < boxes.length;
    });
  }

  function partTree() {
    var tree = document.getElementById("tree");
    var groups = {};
    data.parts.forEach(function (p) {
      if (!parts[p.name]) return;
      (groups[p.group] = groups[p.group] || []).push(p);
    });
    Object.keys(groups).forEach(function (g) {
      var d = el("details", { "class": "group", open: "" });
      var s = el("summary");
      var gbox = el("input", { type: "checkbox", title: "show or hide the group" });
      gbox.checked = true;
      gbox.addEventListener("click", function (ev) { ev.stopPropagation(); });
      gbox.addEventListener("change", function () {
        groups[g].forEach(function (p) { setVisible(p.name, gbox.checked); });
        syncGroups();
        render();
      });
      s.appendChild(gbox);
      s.appendChild(document.createTextNode(" " + g + " (" + groups[g].length + ")"));
      d.appendChild(s);
      groups[g].forEach(function (p) {
        var row = el("div", { "class": "part", "data-part": p.name, title: p.description || p.kind });
        var box = el("input", { type: "checkbox", title: "show or hide" });
        box.checked = true;
        box.addEventListener("change", function () { setVisible(p.name, box.checked); syncGroups(); render(); });
        var label = el("span", { "class": "name" }, p.name);
        label.addEventListener("click", function () { select([p.name], partInfo(p.name)); });
        var iso = el("button", { title: "show this part alone" }, "isolate");
        iso.addEventListener("click", function () { isolate([p.name]); select([p.name], partInfo(p.name)); });
        row.appendChild(box);
        row.appendChild(label);
        row.appendChild(iso);
        d.appendChild(row);
      });
      tree.appendChild(d);
    });
  }

  function meshList() {
    var list = document.getElementById("meshes");
    data.meshes.forEach(function (m) {
      var row = el("div", { "class": "meshrow " + (m.engaged && m.failures && m.failures.length ? "failing" : "passing") });
      row.appendChild(el("span", { "class": "name" }, m.mesh));
      row.appendChild(el("span", {}, " " + m.gear1 + " / " + m.gear2 + ": " + (m.engaged
        ? length(m.backlash_min) + " to " + length(m.backlash_max) + " " + unit : "disengaged")));
      row.addEventListener("click", function () {
        var box = el("div");
        box.appendChild(meshTable(m));
        select([m.gear1, m.gear2], box);
      });
      list.appendChild(row);
    });
  }

  // ------------------------------------------------------------------ section plane

  function section() {
    var axis = document.getElementById("section-axis").value;
    var slider = document.getElementById("section-pos");
    var label = document.getElementById("section-value");
    if (axis === "none") {
      renderer.clippingPlanes = [];
      slider.disabled = true;
      label.textContent = "";
      render();
      return;
    }
    var n = new THREE.Vector3().fromArray(AXES[axis]);
    var box = new THREE.Box3().setFromObject(model);
    var corners = [box.min, box.max].map(function (c) { return n.dot(c) * 1000; });  // design mm
    var lo = Math.min.apply(null, corners), hi = Math.max.apply(null, corners);
    if (slider.getAttribute("data-axis") !== axis) {  // a new axis starts at the middle
      slider.setAttribute("data-axis", axis);
      slider.value = 500;
    }
    slider.disabled = false;
    var mm = lo + (hi - lo) * slider.value / 1000;
    var keepAbove = document.getElementById("section-flip").checked;
    // three.js keeps what lies on the plane's positive side: n.p + c >= 0
    sectionPlane.normal.copy(n).multiplyScalar(keepAbove ? 1 : -1);
    sectionPlane.constant = (keepAbove ? -1 : 1) * mm / 1000;
    renderer.clippingPlanes = [sectionPlane];
    label.textContent = axis + " = " + length(mm) + " " + unit;
    render();
  }

  // ------------------------------------------------------------------ picking

  var raycaster = new THREE.Raycaster();
  var pointer = new THREE.Vector2();
  var tip = document.getElementById("tooltip");

  function partAt(ev) {
    var r = renderer.domElement.getBoundingClientRect();
    pointer.set((ev.clientX - r.left) / r.width * 2 - 1, -(ev.clientY - r.top) / r.height * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    var hits = raycaster.intersectObjects(partMeshes.filter(function (m) { return m.parent && visibleChain(m); }), false);
    for (var i = 0; i < hits.length; i++) {
      if (renderer.clippingPlanes.length && renderer.clippingPlanes[0].distanceToPoint(hits[i].point) < 0) continue;
      return partOf(hits[i].object);
    }
    return null;
  }

  function visibleChain(o) {
    for (; o; o = o.parent) if (!o.visible) return false;
    return true;
  }

  function partOf(o) {
    for (; o; o = o.parent) if (o.userData && o.userData.part) return o.userData.part;
    return null;
  }

  renderer.domElement.addEventListener("pointermove", function (ev) {
    var name = partAt(ev);
    var obj = name ? parts[name] : null;
    if (obj !== hovered) { hovered = obj; refreshHighlights(); }
    if (!name) { tip.hidden = true; return; }
    var ms = meshesOf(name);
    tip.textContent = name + (ms.length ? "\n" + ms.map(function (m) {
      return m.mesh + ": " + (m.engaged ? length(m.backlash_min) + " to " + length(m.backlash_max) + " " + unit + ", "
        : "") + meshVerdict(m);
    }).join("\n") : "");
    var r = viewport.getBoundingClientRect();
    tip.style.left = (ev.clientX - r.left + 14) + "px";
    tip.style.top = (ev.clientY - r.top + 14) + "px";
    tip.hidden = false;
  });
  renderer.domElement.addEventListener("pointerleave", function () { tip.hidden = true; hovered = null; refreshHighlights(); });

  var down = null;
  renderer.domElement.addEventListener("pointerdown", function (ev) { down = [ev.clientX, ev.clientY]; });
  renderer.domElement.addEventListener("pointerup", function (ev) {
    if (!down || Math.abs(ev.clientX - down[0]) + Math.abs(ev.clientY - down[1]) > 4) return;  // a drag orbits
    var name = partAt(ev);
    if (name) select([name], partInfo(name)); else select([], null);
  });

  // ------------------------------------------------------------------ a view named in the address

  // index.html#part=NAME, #mesh=NAME, #isolate=NAME,NAME, #section=x|y|z&at=0..1 (a link to a view)
  function fromAddress() {
    var args = {};
    location.hash.replace(/^#/, "").split("&").forEach(function (kv) {
      var i = kv.indexOf("=");
      if (i > 0) args[decodeURIComponent(kv.slice(0, i))] = decodeURIComponent(kv.slice(i + 1));
    });
    if (args.isolate) isolate(args.isolate.split(",").filter(function (n) { return parts[n]; }));
    if (args.part && parts[args.part]) select([args.part], partInfo(args.part));
    var m = data.meshes.filter(function (x) { return x.mesh === args.mesh; })[0];
    if (m) {
      var box = el("div");
      box.appendChild(meshTable(m));
      select([m.gear1, m.gear2], box);
    }
    if (AXES[args.section]) {
      document.getElementById("section-axis").value = args.section;
      section();
      if (args.at !== undefined) {
        document.getElementById("section-pos").value = Math.round(1000 * Math.min(1, Math.max(0, Number(args.at))));
        section();
      }
    }
  }

  // ------------------------------------------------------------------ loading

  function base64Bytes(text) {
    var raw = atob(text);
    var out = new Uint8Array(raw.length);
    for (var i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
    return out;
  }

  reportTables();
  var bytes = base64Bytes(window.GEARGEN_MODEL.glb_base64);
  new THREE.GLTFLoader().parse(bytes.buffer, "", function (gltf) {
    model = gltf.scene;
    model.traverse(function (o) {
      if (o.userData && o.userData.part) parts[o.userData.part] = o;
      if (o.isMesh) {
        o.material = o.material.clone();  // highlighting one part must not light its twins
        if (o.material.transparent) o.material.depthWrite = false;
        partMeshes.push(o);
      }
    });
    scene.add(model);
    partTree();
    meshList();
    document.getElementById("show-all").addEventListener("click", function () {
      isolate(Object.keys(parts));
    });
    document.getElementById("isolate-selection").addEventListener("click", function () {
      if (selected.length) isolate(selected);
    });
    document.getElementById("frame").addEventListener("click", frame);
    ["section-axis", "section-flip"].forEach(function (id) {
      document.getElementById(id).addEventListener("change", section);
    });
    document.getElementById("section-pos").addEventListener("input", section);
    controls.addEventListener("change", render);
    window.addEventListener("resize", resize);
    resize();
    frame();
    fromAddress();
    body.setAttribute("data-parts", String(Object.keys(parts).length));
    body.setAttribute("data-loaded", "true");
  }, function (err) {
    fail("the model could not be read (" + (err && err.message ? err.message : err) + ")");
  });
})();
