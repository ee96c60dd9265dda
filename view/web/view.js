// fleetmap view: draws the state `fleetmap view` streams on /events (docs/view.md). The first
// event is the whole state; each later one holds only what changed (null: removed). Coordinates
// are fleet-frame metres; Leaflet's simple CRS takes [y, x], one unit a metre.
'use strict';

const COLORS = {
  obstacle: '#202020',
  free: '#ffffff',
  observed: '#4a78c2',
  predicted: '#f0a030',
  confirmed: '#2e9e4f',
  retracted: '#d03030',
  object: '#8e44ad',
  route: '#0097a7',  // the route graph's edges; its doorways in the sub-maps' predicted orange
  quarantine: '#c62828',  // the area a quarantined robot's map contradicts
  // A robot's state is the ring around its dot; the dot, heading and path are the robot's own
  // colour (robotColor).
  robotState: { live: '#2e7d32', stale: '#ef8f00', lost: '#c62828', left: '#777777' },
};

// 32-bit FNV-1a of a string.
function hashOf(text) {
  let hash = 0x811c9dc5;
  for (let i = 0; i < text.length; ++i) hash = Math.imul(hash ^ text.charCodeAt(i), 0x01000193);
  return hash >>> 0;
}

// '#rrggbb' of a hue in degrees, saturation and lightness in [0, 1].
function hslHex(hue, saturation, lightness) {
  const a = saturation * Math.min(lightness, 1 - lightness);
  const channel = (n) => {
    const k = (n + hue / 30) % 12;
    const value = lightness - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
    return Math.round(255 * value).toString(16).padStart(2, '0');
  };
  return `#${channel(0)}${channel(8)}${channel(4)}`;
}

// A colour per robot, the same on every page and in every run: its hue comes from its id alone.
// Ids that differ in a trailing number (robot1, robot2, ...) are a golden angle (137.5°) apart,
// so neighbours never look alike; other ids are spread by a hash of the name. Dark enough to read
// on white free space and on grey unknown space.
const robotColors = new Map();
function robotColor(id) {
  if (!robotColors.has(id)) {
    const numbered = /^(.*?)(\d{1,9})$/.exec(id);
    const stem = numbered ? numbered[1] : id;
    const number = numbered ? Number(numbered[2]) : 0;
    const hue = ((hashOf(stem) % 360) + number * 137.508) % 360;
    robotColors.set(id, hslHex(hue, 0.75, 0.4));
  }
  return robotColors.get(id);
}

const map = L.map('map', {
  crs: L.CRS.Simple, minZoom: -5, maxZoom: 8, zoomSnap: 0.25, zoomDelta: 0.5,
  attributionControl: false,
});
map.setView([0, 0], 2);
// One canvas per layer kind keeps the drawing order: free space, unplaced robots' own maps,
// sub-maps, obstacles, the route graph, objects, robots on top.
const panes = ['free', 'own', 'submaps', 'obstacles', 'routes', 'objects', 'robots'];
const renderers = {};
panes.forEach((name, i) => {
  map.createPane(name).style.zIndex = 400 + 10 * i;
  renderers[name] = L.canvas({ pane: name, padding: 0.5 });
});
const layers = {
  free: L.layerGroup().addTo(map),
  obstacles: L.layerGroup().addTo(map),
  own: L.layerGroup().addTo(map),
  submaps: L.layerGroup().addTo(map),
  routes: L.layerGroup().addTo(map),
  objects: L.layerGroup().addTo(map),
  robots: L.layerGroup().addTo(map),
};
let gridOverlay = null;
const gridLayer = L.layerGroup();  // off by default: the vectors are the map
const shardLayer = L.layerGroup().addTo(map);  // the shards' regions (docs/shards.md)
let drawnShards = '';
L.control.layers(null, {
  'fused grid (rt/fleetmap/map)': gridLayer,
  'free space': layers.free,
  obstacles: layers.obstacles,
  "unplaced robots' own maps": layers.own,
  'sub-maps': layers.submaps,
  'route graph (rt/fleetmap/route_graph)': layers.routes,
  objects: layers.objects,
  robots: layers.robots,
  'shard regions': shardLayer,
}, { collapsed: false }).addTo(map);
L.control.scale({ metric: true, imperial: false }).addTo(map);

