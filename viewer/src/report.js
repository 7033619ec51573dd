// The HTML report's viewer (src/report/html_report.cpp writes the page): reads the page's data (the JSON in
// #symcompress-data), draws the scene with three.js (stored meshes drawn by instancing), the classes'
// table, the symmetry elements, and the size charts. Bundled with three.js and OrbitControls into one
// script (viewer/build.mjs) that the library inlines into every page, so the page needs no network.
import {
    BufferAttribute,
    BufferGeometry,
    CanvasTexture,
    CircleGeometry,
    Color,
    DirectionalLight,
    DoubleSide,
    Group,
    HemisphereLight,
    InstancedBufferAttribute,
    InstancedMesh,
    Line,
    LineBasicMaterial,
    LineLoop,
    Matrix4,
    Mesh,
    MeshBasicMaterial,
    MeshStandardMaterial,
    PerspectiveCamera,
    Quaternion,
    Scene,
    Sprite,
    SpriteMaterial,
    Vector3,
    WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const data = JSON.parse(document.getElementById('symcompress-data').textContent);

// --- decoding -------------------------------------------------------------------------------------------

function bytesOf(base64) {
    const text = atob(base64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return bytes;
}
const floatsOf = (base64) => new Float32Array(bytesOf(base64).buffer);
const indicesOf = (base64) => new Uint32Array(bytesOf(base64).buffer);

// --- colours --------------------------------------------------------------------------------------------

const GREY = new Color(0x9a9a9a);
const DIM = new Color(0xe4e4e4);
const KEPT = new Color(0xa9b4c8);
const SHAPE = new Color(0x8fa6c4);  // detect: the one shape
// Neighbouring class numbers far apart on the colour wheel (the golden angle).
function classColor(k, lightness = 0.52) {
    return new Color().setHSL((k * 0.6180339887) % 1, 0.68, lightness);
}
const cssColor = (color) => '#' + color.getHexString();

// --- the scene ------------------------------------------------------------------------------------------

const canvas = document.getElementById('scene');
const renderer = new WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
renderer.setClearColor(0xffffff, 1);
const scene = new Scene();
const camera = new PerspectiveCamera(40, 1, 1e-3, 1e4);
const controls = new OrbitControls(camera, canvas);
scene.add(new HemisphereLight(0xffffff, 0x8a8f99, 1.6));
const sun = new DirectionalLight(0xffffff, 1.6);
scene.add(sun);
scene.add(sun.target);

const material = new MeshStandardMaterial({
    vertexColors: false,
    flatShading: true,
    side: DoubleSide,
    metalness: 0,
    roughness: 0.85,
});
const vertexColored = material.clone();
vertexColored.vertexColors = true;

const geometries = (data.geometries || []).map((g) => {
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(floatsOf(g.positions), 3));
    geometry.setIndex(new BufferAttribute(indicesOf(g.indices), 1));
    geometry.userData.vertexClasses = g.vertexClasses ? indicesOf(g.vertexClasses) : null;
    return geometry;
});

// Every draw paints itself for the selected class (null: none selected).
const painters = [];
for (const draw of data.draws || []) {
    const geometry = geometries[draw.geometry];
    if (draw.kind === 'merged') {
        // Tiles stored as they are, in world coordinates, one colour per vertex so that a class's members
        // among them can be highlighted.
        const classes = geometry.userData.vertexClasses;
        const colors = new Float32Array(classes.length * 3);
        geometry.setAttribute('color', new BufferAttribute(colors, 3));
        scene.add(new Mesh(geometry, vertexColored));
        painters.push((selected) => {
            const highlight = selected === null ? null : classColor(selected);
            for (let v = 0; v < classes.length; ++v) {
                const color = selected === null ? GREY : classes[v] === selected ? highlight : DIM;
                colors[3 * v] = color.r;
                colors[3 * v + 1] = color.g;
                colors[3 * v + 2] = color.b;
            }
            geometry.attributes.color.needsUpdate = true;
        });
        continue;
    }
    const matrices = floatsOf(draw.matrices);
    const count = matrices.length / 16;
    const mesh = new InstancedMesh(geometry, material, count);
    mesh.instanceMatrix = new InstancedBufferAttribute(matrices, 16);
    mesh.instanceColor = new InstancedBufferAttribute(new Float32Array(count * 3), 3);
    mesh.frustumCulled = false;  // the geometry's own bounds are not the instances'
    scene.add(mesh);
    const roles = draw.roles ? bytesOf(draw.roles) : null;
    painters.push((selected) => {
        let base;
        if (draw.kind === 'kept') base = () => KEPT;
        else if (draw.kind === 'shape') base = () => SHAPE;
        else if (draw.kind === 'region')
            // The stored fundamental region of each member light, the copies that rebuild the rest dark.
            base = (i) => classColor(draw.cls, roles && roles[i] ? 0.74 : 0.42);
        else if (draw.kind === 'tiles')
            // Members drawn by an assembly or the scene's symmetry in their class's colour, those stored as they
            // are grey (highlighted in the class's colour when it is selected).
            base = (i) => (roles && roles[i] && selected === null ? GREY : classColor(draw.cls));
        else base = () => classColor(draw.cls);
        for (let i = 0; i < count; ++i) {
            const color = selected === null || selected === draw.cls ? base(i) : DIM;
            mesh.setColorAt(i, color);
        }
        mesh.instanceColor.needsUpdate = true;
    });
}

// --- symmetry elements ----------------------------------------------------------------------------------

const AXIS_COLORS = { 2: 0xd62728, 3: 0x2ca02c, 4: 0xff7f0e, 5: 0x9467bd, 6: 0x8c564b };
const axisColor = (fold) => AXIS_COLORS[fold] ?? 0x17becf;

function label(text, color, size) {
    const image = document.createElement('canvas');
    image.width = image.height = 64;
    const context = image.getContext('2d');
    context.fillStyle = '#ffffff';
    context.beginPath();
    context.arc(32, 32, 28, 0, 2 * Math.PI);
    context.fill();
    context.lineWidth = 4;
    context.strokeStyle = cssColor(new Color(color));
    context.stroke();
    context.fillStyle = '#111111';
    context.font = 'bold 34px sans-serif';
    context.textAlign = 'center';
    context.textBaseline = 'middle';
    context.fillText(text, 32, 34);
    const sprite = new Sprite(new SpriteMaterial({ map: new CanvasTexture(image), depthTest: false }));
    sprite.scale.setScalar(size);
    sprite.renderOrder = 11;
    return sprite;
}

// Mirror planes as translucent discs, rotation axes as lines labelled with their order, about `centre`,
// sized to `size` (the part's or the scene's diagonal). `only` picks one element (detect's table).
function elementsObject(symmetry, only = null) {
    const group = new Group();
    const centre = new Vector3(...symmetry.centre);
    const size = symmetry.size;
    symmetry.planes.forEach((plane, index) => {
        if (only && !(only.kind === 'plane' && only.index === index)) return;
        const normal = new Vector3(...plane.normal).normalize();
        const turn = new Quaternion().setFromUnitVectors(new Vector3(0, 0, 1), normal);
        const disc = new Mesh(
            new CircleGeometry(size * 0.55, 64),
            new MeshBasicMaterial({ color: 0x3b82f6, transparent: true, opacity: 0.25, side: DoubleSide, depthWrite: false }),
        );
        disc.quaternion.copy(turn);
        disc.position.copy(centre);
        disc.renderOrder = 5;
        const rimPoints = [];
        for (let i = 0; i < 96; ++i) {
            const angle = (2 * Math.PI * i) / 96;
            rimPoints.push(new Vector3(Math.cos(angle), Math.sin(angle), 0).multiplyScalar(size * 0.55));
        }
        const rim = new LineLoop(new BufferGeometry().setFromPoints(rimPoints),
            new LineBasicMaterial({ color: 0x1d4ed8, transparent: true, opacity: 0.8 }));
        rim.quaternion.copy(turn);
        rim.position.copy(centre);
        group.add(disc, rim);
    });
    symmetry.axes.forEach((axis, index) => {
        if (only && !(only.kind === 'axis' && only.index === index)) return;
        const direction = new Vector3(...axis.axis).normalize();
        const reach = size * 0.6;
        const ends = [centre.clone().addScaledVector(direction, -reach), centre.clone().addScaledVector(direction, reach)];
        const line = new Line(new BufferGeometry().setFromPoints(ends),
            new LineBasicMaterial({ color: axisColor(axis.fold), depthTest: false }));
        line.renderOrder = 10;
        const tag = label(String(axis.fold), axisColor(axis.fold), size * 0.14);
        tag.position.copy(ends[1]);
        group.add(line, tag);
    });
    return group;
}

// --- framing and drawing --------------------------------------------------------------------------------

const bounds = data.bounds;
const middle = new Vector3(...bounds.min).add(new Vector3(...bounds.max)).multiplyScalar(0.5);
const radius = Math.max(new Vector3(...bounds.max).sub(new Vector3(...bounds.min)).length() / 2, 1e-6);
controls.target.copy(middle);
camera.position.copy(middle).add(new Vector3(0.8, 1.3, 1.2).normalize().multiplyScalar(radius * 2.3));
camera.near = radius / 100;
camera.far = radius * 100;
controls.update();

function render() {
    const width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== Math.floor(width * renderer.getPixelRatio()) ||
        canvas.height !== Math.floor(height * renderer.getPixelRatio())) {
        renderer.setSize(width, height, false);
        camera.aspect = width / Math.max(height, 1);
        camera.updateProjectionMatrix();
    }
    sun.position.copy(camera.position).add(new Vector3(radius, radius * 2, radius));
    sun.target.position.copy(controls.target);
    renderer.render(scene, camera);
}
controls.addEventListener('change', render);
window.addEventListener('resize', render);

