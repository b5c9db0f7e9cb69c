/* tests/view/drawn.js PAGE.html SECONDS - what csfview's page draws at
 * t = SECONDS, without a browser: the page's own scripts (three.js and
 * view.js, with CSF_META and the CSV) run in node with a stub DOM, a stub
 * WebGL renderer that keeps the scene it is asked to draw, and a stub
 * dygraphs. Prints one line per named thing in that scene and per link in
 * the legend, numbers in full:
 *   object|fixed NAME X Y Z GEOMETRY SIZE     (a sphere's radius, an octahedron's)
 *   link KIND A B [slack] shown|hidden N X1 Y1 Z1 ... XN YN ZN
 *   plane NAME WIDTH HEIGHT CX CY CZ NX NY NZ
 *   legend KIND A B STATE TEXT
 * Exit 1 on an exception in the page. */
'use strict';
var fs = require('fs');
var vm = require('vm');

var html = fs.readFileSync(process.argv[2], 'utf8');
var t = process.argv[3];

/* the page's scripts in order; the CSV is the one of type text/csv */
var scripts = [], csv = '', re = /<script( id="csv" type="text\/csv")?>\n([\s\S]*?)\n<\/script>/g, m;
while ((m = re.exec(html)) !== null) {
	if (m[1]) csv = m[2];
	else scripts.push(m[2]);
}
if (scripts.length !== 4) {
	console.error('drawn.js: want 4 scripts in the page (three, dygraphs, CSF_META, view.js), found ' + scripts.length);
	process.exit(2);
}

function Element(tag) {
	this.tagName = tag;
	this.children = [];
	this.attributes = {};
	this.style = {};
	this.textContent = '';
	this.clientWidth = 640;
	this.clientHeight = 460;
	this.offsetLeft = 0;
	this.offsetTop = 0;
	this.value = '';
}
Element.prototype = {
	appendChild: function (c) { this.children.push(c); return c; },
	setAttribute: function (k, v) { this.attributes[k] = String(v); },
	getAttribute: function (k) { return this.attributes[k]; },
	addEventListener: function () {},
	removeEventListener: function () {},
	insertRow: function () { return this.appendChild(new Element('tr')); },
	insertCell: function () { return this.appendChild(new Element('td')); },
	get firstChild() { return this.children[0]; },
	set innerHTML(h) { this.children = /<span/.test(h) ? [new Element('span')] : []; },
	get innerHTML() { return ''; }
};
var byId = {};
['csv', 'info', 'decimation', 'tunit', 'slider', 'time', 'play', 'speed', 'readout', 'view3d',
	'plots', 'links', 'viewmode', 'title', 'note'].forEach(function (id) { byId[id] = new Element('div'); });
byId.csv.textContent = csv;
var document = {
	getElementById: function (id) { return byId[id] || null; },
	createElement: function (tag) { return new Element(tag); },
	createTextNode: function (s) { return { textContent: s }; },
	addEventListener: function () {},
	removeEventListener: function () {},
	documentElement: new Element('html')
};
function Dygraph(div, rows) { this.rows = rows; }
Dygraph.prototype = {
	setSelection: function () {},
	updateOptions: function () {},
	xAxisRange: function () { return [this.rows[0][0], this.rows[this.rows.length - 1][0]]; },
	getArea: function () { return { x: 0, y: 0, w: 600, h: 200 }; },
	toDomXCoord: function () { return 0; }
};

var drawn = null;
var sandbox = {
	document: document,
	location: { hash: '#t=' + t },
	devicePixelRatio: 1,
	addEventListener: function () {},
	removeEventListener: function () {},
	requestAnimationFrame: function () {},
	console: console
};
sandbox.window = sandbox;
vm.createContext(sandbox);
try {
	vm.runInContext(scripts[0], sandbox, { filename: 'three' });
	sandbox.THREE.WebGLRenderer = function () { this.domElement = new Element('canvas'); };
	sandbox.THREE.WebGLRenderer.prototype = {
		setPixelRatio: function () {},
		setClearColor: function () {},
		setSize: function () {},
		render: function (scene) { drawn = scene; }
	};
	sandbox.Dygraph = Dygraph;
	vm.runInContext(scripts[2], sandbox, { filename: 'CSF_META' });
	vm.runInContext(scripts[3], sandbox, { filename: 'view.js' });
} catch (err) {
	console.error('drawn.js: the page threw: ' + (err && err.stack || err));
	process.exit(1);
}

var out = [];
function xyz(v) { return [v.x, v.y, v.z].join(' '); }
if (drawn) {
	var THREE = sandbox.THREE;
	drawn.children.forEach(function (o) {
		var w = o.name.split(' ');
		if (w[0] === 'object' || w[0] === 'fixed') {
			var g = o.geometry;
			out.push([o.name, xyz(o.position), g.type, g.parameters.radius].join(' '));
		} else if (w[0] === 'link') {
			var a = o.geometry.attributes.position, pts = [];
			for (var j = 0; j < a.count; j++) pts.push(a.getX(j), a.getY(j), a.getZ(j));
			out.push([o.name, o.visible ? 'shown' : 'hidden', a.count].concat(pts).join(' '));
		} else if (w[0] === 'plane' && o.type === 'Mesh') {
			var nrm = new THREE.Vector3(0, 0, 1).applyQuaternion(o.quaternion);
			out.push([o.name, o.geometry.parameters.width, o.geometry.parameters.height, xyz(o.position), xyz(nrm)].join(' '));
		}
	});
}
byId.links.children.forEach(function (c) {
	if (!c.attributes || !c.attributes['data-link']) return;
	out.push(['legend', c.attributes['data-link'], c.attributes['data-state'], c.children[1].textContent].join(' '));
});
console.log(out.join('\n'));