const ll = (x, y) => [y, x];
const ring = (flat) => {
  const points = [];
  for (let i = 0; i + 1 < flat.length; i += 2) points.push(ll(flat[i], flat[i + 1]));
  return points;
};

// What is drawn, by key, so that a delta can replace or remove it.
const drawn = { tiles: {}, ownTiles: {}, robots: {}, submaps: {}, objects: {}, routes: {} };
let state = { robots: {}, paths: {}, submaps: {}, templates: {}, routeGraphs: {}, status: null };
const PATH_POINTS = 200;  // as many as the view keeps
let lastSeq = -1;
let fitted = false;

// Obstacles are drawn at their true width: 2 * half width metres, in pixels at this zoom.
const obstacleLines = new Set();
const pixelsPerMetre = () => Math.pow(2, map.getZoom());
const obstacleWeight = (halfWidth) => Math.max(1, 2 * halfWidth * pixelsPerMetre());
// Free outlines pass through the centres of their boundary cells: the rasterizer fills a polygon
// with its outline, so the free space is half a cell wider than the outline, and two neighbouring
// tiles' outlines stop a cell apart at their shared border; the simplification (within epsilon)
// cuts corners there too. Stroked two cells wide (a cell each side) plus a pixel they overlap at
// every zoom (half a cell each side still left seams at 17 of 859 border crossings at zoom 5 on a
// live fleet: view_browser_test); the price is free space drawn up to half a cell too far into
// unknown space, under the obstacles, which are drawn over it.
const freeOutlines = new Set();
const freeWeight = (resolution) => 2 * resolution * pixelsPerMetre() + 1;
map.on('zoomend', () => {
  obstacleLines.forEach((line) => line.setStyle({ weight: obstacleWeight(line.halfWidth) }));
  freeOutlines.forEach((free) => free.setStyle({ weight: freeWeight(free.resolution) }));
});

// How a tile is drawn: the fused map's in black and white, seamless; an unplaced robot's own in
// its colour, translucent, over the fused map (it is in the robot's own frame, not placed yet).
function fusedLook() {
  return {
    freeGroup: layers.free, lineGroup: layers.obstacles, seamless: true,
    free: { renderer: renderers.free, color: COLORS.free, fillColor: COLORS.free, fillOpacity: 1 },
    line: { renderer: renderers.obstacles, color: COLORS.obstacle, opacity: 1 },
  };
}
function ownLook(robot) {
  const color = robotColor(robot);
  return {
    freeGroup: layers.own, lineGroup: layers.own, seamless: false,
    free: { renderer: renderers.own, stroke: false, fillColor: color, fillOpacity: 0.15 },
    line: { renderer: renderers.own, color, opacity: 0.7 },
  };
}

function removeTileFrom(shapes, key, look) {
  const tile = shapes[key];
  if (!tile) return;
  look.freeGroup.removeLayer(tile.free);
  freeOutlines.delete(tile.free);
  tile.lines.forEach((line) => { look.lineGroup.removeLayer(line); obstacleLines.delete(line); });
  delete shapes[key];
}