let shownElements = null;
function showElements(object) {
    if (shownElements) scene.remove(shownElements);
    shownElements = object;
    if (object) scene.add(object);
}
let sceneElements = null;  // the scene's own group, drawn while nothing is selected

let selectedClass = null;
function selectClass(k) {
    selectedClass = k;
    for (const paint of painters) paint(k);
    const entry = k === null ? null : data.classes.find((c) => c.id === k);
    showElements(entry && entry.symmetry ? elementsObject(entry.symmetry) : sceneElements);
    for (const row of document.querySelectorAll('#classes tbody tr'))
        row.classList.toggle('selected', Number(row.dataset.id) === k);
    document.getElementById('selection').textContent = entry
        ? `class ${k}: ${entry.members} members, group ${entry.group}, stored ${entry.storage}` +
          (entry.symmetry ? '' : ' (no symmetry elements to draw)')
        : '';
    render();
}

// --- tables ---------------------------------------------------------------------------------------------

const formatBytes = (bytes) => bytes === null || bytes === undefined ? '—'
    : bytes < 1e4 ? `${Math.round(bytes)} B` : bytes < 1e7 ? `${(bytes / 1e3).toFixed(1)} kB` : `${(bytes / 1e6).toFixed(2)} MB`;

function element(tag, attributes = {}, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attributes)) {
        if (key === 'style') node.style.cssText = value;
        else if (key.startsWith('on')) node.addEventListener(key.slice(2), value);
        else node.setAttribute(key, value);
    }
    for (const child of children) node.append(child);
    return node;
}

