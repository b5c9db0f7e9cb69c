/* view.js - the page csfview(1) writes: a 3-D animation of the objects whose
 * pos was watched and a plot of every column against time, one panel per unit.
 *
 * Design: the page carries the run as CSV text (<script id="csv">, every
 * k-th row of the run as csfview decimated it) and the facts csfview worked
 * out from the scene and the whole CSV as window.CSF_META, in metres: rows
 * in the run, k, the scene's end time, the radii, the box of every object's
 * centre over the run, the planes each with the rectangle to draw, the fixed
 * objects (anchors) with their positions, and the links (rods, strings,
 * springs) between two objects. The CSV is parsed into one Float64Array per
 * column. An object is a NAME.pos.x/.y/.z triple, or a fixed object of the
 * scene at its scene position when the CSV has no pos of it; its radius is
 * CSF_META's, else a size that shows. A link is a line between the centres
 * of its two objects: a rod solid, a string solid when taut and dashed when
 * slack, a spring a zigzag.
 * One time, state.t, drives everything: the spheres (linear between rows),
 * their trails, the links, the slider, the readout table and the cursor in
 * every plot.
 * three.js (libjs-three) draws the scene; OrbitControls turns and zooms it;
 * a scene that is flat (every z = 0, or every y = 0) is shown face-on with an
 * orthographic camera. dygraphs (libjs-dygraphs) draws the plots; zooming one
 * zooms all, a click on one sets the time. The fragment #t=SECONDS sets the
 * time at load and pauses; the readout's rows carry the shown position in
 * data-pos, so a test can read it from the DOM.
 */