function drawTileInto(shapes, key, tile, look) {
  removeTileFrom(shapes, key, look);
  const polygons = tile.fr.map((rings) => rings.map(ring));
  const resolution = tile.res || 0.05;
  // Mitred joins keep the cells' square corners where four tiles meet.
  const free = L.polygon(polygons, {
    weight: freeWeight(resolution), opacity: 1, lineJoin: 'miter', interactive: false,
    ...look.free,
  });
  free.resolution = resolution;
  if (look.seamless) freeOutlines.add(free);
  look.freeGroup.addLayer(free);
  // One polyline layer per half width (a tile has few distinct widths).
  const byWidth = new Map();
  tile.ob.forEach((obstacle) => {
    const halfWidth = obstacle[0];
    const line = ring(obstacle.slice(2));
    if (obstacle[1] === 1 && line.length > 2) line.push(line[0]);
    if (line.length === 1) line.push(line[0]);  // a point obstacle: a round dot
    if (!byWidth.has(halfWidth)) byWidth.set(halfWidth, []);
    byWidth.get(halfWidth).push(line);
  });
  const lines = [];
  byWidth.forEach((paths, halfWidth) => {
    const line = L.polyline(paths, {
      weight: obstacleWeight(halfWidth), lineCap: 'round', lineJoin: 'round', interactive: false,
      ...look.line,
    });
    line.halfWidth = halfWidth;
    obstacleLines.add(line);
    look.lineGroup.addLayer(line);
    lines.push(line);
  });
  shapes[key] = { free, lines, bounds: [ll(tile.x * tile.size, tile.y * tile.size),
    ll((tile.x + 1) * tile.size, (tile.y + 1) * tile.size)] };
}

const removeTile = (key) => removeTileFrom(drawn.tiles, key, fusedLook());
const drawTile = (key, tile) => drawTileInto(drawn.tiles, key, tile, fusedLook());
// Own-frame tiles are keyed "robot/x,y".
const removeOwnTile = (key) => removeTileFrom(drawn.ownTiles, key, ownLook(''));
const drawOwnTile = (key, tile) => drawTileInto(drawn.ownTiles, key, tile, ownLook(tile.robot));

function removeRobot(id) {
  const robot = drawn.robots[id];
  if (!robot) return;
  robot.forEach((layer) => layers.robots.removeLayer(layer));
  delete drawn.robots[id];
}

// Whether this page hears its view process. While it does not, nothing it shows is current.
let connected = false;
// The state to show: what the view process says, except that a page which lost its view process
// cannot vouch that anyone is live.
const shownState = (robot) => (connected || robot.state !== 'live' ? robot.state : 'stale');

function drawRobot(id, robot) {
  removeRobot(id);
  if (robot.x === undefined) return;
  const shown = shownState(robot);
  const color = robotColor(id);
  const here = ll(robot.x, robot.y);
  const ahead = ll(robot.x + 0.8 * Math.cos(robot.yaw), robot.y + 0.8 * Math.sin(robot.yaw));
  // One polyline of several runs: no segment joins a pose before a placement to one after it.
  const path = L.polyline(state.paths[id] || [], {
    renderer: renderers.robots, color, weight: 2, opacity: 0.75, interactive: false,
  });
  const heading = L.polyline([here, ahead], {
    renderer: renderers.robots, color, weight: 3, interactive: false,
  });
  const marker = L.circleMarker(here, {
    renderer: renderers.robots, radius: 7, color: COLORS.robotState[shown], weight: 3,
    opacity: 1, fillColor: color, fillOpacity: shown === 'live' ? 1 : 0.4,
  }).bindTooltip(`${id} (${shown})`, {
    permanent: true, direction: 'right', offset: [8, 0], className: 'robot-label',
  });
  drawn.robots[id] = [path, heading, marker];
  if (robot.standing === 'quarantined' && robot.area) {
    // What its map contradicts: drawn so an operator can look there before admitting it.
    const [x0, y0, x1, y1] = robot.area;
    drawn.robots[id].push(L.rectangle([ll(x0, y0), ll(x1, y1)], {
      renderer: renderers.robots, color: COLORS.quarantine, weight: 2, dashArray: '6 4',
      fill: false, interactive: false,
    }));
  }
  drawn.robots[id].forEach((layer) => layers.robots.addLayer(layer));
}

function submapColor(submap) {
  return submap.kind === 'observed' ? COLORS.observed : (COLORS[submap.state] || COLORS.predicted);
}

function removeSubmap(id) {
  if (!drawn.submaps[id]) return;
  layers.submaps.removeLayer(drawn.submaps[id]);
  delete drawn.submaps[id];
}