// A table sortable by any column (click a heading; again to reverse).
function sortableTable(table, columns, rows, onRow) {
    const head = element('tr');
    const body = element('tbody');
    let order = { column: 0, ascending: true };
    function fill() {
        const column = columns[order.column];
        const sorted = rows.slice().sort((a, b) => {
            const x = column.value(a), y = column.value(b);
            const difference = typeof x === 'number' || typeof y === 'number'
                ? (x ?? -Infinity) - (y ?? -Infinity) : String(x).localeCompare(String(y));
            return order.ascending ? difference : -difference;
        });
        body.replaceChildren(...sorted.map((row) => {
            const tr = element('tr', { 'data-id': row.id }, ...columns.map((c) => element('td', {}, c.show(row))));
            if (onRow) tr.addEventListener('click', () => onRow(row));
            return tr;
        }));
        for (const [index, th] of [...head.children].entries())
            th.dataset.sorted = index === order.column ? (order.ascending ? 'up' : 'down') : '';
    }
    columns.forEach((column, index) => {
        head.append(element('th', {
            title: 'sort',
            onclick: () => {
                order = { column: index, ascending: order.column === index ? !order.ascending : column.ascending !== false };
                fill();
            },
        }, column.title));
    });
    table.replaceChildren(element('thead', {}, head), body);
    fill();
}

function swatch(k) {
    return element('span', { class: 'swatch', style: `background:${cssColor(classColor(k))}` });
}