(function () {
	'use strict';

	var LENGTH = { m: 1, cm: 0.01, mm: 0.001, km: 1000, ft: 0.3048, in: 0.0254 };
	var COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd',
		'#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
	var FIXED = '#666666';   /* anchors and other fixed objects */
	/* how each kind of link is drawn: its colour and its name in the legend */
	var LINKS = { rod: '#333333', string: '#a0522d', spring: '#2a9d4a' };
	/* a string is slack while its length is short of L by more than this part of L */
	var SLACK = 1e-6;
	var meta = window.CSF_META ||
		{ rows: 0, stride: 1, till: null, planes: [], radii: {}, box: null, anchors: [], links: [] };

	/* The CSV text as {cols: [{name, unit}], data: [Float64Array per column], n}. */
	function parseCsv(text) {
		var lines = text.replace(/\\x3c/g, '<').split('\n').filter(function (l) { return l.trim() !== ''; });
		var cols = lines[0].split(',').map(function (h) {
			var m = /^\s*(.*?)\s*\[([^\]]*)\]\s*$/.exec(h);
			return m ? { name: m[1], unit: m[2] } : { name: h.trim(), unit: '' };
		});
		if (cols[0].name === 't' && !cols[0].unit) cols[0].unit = 's';   /* csfvm's time is in seconds */
		var n = lines.length - 1;
		var data = cols.map(function () { return new Float64Array(n); });
		for (var r = 0; r < n; r++) {
			var f = lines[r + 1].split(',');
			for (var c = 0; c < cols.length; c++) data[c][r] = Number(f[c]);
		}
		return { cols: cols, data: data, n: n };
	}

	/* A number in at most 6 significant digits. */
	function fmt(v) {
		return String(Number(v.toPrecision(6)));
	}

	function label(col) {
		return col.unit ? col.name + ' [' + col.unit + ']' : col.name;
	}

	var run = parseCsv(document.getElementById('csv').textContent);
	var cols = run.cols, data = run.data, n = run.n;
	var T = data[0];
	var t0 = T[0], t1 = T[n - 1];
	var tunit = cols[0].unit;
	var byName = {};
	cols.forEach(function (c, i) { byName[c.name] = i; });

	/* The column triple NAME.P.x/.y/.z (P.x... when NAME is ''), or null. */
	function triple(name, p) {
		var base = name === '' ? p : name + '.' + p;
		var ix = byName[base + '.x'], iy = byName[base + '.y'], iz = byName[base + '.z'];
		return ix !== undefined && iy !== undefined && iz !== undefined ? [ix, iy, iz] : null;
	}

	/* ---- the header: columns, units, decimation ---- */
	var units = {};
	cols.forEach(function (c, i) {
		if (i === 0) return;
		var u = c.unit || '(no unit)';
		(units[u] = units[u] || []).push(c.name);
	});
	document.getElementById('info').textContent = 'Columns by unit: ' + label(cols[0]) + '; ' +
		Object.keys(units).map(function (u) { return '[' + u + '] ' + units[u].join(', '); }).join('; ') + '.';
	var rowsInRun = meta.rows || n;
	document.getElementById('decimation').textContent = meta.stride > 1
		? 'Decimated for display: the run has ' + rowsInRun + ' rows; every ' + meta.stride +
		  'th row (and the last) is shown, ' + n + ' rows.'
		: n + ' rows, all shown.';
	document.getElementById('tunit').textContent = tunit;

	/* ---- the objects, links and planes ---- */
	/* objects: {name, i: its pos columns (or at: its fixed position), fixed, color, radius} */
	var anchors = {};
	(meta.anchors || []).forEach(function (a) { anchors[a.name] = a; });
	var objects = [], moving = 0;
	cols.forEach(function (c) {
		var m = /^(?:(.*)\.)?pos\.x$/.exec(c.name);
		var ix = m && triple(m[1] || '', 'pos');
		if (!ix) return;
		var name = m[1] || 'pos', fixed = name in anchors;
		objects.push({ name: name, i: ix, fixed: fixed, color: fixed ? FIXED : COLORS[moving++ % COLORS.length] });
	});
	var posUnit = objects.length ? cols[objects[0].i[0]].unit : 'm';
	var perMetre = 1 / (LENGTH[posUnit] || 1);   /* display units in a metre */
	var inCsv = objects.length;   /* objects[0 .. inCsv - 1] have columns */
	function scaled(a) {
		return a.map(function (v) { return v * perMetre; });
	}
	var objectByName = {};
	objects.forEach(function (o) { objectByName[o.name] = o; });
	(meta.anchors || []).forEach(function (a) {
		if (a.pos && !(a.name in objectByName))
			objects.push(objectByName[a.name] = { name: a.name, at: scaled(a.pos), fixed: true, color: FIXED });
	});
	objects.forEach(function (o) {
		o.radius = meta.radii[o.name] !== undefined ? meta.radii[o.name] * perMetre : 0;
	});

	/* links: {a, b (objects, or undefined when the page has no position of one), names, kind, length, op} */
	var links = (meta.links || []).map(function (l) {
		return { a: objectByName[l.a], b: objectByName[l.b], names: [l.a, l.b], kind: l.kind,
			length: l.length === null ? null : l.length * perMetre, op: l.op };
	});

	var bounds = meta.box || { lo: [0, 0, 0], hi: [0, 0, 0] };   /* of every centre over the run */
	var lo = scaled(bounds.lo), hi = scaled(bounds.hi);
	var extent = 0, maxR = 0;
	objects.forEach(function (o) { maxR = Math.max(maxR, o.radius); });
	for (var k = 0; k < 3; k++) extent = Math.max(extent, hi[k] - lo[k]);
	extent = Math.max(extent, 4 * maxR);
	if (!(extent > 0)) extent = 1;
	var centre = objects.length ? [0, 1, 2].map(function (k) { return (lo[k] + hi[k]) / 2; }) : [0, 0, 0];
	var flatZ = objects.length && Math.max(Math.abs(lo[2]), Math.abs(hi[2])) <= 1e-12 * extent;
	var flatY = objects.length && Math.max(Math.abs(lo[1]), Math.abs(hi[1])) <= 1e-12 * extent;
	var mode = flatZ ? 'xy' : flatY ? 'xz' : '3d';
	document.getElementById('viewmode').textContent = !objects.length ? '' :
		mode === 'xy' ? 'Face-on: the x-y plane (every z = 0). Drag to pan, wheel to zoom.'
		: mode === 'xz' ? 'Face-on: the x-z plane (every y = 0). Drag to pan, wheel to zoom.'
		: 'Drag to turn, right-drag to pan, wheel to zoom.';

	/* planes: the rectangles csfview worked out (the box and a margin, projected onto each) */
	var planes = (meta.planes || []).filter(function (p) { return p.size; }).map(function (p) {
		return { name: p.name, centre: scaled(p.centre), u: p.u, v: p.v, size: scaled(p.size) };
	});

	/* ---- time ---- */
	var state = { t: t0, playing: false, speed: 1, dirty: true, row: -1 };
	var slider = document.getElementById('slider');
	var timeEl = document.getElementById('time');
	var playBtn = document.getElementById('play');
	slider.min = t0;
	slider.max = t1;

	/* the last row whose t is at or before t */
	function rowAt(t) {
		var a = 0, b = n - 1;
		if (t <= T[0]) return 0;
		if (t >= T[b]) return b;
		while (b - a > 1) {
			var m = (a + b) >> 1;
			if (T[m] <= t) a = m; else b = m;
		}
		return a;
	}

	/* the row nearest to t */
	function nearestRow(t) {
		var row = rowAt(t);
		return row + 1 < n && T[row + 1] - t < t - T[row] ? row + 1 : row;
	}

	/* the position of object o at time t, between the rows around it */
	function positionAt(o, t) {
		if (o.at) return o.at.slice();
		var i = rowAt(t), j = Math.min(i + 1, n - 1);
		var f = j > i && T[j] > T[i] ? Math.min(1, Math.max(0, (t - T[i]) / (T[j] - T[i]))) : 0;
		return o.i.map(function (c) { return data[c][i] + f * (data[c][j] - data[c][i]); });
	}

	function distance(p, q) {
		return Math.sqrt(Math.pow(p[0] - q[0], 2) + Math.pow(p[1] - q[1], 2) + Math.pow(p[2] - q[2], 2));
	}

	/* a string of known length at row r: slack while shorter than it (longer, for >=) */
	function slackAt(l, r) {
		var p = l.a.at || l.a.i.map(function (c) { return data[c][r]; });
		var q = l.b.at || l.b.i.map(function (c) { return data[c][r]; });
		var d = distance(p, q);
		return l.op === '>=' ? d > l.length * (1 + SLACK) : d < l.length * (1 - SLACK);
	}

	function setTime(t) {
		state.t = Math.min(t1, Math.max(t0, t));
		state.dirty = true;
	}

	function setPlaying(on) {
		if (on && state.t >= t1) state.t = t0;
		state.playing = on;
		playBtn.textContent = on ? 'Pause' : 'Play';
	}

	playBtn.addEventListener('click', function () { setPlaying(!state.playing); });
	slider.addEventListener('input', function () { setPlaying(false); setTime(Number(slider.value)); });

	/* speeds in a 1-2-5 series around the one that shows the run in about 10 s */
	var speedSel = document.getElementById('speed');
	(function () {
		var want = (t1 - t0) / 10 || 1;
		var e = Math.pow(10, Math.floor(Math.log10(want)));
		var best = [1, 2, 5, 10].map(function (m) { return m * e; })
			.reduce(function (a, b) { return Math.abs(Math.log(b / want)) < Math.abs(Math.log(a / want)) ? b : a; });
		for (var p = -2; p <= 2; p++) {
			[1, 2, 5].forEach(function (m) {
				var v = Number((m * best * Math.pow(10, p)).toPrecision(3));
				var opt = document.createElement('option');
				opt.value = v;
				opt.textContent = v + '\u00d7' + (v === 1 ? ' (real time)' : '');
				if (v === Number(best.toPrecision(3))) opt.selected = true;
				speedSel.appendChild(opt);
			});
		}
		state.speed = Number(speedSel.value);
		speedSel.addEventListener('change', function () { state.speed = Number(speedSel.value); });
	})();

	/* ---- the readout: t and each object's position ---- */
	var readout = document.getElementById('readout');
	if (inCsv) {
		var head = readout.insertRow();
		['object', 'x', 'y', 'z'].forEach(function (h, k) {
			var th = document.createElement('th');
			th.textContent = k ? h + (posUnit ? ' [' + posUnit + ']' : '') : h;
			head.appendChild(th);
		});
		objects.slice(0, inCsv).forEach(function (o) {
			o.row = readout.insertRow();
			o.row.id = 'obj-' + o.name;
			var c = o.row.insertCell();
			c.innerHTML = '<span class="swatch"></span>';
			c.firstChild.style.background = o.color;
			c.appendChild(document.createTextNode(o.name));
			o.cells = [o.row.insertCell(), o.row.insertCell(), o.row.insertCell()];
		});
	}

	/* ---- the legend of the links, with each string's state ---- */
	var linksEl = document.getElementById('links');
	links.forEach(function (l, k) {
		if (!k) linksEl.appendChild(document.createTextNode('Links: '));
		l.el = document.createElement('span');
		l.el.setAttribute('data-link', l.kind + ' ' + l.names.join(' '));
		l.el.innerHTML = '<span class="swatch"></span>';
		l.el.firstChild.style.background = LINKS[l.kind];
		l.text = document.createTextNode('');
		l.el.appendChild(l.text);
		linksEl.appendChild(l.el);
		linksEl.appendChild(document.createTextNode(k + 1 < links.length ? '; ' : '.'));
	});
	/* the legend's words for link l, slack or not */
	function linkText(l, slack) {
		var s = l.kind + ' ' + l.names.join('\u2013');
		var missing = l.names.filter(function (name) { return !objectByName[name]; });
		if (missing.length) return s + ' (not drawn: no position of ' + missing.join(' or ') + ')';
		if (l.kind !== 'string') return s;
		return s + (l.length === null ? ' (length unknown: drawn taut)' : slack ? ', slack' : ', taut');
	}

	/* a spring from p to q: straight ends and ZIGZAG corners width apart
	 * between them, across the link in the plane of the view */
	var ZIGZAG = 16;
	function zigzag(p, q, width) {
		var d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
		function across(s) { return [d[1] * s[2] - d[2] * s[1], d[2] * s[0] - d[0] * s[2], d[0] * s[1] - d[1] * s[0]]; }
		function at(f, side) { return [0, 1, 2].map(function (k) { return p[k] + f * d[k] + side * w[k]; }); }
		var w = across(mode === 'xz' ? [0, 1, 0] : [0, 0, 1]);
		var len = distance(w, [0, 0, 0]);
		if (len <= 1e-9 * distance(p, q)) {
			w = across([1, 0, 0]);
			len = distance(w, [0, 0, 0]);
		}
		w = w.map(function (v) { return len > 0 ? v * width / 2 / len : 0; });
		var pts = [p, at(0.1, 0)];
		for (var j = 0; j < ZIGZAG; j++) pts.push(at(0.1 + 0.8 * (j + 0.5) / ZIGZAG, j % 2 ? -1 : 1));
		pts.push(at(0.9, 0), q);
		return pts;
	}

	/* ---- the 3-D view ---- */
	var box = document.getElementById('view3d');
	function makeView() {
		if (!objects.length) {
			box.innerHTML = '<div id="nowebgl">No pos was watched: nothing to animate.</div>';
			return null;
		}
		var renderer;
		try {
			renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
		} catch (err) {
			box.innerHTML = '<div id="nowebgl">This browser has no WebGL: the 3-D view is off.</div>';
			return null;
		}
		renderer.setPixelRatio(window.devicePixelRatio || 1);
		renderer.setClearColor(0xf4f6f8);
		box.appendChild(renderer.domElement);
		var scene = new THREE.Scene();
		var V = function (a) { return new THREE.Vector3(a[0], a[1], a[2]); };
		var c = V(centre);
		var camera;
		var w = box.clientWidth, h = box.clientHeight;
		if (mode === '3d') {
			camera = new THREE.PerspectiveCamera(40, w / h, extent * 1e-3, extent * 100);
			camera.up.set(0, 0, 1);
			camera.position.copy(c).add(new THREE.Vector3(1, -1.8, 0.9).normalize().multiplyScalar(extent * 2.4));
		} else {
			var half = extent * 0.65;
			camera = new THREE.OrthographicCamera(-half * w / h, half * w / h, half, -half, -extent * 100, extent * 100);
			if (mode === 'xy') {
				camera.up.set(0, 1, 0);
				camera.position.copy(c).add(new THREE.Vector3(0, 0, extent * 10));
			} else {
				camera.up.set(0, 0, 1);
				camera.position.copy(c).add(new THREE.Vector3(0, -extent * 10, 0));
			}
		}
		scene.add(camera);
		scene.add(new THREE.AmbientLight(0xffffff, 0.55));
		var light = new THREE.DirectionalLight(0xffffff, 0.6);
		light.position.set(1, 1, 2);
		camera.add(light);

		var controls = new THREE.OrbitControls(camera, renderer.domElement);
		controls.target.copy(c);
		if (mode !== '3d') {
			controls.enableRotate = false;
			controls.mouseButtons = { LEFT: THREE.MOUSE.PAN, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.PAN };
		}
		controls.update();
		controls.addEventListener('change', function () { state.dirty = true; });

		if (c.length() < 5 * extent) scene.add(new THREE.AxesHelper(extent * 0.2));

		planes.forEach(function (p) {
			var u = V(p.u), v = V(p.v), nrm = new THREE.Vector3().crossVectors(u, v);
			var geom = new THREE.PlaneBufferGeometry(p.size[0], p.size[1]);
			var mesh = new THREE.Mesh(geom, new THREE.MeshBasicMaterial({
				color: 0x8899aa, transparent: true, opacity: 0.25, side: THREE.DoubleSide, depthWrite: false }));
			var outline = new THREE.LineSegments(new THREE.EdgesGeometry(geom), new THREE.LineBasicMaterial({ color: 0x445566 }));
			[mesh, outline].forEach(function (m) {
				m.name = 'plane ' + p.name;
				m.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(u, v, nrm));
				m.position.copy(V(p.centre));
				scene.add(m);
			});
		});

		/* a moving object is a sphere with its trail; a fixed one a grey
		 * sphere of its radius, or a small octahedron when it is a point */
		objects.forEach(function (o) {
			var r = o.radius > 0 ? o.radius : extent * 0.02;
			var geom = o.fixed && !(o.radius > 0) ? new THREE.OctahedronBufferGeometry(extent * 0.015)
				: new THREE.SphereBufferGeometry(r, 24, 16);
			o.mesh = new THREE.Mesh(geom, new THREE.MeshLambertMaterial({ color: o.color }));
			o.mesh.name = (o.fixed ? 'fixed ' : 'object ') + o.name;
			scene.add(o.mesh);
			if (o.fixed) return;
			var pts = new Float32Array(n * 3);
			for (var r2 = 0; r2 < n; r2++)
				for (var k = 0; k < 3; k++) pts[3 * r2 + k] = data[o.i[k]][r2];
			var g = new THREE.BufferGeometry();
			g.setAttribute('position', new THREE.BufferAttribute(pts, 3));
			g.setDrawRange(0, 1);
			o.trail = new THREE.Line(g, new THREE.LineBasicMaterial({ color: o.color }));
			scene.add(o.trail);
		});

		/* a link is a line of as many points as its shape, moved by show();
		 * a string has a second, dashed line, shown while it is slack */
		function line(count, material, name) {
			var g = new THREE.BufferGeometry();
			g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
			var ln = new THREE.Line(g, material);
			ln.name = name;
			ln.frustumCulled = false;
			scene.add(ln);
			return ln;
		}
		links.forEach(function (l) {
			if (!l.a || !l.b) return;
			var name = 'link ' + l.kind + ' ' + l.names.join(' ');
			l.line = line(l.kind === 'spring' ? ZIGZAG + 4 : 2, new THREE.LineBasicMaterial({ color: LINKS[l.kind] }), name);
			if (l.kind === 'string')
				l.dashed = line(2, new THREE.LineDashedMaterial({ color: LINKS[l.kind], dashSize: extent * 0.02,
					gapSize: extent * 0.015 }), name + ' slack');
		});

		function resize() {
			var w = box.clientWidth, h = box.clientHeight;
			renderer.setSize(w, h);
			if (camera.isPerspectiveCamera) camera.aspect = w / h;
			else {
				var half = (camera.top - camera.bottom) / 2;
				camera.left = -half * w / h;
				camera.right = half * w / h;
			}
			camera.updateProjectionMatrix();
			state.dirty = true;
		}
		resize();
		window.addEventListener('resize', resize);
		return { render: function () { renderer.render(scene, camera); } };
	}
	var view = makeView();

	/* ---- the plots: one panel per unit of the columns that change ---- */
	var graphs = [];
	var plotsEl = document.getElementById('plots');
	var groups = {}, order = [], constants = [];
	cols.forEach(function (c, i) {
		if (i === 0) return;
		var col = data[i], same = true;
		for (var r = 1; r < n && same; r++) same = col[r] === col[0];
		if (same) { constants.push(c.name + ' = ' + fmt(col[0]) + (c.unit ? ' ' + c.unit : '')); return; }
		if (!(c.unit in groups)) { groups[c.unit] = []; order.push(c.unit); }
		groups[c.unit].push(i);
	});
	/* a column's object (the one its name starts with), or null */
	function ownerOf(i) {
		for (var k = 0; k < objects.length; k++)
			if (cols[i].name.indexOf(objects[k].name + '.') === 0) return objects[k];
		return null;
	}
	var syncing = false;
	order.forEach(function (unit) {
		var idx = groups[unit];
		/* the objects' colours where each object has one line in the panel */
		var owners = idx.map(ownerOf);
		var byObject = owners.every(function (o, k) { return o && owners.indexOf(o) === k; });
		var panel = document.createElement('div');
		panel.className = 'panel';
		var legend = document.createElement('div');
		legend.className = 'legend';
		var graphDiv = document.createElement('div');
		graphDiv.className = 'graph';
		var cursor = document.createElement('div');
		cursor.className = 'cursor';
		panel.appendChild(legend);
		panel.appendChild(graphDiv);
		panel.appendChild(cursor);
		plotsEl.appendChild(panel);
		var rows = new Array(n);
		for (var r = 0; r < n; r++) {
			var row = [T[r]];
			for (var k = 0; k < idx.length; k++) row.push(data[idx[k]][r]);
			rows[r] = row;
		}
		var g = new Dygraph(graphDiv, rows, {
			labels: [cols[0].name].concat(idx.map(function (i) { return cols[i].name; })),
			colors: idx.map(function (_, k) { return byObject ? owners[k].color : COLORS[k % COLORS.length]; }),
			xlabel: label(cols[0]),
			ylabel: unit ? '[' + unit + ']' : '(no unit)',
			labelsDiv: legend,
			legend: 'always',
			strokeWidth: 1.5,
			axes: { x: { valueFormatter: fmt }, y: { valueFormatter: fmt } },
			clickCallback: function (e, x) { setPlaying(false); setTime(x); },
			drawCallback: function (me, initial) {
				if (syncing || initial) return;
				syncing = true;
				var range = me.xAxisRange();
				graphs.forEach(function (o) { if (o.g !== me) o.g.updateOptions({ dateWindow: range }); });
				syncing = false;
				state.dirty = true;
				state.row = -1;
			}
		});
		graphs.push({ g: g, div: graphDiv, cursor: cursor });
	});
	if (constants.length) {
		var p = document.createElement('div');
		p.className = 'constant';
		p.textContent = 'Constant: ' + constants.join(', ') + '.';
		plotsEl.appendChild(p);
	}
	if (!order.length && !constants.length) plotsEl.textContent = 'No column to plot.';

	/* ---- one frame ---- */
	function setLine(ln, pts) {
		var a = ln.geometry.attributes.position;
		pts.forEach(function (p, j) { a.setXYZ(j, p[0], p[1], p[2]); });
		a.needsUpdate = true;
	}
	function show() {
		var t = state.t, row = nearestRow(t);
		objects.forEach(function (o) {
			var p = positionAt(o, t);
			if (o.row) {
				for (var k = 0; k < 3; k++) o.cells[k].textContent = fmt(p[k]);
				o.row.setAttribute('data-pos', p.join(' '));
			}
			if (view) {
				o.mesh.position.set(p[0], p[1], p[2]);
				if (o.trail) o.trail.geometry.setDrawRange(0, rowAt(t) + 1);
			}
		});
		/* a string's state is its nearest row's */
		links.forEach(function (l) {
			var placed = l.a && l.b;
			var slack = placed && l.kind === 'string' && l.length !== null && slackAt(l, row);
			l.text.textContent = linkText(l, slack);
			l.el.setAttribute('data-state', !placed ? 'none' : l.kind !== 'string' ? 'drawn' : slack ? 'slack' : 'taut');
			if (!view || !placed) return;
			var p = positionAt(l.a, t), q = positionAt(l.b, t);
			var pts = l.kind === 'spring' ? zigzag(p, q, extent * 0.03) : [p, q];
			setLine(l.line, pts);
			l.line.visible = !slack;
			if (l.dashed) {
				setLine(l.dashed, pts);
				l.dashed.computeLineDistances();
				l.dashed.visible = slack;
			}
		});
		if (view) view.render();
		slider.value = t;
		timeEl.textContent = fmt(t);
		timeEl.setAttribute('data-t', t);
		graphs.forEach(function (o) {
			if (row !== state.row) o.g.setSelection(row);
			var range = o.g.xAxisRange(), area = o.g.getArea();
			if (t < range[0] || t > range[1]) {
				o.cursor.style.display = 'none';
				return;
			}
			o.cursor.style.display = 'block';
			o.cursor.style.left = (o.div.offsetLeft + o.g.toDomXCoord(t)) + 'px';
			o.cursor.style.top = (o.div.offsetTop + area.y) + 'px';
			o.cursor.style.height = area.h + 'px';
		});
		state.row = row;
	}

	var last = null;
	function frame(now) {
		if (state.playing && last !== null) {
			state.t += (now - last) / 1000 * state.speed;
			if (state.t >= t1) { state.t = t1; setPlaying(false); }
			state.dirty = true;
		}
		last = now;
		if (state.dirty) {
			state.dirty = false;
			show();
		}
		requestAnimationFrame(frame);
	}

	var m = /(?:^#|&)t=([-+0-9.eE]+)/.exec(window.location.hash);
	if (m) setTime(Number(m[1]));
	else setPlaying(true);
	window.addEventListener('resize', function () { state.dirty = true; });
	show();
	state.dirty = false;
	requestAnimationFrame(frame);
})();