function drawSubmap(id, submap) {
  removeSubmap(id);
  const observed = submap.kind === 'observed';
  const color = submapColor(submap);
  const precision = submap.precision === null ? 'not measured yet' : submap.precision.toFixed(3);
  const layer = L.polygon(submap.rings.map(ring), {
    renderer: renderers.submaps, color, weight: observed ? 1 : 1.5, dashArray: observed ? '4 4' : null,
    fill: !observed, fillColor: color, fillOpacity: 0.35,
  }).bindTooltip(`sub-map ${id}: ${submap.kind}, ${submap.state}, precision ${precision}`);
  drawn.submaps[id] = layer;
  layers.submaps.addLayer(layer);
}

function removeObject(id) {
  if (!drawn.objects[id]) return;
  layers.objects.removeLayer(drawn.objects[id]);
  delete drawn.objects[id];
}

function drawObject(id, object) {
  removeObject(id);
  if (object.x === undefined) return;
  const c = Math.cos(object.yaw);
  const s = Math.sin(object.yaw);
  const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([u, v]) => {
    const dx = 0.5 * u * object.w;
    const dy = 0.5 * v * object.h;
    return ll(object.x + c * dx - s * dy, object.y + s * dx + c * dy);
  });
  const layer = L.polygon(corners, {
    renderer: renderers.objects, color: COLORS.object, weight: 1.5, fillColor: COLORS.object,
    fillOpacity: 0.25,
  }).bindTooltip(`object ${id} (template ${object.template}), seen ${object.sightings.length}x`);
  drawn.objects[id] = layer;
  layers.objects.addLayer(layer);
}

function removeRouteGraph(id) {
  if (!drawn.routes[id]) return;
  drawn.routes[id].forEach((layer) => layers.routes.removeLayer(layer));
  delete drawn.routes[id];
}

// The edges as one polyline of segments, the nodes as small dots (doorways larger): a fleet
// manager's view of where a robot of the graph's radius can go.
function drawRouteGraph(id, graph) {
  removeRouteGraph(id);
  const at = (i) => ll(graph.nodes[2 * i], graph.nodes[2 * i + 1]);
  const title = `route graph ${id}, revision ${graph.revision}: ${graph.kinds.length} nodes, ` +
    `${graph.edges.length} edges, radius ${graph.radius} m${graph.note ? ` (${graph.note})` : ''}`;
  // Edges through predicted space dashed in the predictions' orange, edges a learned movable
  // object blocks in the objects' purple: a fleet manager may plan on them, knowing why not yet.
  const predicted = new Set(graph.predicted || []);
  const blocked = new Map((graph.blocked || []).map(([edge, object]) => [edge, object]));
  const plain = graph.edges.filter((_, k) => !predicted.has(k) && !blocked.has(k));
  const line = (edges, style) => L.polyline(edges.map(([a, b]) => [at(a), at(b)]), {
    renderer: renderers.routes, weight: 2, opacity: 0.8, ...style,
  });
  const drawnLayers = [line(plain, { color: COLORS.route }).bindTooltip(title)];
  predicted.forEach((k) => {
    if (blocked.has(k)) return;
    drawnLayers.push(line([graph.edges[k]], { color: COLORS.predicted, dashArray: '6 4' })
      .bindTooltip(`edge ${k}: through predicted space`));
  });
  blocked.forEach((object, k) => {
    drawnLayers.push(line([graph.edges[k]], { color: COLORS.object, dashArray: '2 4' })
      .bindTooltip(`edge ${k}: blocked by object ${object}`));
  });
  graph.kinds.forEach((kind, i) => {
    const doorway = kind === 'doorway';
    drawnLayers.push(L.circleMarker(at(i), {
      renderer: renderers.routes, radius: doorway ? 4 : 2.5, weight: 1, color: COLORS.route,
      fillColor: doorway ? COLORS.predicted : COLORS.route, fillOpacity: 1,
    }).bindTooltip(`node ${i}: ${kind}`));
  });
  drawnLayers.forEach((layer) => layers.routes.addLayer(layer));
  drawn.routes[id] = drawnLayers;
}