if (data.kind === 'compress') {
    const columns = [
        { title: 'class', value: (c) => c.id, show: (c) => element('span', {}, swatch(c.id), String(c.id)) },
        { title: 'members', value: (c) => c.members, show: (c) => String(c.members), ascending: false },
        { title: 'triangles', value: (c) => c.triangles, show: (c) => String(c.triangles), ascending: false },
        { title: 'group', value: (c) => c.group, show: (c) => c.group },
        { title: 'stored', value: (c) => c.storage, show: (c) => c.storage },
        { title: 'bytes', value: (c) => c.bytes, show: (c) => formatBytes(c.bytes), ascending: false },
    ];
    sortableTable(document.getElementById('classes'), columns, data.classes,
        (c) => selectClass(selectedClass === c.id ? null : c.id));
    document.getElementById('clear').addEventListener('click', () => selectClass(null));
    if (data.sceneSymmetry) {
        sceneElements = elementsObject(data.sceneSymmetry);
        const toggle = document.getElementById('scene-elements');
        toggle.addEventListener('change', () => {
            sceneElements = toggle.checked ? elementsObject(data.sceneSymmetry) : null;
            if (selectedClass === null) showElements(sceneElements);
            render();
        });
    }
} else {
    // detect: every element of the shape's group with its deviation; a row shows only that element.
    const symmetry = data.symmetry;
    sceneElements = elementsObject(symmetry);
    const degrees = (radians) => (radians * 180 / Math.PI).toFixed(2);
    const columns = [
        { title: '#', value: (e) => e.id, show: (e) => String(e.id) },
        { title: 'element', value: (e) => e.type, show: (e) => e.type },
        { title: 'axis / normal', value: (e) => e.axis.join(' '), show: (e) => e.axis.map((x) => x.toFixed(4)).join(' ') },
        { title: 'angle°', value: (e) => e.angle, show: (e) => e.angle ? degrees(e.angle) : '' },
        { title: 'fold', value: (e) => e.fold, show: (e) => e.fold ? String(e.fold) : '' },
        { title: 'deviation', value: (e) => e.deviation, show: (e) => e.deviation.toExponential(2) },
    ];
    let picked = null;
    sortableTable(document.getElementById('classes'), columns, symmetry.elements, (e) => {
        picked = picked === e.id || !e.drawn ? null : e.id;
        showElements(picked === null ? sceneElements : elementsObject(symmetry, e.drawn));
        for (const row of document.querySelectorAll('#classes tbody tr'))
            row.classList.toggle('selected', Number(row.dataset.id) === picked);
        render();
    });
}

// --- charts (SVG) ---------------------------------------------------------------------------------------

const SVG = 'http://www.w3.org/2000/svg';
function svg(tag, attributes = {}, text) {
    const node = document.createElementNS(SVG, tag);
    for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
    if (text !== undefined) node.textContent = text;
    return node;
}

// Horizontal bars, one per item ({label, value, note}), scaled to the largest.
function barChart(title, items, format) {
    const shown = items.filter((item) => item.value !== null && item.value !== undefined);
    const width = 420, labelWidth = 150, barHeight = 22, gap = 6;
    const height = shown.length * (barHeight + gap) + 8;
    const largest = Math.max(...shown.map((item) => item.value), 1e-12);
    const chart = svg('svg', { width, height, viewBox: `0 0 ${width} ${height}`, role: 'img' });
    shown.forEach((item, index) => {
        const y = index * (barHeight + gap) + 4;
        const length = Math.max((width - labelWidth - 90) * item.value / largest, 1);
        chart.append(svg('text', { x: labelWidth - 6, y: y + barHeight * 0.7, 'text-anchor': 'end', class: 'label' }, item.label));
        chart.append(svg('rect', { x: labelWidth, y, width: length, height: barHeight, fill: item.color || '#4c78a8', rx: 2 }));
        chart.append(svg('text', { x: labelWidth + length + 5, y: y + barHeight * 0.7, class: 'value' },
            format(item.value) + (item.note ? ` ${item.note}` : '')));
    });
    return element('figure', {}, element('figcaption', {}, title), chart);
}

const charts = document.getElementById('charts');
if (data.charts) {
    const palette = ['#9d9d9d', '#4c78a8', '#f58518', '#54a24b', '#e45756'];
    const withColors = (items) => items.map((item, index) => ({ ...item, color: palette[index % palette.length] }));
    charts.append(barChart('Size of each plan (the ablation)', withColors(data.charts.ablation), formatBytes));
    charts.append(barChart('Bytes of the output by kind', withColors(data.charts.kinds), formatBytes));
    charts.append(barChart('Seconds per stage', withColors(data.charts.seconds), (s) => `${s.toFixed(s < 10 ? 3 : 1)} s`));
}

selectClass(null);
window.symcompressReport = {
    ready: true,
    classesShown: document.querySelectorAll('#classes tbody tr').length,
    selectClass,
    render,
};