function applySection(items, draw, remove, keep) {
  if (!items) return;
  Object.entries(items).forEach(([key, item]) => {
    if (item === null) {
      remove(key);
      if (keep) delete keep[key];
    } else {
      draw(key, item);
      if (keep) keep[key] = item;
    }
  });
}

function clearAll() {
  Object.keys(drawn.tiles).forEach(removeTile);
  Object.keys(drawn.ownTiles).forEach(removeOwnTile);
  Object.keys(drawn.robots).forEach(removeRobot);
  Object.keys(drawn.submaps).forEach(removeSubmap);
  Object.keys(drawn.objects).forEach(removeObject);
  Object.keys(drawn.routes).forEach(removeRouteGraph);
  state = { robots: {}, paths: {}, submaps: {}, templates: {}, routeGraphs: {}, status: null };
}

// The newest `count` points of a path's runs, oldest run first.
function newestPoints(runs, count) {
  let excess = runs.reduce((n, run) => n + run.length, 0) - count;
  const kept = [];
  runs.forEach((run) => {
    const dropped = Math.min(Math.max(excess, 0), run.length);
    excess -= dropped;
    if (dropped < run.length) kept.push(run.slice(dropped));
  });
  return kept;
}

// Whole paths come with the whole state; deltas bring the points each path gained. Both are
// runs: a new run starts where the server placed or moved the robot's frame. Of a delta's runs
// the first continues the newest run the page has, each further one is new.
function applyPaths(paths, replace) {
  if (!paths) return;
  Object.entries(paths).forEach(([id, flatRuns]) => {
    const runs = flatRuns.map(ring);
    let path = runs;
    if (!replace) {
      const [continued, ...started] = runs;
      path = (state.paths[id] || []).slice();
      if (path.length > 0) {
        path[path.length - 1] = path[path.length - 1].concat(continued);
      } else if (continued.length > 0) {
        path.push(continued);
      }
      path = path.concat(started);
    }
    state.paths[id] = newestPoints(path, PATH_POINTS);
    if (state.robots[id]) drawRobot(id, state.robots[id]);
  });
}

function apply(event) {
  if (event.type === 'full') {
    clearAll();
    connected = true;
  } else if (event.seq <= lastSeq) {
    return;  // already in the whole state this browser got
  }
  lastSeq = event.seq;
  applySection(event.tiles, drawTile, removeTile);
  applySection(event.own_tiles, drawOwnTile, removeOwnTile);
  applySection(event.robots, drawRobot, removeRobot, state.robots);
  applyPaths(event.type === 'full' ? event.paths : event.path_points, event.type === 'full');
  applySection(event.submaps, drawSubmap, removeSubmap, state.submaps);
  applySection(event.objects, drawObject, removeObject);
  applySection(event.route_graphs, drawRouteGraph, removeRouteGraph, state.routeGraphs);
  applySection(event.templates, () => {}, () => {}, state.templates);
  if (event.status) state.status = event.status;
  document.getElementById('map').dataset.drawnTiles = Object.keys(drawn.tiles).length;
  // Edges drawn over all route graphs (one per shard), for whoever checks the page.
  const graphs = Object.values(state.routeGraphs);
  const mapElement = document.getElementById('map');
  mapElement.dataset.routeEdges = graphs.reduce((n, graph) => n + graph.edges.length, 0);
  mapElement.dataset.routePredictedEdges =
    graphs.reduce((n, graph) => n + (graph.predicted || []).length, 0);
  mapElement.dataset.routeBlockedEdges =
    graphs.reduce((n, graph) => n + (graph.blocked || []).length, 0);
  renderTables();
  renderStatus();
  fitOnce();
}

function fitOnce() {
  const tiles = Object.values(drawn.tiles);
  if (fitted || tiles.length === 0) return;
  const bounds = L.latLngBounds(tiles[0].bounds);
  tiles.forEach((tile) => bounds.extend(tile.bounds));
  map.fitBounds(bounds, { padding: [10, 10] });
  fitted = true;
}

const text = (value) => document.createTextNode(String(value));
function row(cells, attributes) {
  const tr = document.createElement('tr');
  Object.entries(attributes).forEach(([name, value]) => tr.setAttribute(name, value));
  cells.forEach((cell) => {
    const td = document.createElement('td');
    td.appendChild(text(cell));
    tr.appendChild(td);
  });
  return tr;
}
const rate = (bytesPerSecond) => {
  if (bytesPerSecond >= 1e6) return `${(bytesPerSecond / 1e6).toFixed(2)} MB/s`;
  if (bytesPerSecond >= 1e3) return `${(bytesPerSecond / 1e3).toFixed(1)} kB/s`;
  return `${Math.round(bytesPerSecond)} B/s`;
};
const degrees = (radians) => `${Math.round((radians * 180) / Math.PI)}°`;

function renderTables() {
  const robots = document.querySelector('#robots tbody');
  robots.replaceChildren(...Object.keys(state.robots).sort().map((id) => {
    const r = state.robots[id];
    const shown = shownState(r);
    const where = r.x === undefined ? '-' : `${r.x.toFixed(2)}, ${r.y.toFixed(2)}`;
    const standing = r.standing === 'trusted' ? 'fused' : r.standing;
    const unheard = shown === r.state ? '' : `the view process does not answer: ${r.state} when last heard`;
    const tr = row([id, shown, r.placement, standing, where,
      r.yaw === undefined ? '-' : degrees(r.yaw), r.rev ?? '-', rate(r.bps), r.ups.toFixed(1),
      r.latency_ms === null ? '-' : `${r.latency_ms.toFixed(1)} ms`],
    { 'data-robot': id, 'data-state': shown, 'data-standing': r.standing,
      'data-color': robotColor(id), title: unheard || r.standing_reason || r.waiting_reason || '' });
    const swatch = document.createElement('span');
    swatch.className = 'swatch robot';
    swatch.style.background = robotColor(id);
    tr.cells[0].prepend(swatch);
    return tr;
  }));
  const predictions = document.querySelector('#predictions tbody');
  predictions.replaceChildren(...Object.keys(state.submaps)
    .filter((id) => state.submaps[id].kind !== 'observed')
    .sort((a, b) => a - b)
    .map((id) => {
      const s = state.submaps[id];
      return row([id, s.kind.replace('predicted_', ''), s.state,
        s.precision === null ? '-' : s.precision.toFixed(3), s.source],
      { 'data-submap': id, 'data-state': s.state, 'data-color': submapColor(s) });
    }));
  const templates = document.querySelector('#templates tbody');
  templates.replaceChildren(...Object.keys(state.templates).sort((a, b) => a - b).map((id) => {
    const t = state.templates[id];
    return row([id, t.objects, `${t.w.toFixed(2)} x ${t.h.toFixed(2)}`], { 'data-template': id });
  }));
}

function setText(id, value) { document.getElementById(id).textContent = String(value); }

function renderStatus() {
  const s = state.status;
  if (!s) return;
  setText('status-tiles', s.tiles);
  setText('status-robots', s.robots);
  setText('status-live', connected ? s.live : 0);
  setText('status-lost', s.lost);
  setText('status-bytes', rate(s.bytes_per_s));
  setText('status-updates', s.updates_per_s.toFixed(1));
  const predictions = Object.entries(s.submaps).filter(([name]) => name !== 'observed')
    .map(([name, count]) => `${count} ${name}`);
  setText('status-predictions', predictions.length ? predictions.join(', ') : 'none');
  setText('status-objects', s.objects);
  setText('status-templates', s.templates);
  const byTopic = Object.entries(s.rejected_by_topic).map(([topic, n]) => `${topic}: ${n}`);
  setText('status-rejected', byTopic.length ? `${s.rejected} (${byTopic.join(', ')})` : '0');
  renderServer(s.server);
  updateGrid(s.grid);
}

// Which fleetmap-server serves the fleet (docs/standby.md), or each shard's (docs/shards.md), or
// that none is alive.
function renderServer(server) {
  const element = document.getElementById('status-server');
  element.dataset.state = server ? 'serving' : 'none';
  renderShards(server && server.shards ? server.shards : []);
  if (!server) {
    element.textContent = 'no fleet server';
    return;
  }
  const standby = (n) => (n ? ` + ${n} standby` : '');
  const parts = [];
  if (server.name) parts.push(`server ${server.name}${standby(server.standbys)}`);
  if (server.shards) {
    parts.push(`${server.shards.length} shards: ` + server.shards
      .map((s) => `${s.name} (server ${s.server}${standby(s.standbys)})`).join(', '));
  }
  element.textContent = parts.join('; ');
}

// Each shard's region, a dashed outline, named where the region meets the fused map (a region
// may reach far beyond it); redrawn when the regions or the map's extent change.
function renderShards(shards) {
  const grid = state.status && state.status.grid;
  const shown = grid ? [grid.ox, grid.oy, grid.ox + grid.w * grid.res, grid.oy + grid.h * grid.res]
    : [-50, -50, 50, 50];
  const key = JSON.stringify([shards.map((s) => [s.name, s.region]), shown]);
  if (key === drawnShards) return;
  drawnShards = key;
  shardLayer.clearLayers();
  const clamp = (v, lo, hi) => Math.min(Math.max(v, lo), hi);
  for (const shard of shards) {
    const [x0, y0, x1, y1] = shard.region;
    shardLayer.addLayer(L.rectangle([ll(x0, y0), ll(x1, y1)], {
      className: 'shard-region', color: '#6a1b9a', weight: 2, dashArray: '6 6', fill: false,
      interactive: false,
    }));
    const x = clamp((Math.max(x0, shown[0]) + Math.min(x1, shown[2])) / 2, x0, x1);
    const y = clamp((Math.max(y0, shown[1]) + Math.min(y1, shown[3])) / 2, y0, y1);
    shardLayer.addLayer(L.marker(ll(x, y), {
      interactive: false,
      icon: L.divIcon({ className: 'shard-label', html: `<span>shard ${shard.name}</span>`, iconSize: null }),
    }));
  }
}

function updateGrid(grid) {
  if (!grid || (gridOverlay && gridOverlay.count === grid.count)) return;
  const bounds = [ll(grid.ox, grid.oy), ll(grid.ox + grid.w * grid.res, grid.oy + grid.h * grid.res)];
  const url = `map.png?n=${grid.count}`;
  if (gridOverlay) {
    gridOverlay.setUrl(url);
    gridOverlay.setBounds(L.latLngBounds(bounds));
  } else {
    gridOverlay = L.imageOverlay(url, bounds, { className: 'fused-grid', opacity: 0.8 });
    gridLayer.addLayer(gridOverlay);
  }
  gridOverlay.count = grid.count;
}

function connect() {
  const connection = document.getElementById('connection');
  const events = new EventSource('events');
  events.onopen = () => {
    connection.dataset.state = 'open';
    connection.textContent = 'live';
  };
  events.onerror = () => {
    // The browser reconnects by itself; the view then sends the whole state again. Until then
    // nobody is shown live.
    connection.dataset.state = 'reconnecting';
    connection.textContent = 'reconnecting';
    if (events.readyState === EventSource.CLOSED) {
      // The browser gave up on this stream (an answer that was not one): try again, as it would.
      events.close();
      setTimeout(connect, 3000);
    }
    if (!connected) return;
    connected = false;
    Object.entries(state.robots).forEach(([id, robot]) => drawRobot(id, robot));
    renderTables();
    renderStatus();
  };
  events.onmessage = (message) => apply(JSON.parse(message.data));
}
connect();
