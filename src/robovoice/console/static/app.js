// robovoice console: vanilla JS, no build step. Everything about the robot comes from the
// console's API and WebSocket, which read it through the robot's own MCP tools.
"use strict";

const $ = (sel) => document.querySelector(sel);
const el = (tag, attrs = {}, ...children) => {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") node.className = v; else if (k === "text") node.textContent = v; else node.setAttribute(k, v);
  }
  for (const c of children) node.append(c);
  return node;
};
const SVG = "http://www.w3.org/2000/svg";
const svg = (tag, attrs = {}) => {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  return node;
};
const fmtArgs = (args) => Object.entries(args || {}).map(([k, v]) => `${k}=${JSON.stringify(v)}`).join(", ");
const short = (text, n = 160) => (text && text.length > n ? text.slice(0, n - 1) + "…" : text || "");

// ---------------------------------------------------------------- the robot: map and status
const robot = { map: null, mapKey: "", pose: null };
window.robovoice = robot; // for tests and curious people

function drawMap(map) {
  const key = JSON.stringify(map);
  if (key === robot.mapKey) return;
  robot.map = map; robot.mapKey = key;
  const b = map.bounds, pad = 0.4, root = $("#map");
  const top = Math.max(b.max_y, ...(map.places || []).map((p) => p.y)) + pad + 0.5, right = 1.6;
  root.setAttribute("viewBox", `${b.min_x - pad} ${-top} ${b.max_x - b.min_x + pad + right} ${top - b.min_y + pad}`);
  root.replaceChildren();
  root.append(svg("rect", { x: b.min_x, y: -b.max_y, width: b.max_x - b.min_x, height: b.max_y - b.min_y,
                            fill: "none", stroke: "#9ca3af", "stroke-width": 0.06 }));
  for (const [[x1, y1], [x2, y2]] of map.ways || []) {
    root.append(svg("line", { class: "way", x1, y1: -y1, x2, y2: -y2 }));
  }
  for (const p of map.places || []) {
    const g = svg("g", { class: "place" + (p.reachable ? "" : " unreachable"), "data-place": p.name });
    g.append(svg("circle", { cx: p.x, cy: -p.y, r: 0.14 }));
    const label = svg("text", { x: p.x + 0.2, y: -p.y - 0.15 });
    label.textContent = p.reachable ? p.name : `${p.name} ✕`;
    const title = svg("title"); title.textContent = p.blocked ? `${p.name}: ${p.blocked}` : p.description || p.name;
    g.append(label, title);
    root.append(g);
  }
  root.append(svg("polyline", { id: "path", points: "" }));
  const bot = svg("g", { id: "robot" });
  bot.append(svg("circle", { r: 0.28 }), svg("path", { d: "M0.42 0 L0.12 -0.15 L0.12 0.15 Z" }));
  root.append(bot);
}

function drawRobot(state) {
  const pose = state.pose;
  if (!pose || !$("#robot")) return;
  robot.pose = pose;
  robot.stateStamp = (state.stamps || {}).pose;
  const bot = $("#robot");
  bot.setAttribute("transform", `translate(${pose.x} ${-pose.y}) rotate(${-pose.heading_deg})`);
  bot.dataset.x = pose.x; bot.dataset.y = pose.y; bot.dataset.place = pose.nearest_place || "";
  bot.dataset.moving = pose.moving ? "true" : "false";
  $("#path").setAttribute("points", (state.path || []).map(([x, y]) => `${x},${-y}`).join(" "));
  $("#robot-place").textContent = pose.nearest_place + (pose.moving ? " (driving)" : "");
  $("#pose-text").textContent = `x ${pose.x.toFixed(2)} m · y ${pose.y.toFixed(2)} m · heading ${Math.round(pose.heading_deg)}°`;
}

function showState(state) {
  if (state.map) drawMap(state.map);
  drawRobot(state);
  const bat = state.battery;
  if (bat) $("#battery").textContent = `${Math.round(bat.percent)} %${bat.charging ? " ⚡ charging" : ""}`;
  if (state.projector) $("#projector").textContent = state.projector.on ? "on" : "off";
  const call = state.call;
  if (call) $("#call").textContent = call.in_call ? `with ${call.contact}${call.remote_speaking ? " (speaking)" : ""}` : "no call";
  if (state.camera && state.camera.data) $("#camera").src = `data:${state.camera.mime};base64,${state.camera.data}`;
  const errors = Object.entries(state.errors || {});
  $("#robot-errors").textContent = errors.map(([k, v]) => `${k}: ${v}`).join(" · ");
}

// ---------------------------------------------------------------- the conversation
const turnNodes = new Map();
const progressNodes = new Map();

function turnNode(id, source) {
  let node = turnNodes.get(id);
  if (!node) {
    node = el("div", { class: `turn ${source}`, "data-turn": id },
              el("div", { class: "head", text: `#${id} · ${source === "voice" ? "spoken" : "typed"} · ${new Date().toLocaleTimeString()}` }));
    turnNodes.set(id, node);
    const list = $("#turns");
    const atBottom = list.scrollHeight - list.scrollTop - list.clientHeight < 40;
    list.append(node);
    while (list.children.length > 60) { turnNodes.delete(Number(list.firstChild.dataset.turn)); list.firstChild.remove(); }
    if (atBottom) list.scrollTop = list.scrollHeight;
  }
  return node;
}

function line(cls, text, attrs = {}) { return el("div", { class: `ev ${cls}`, text, ...attrs }); }

function resultDetails(ev) {
  const body = ev.result !== null && ev.result !== undefined ? JSON.stringify(ev.result, null, 2) : ev.text;
  const summary = ev.is_error
    ? `← ${ev.name} ERROR ${ev.error || ""}${ev.result && ev.result.message ? ": " + ev.result.message : ""}`
    : `← ${ev.name} ok`;
  const d = el("details", { class: `ev result${ev.is_error ? " err" : ""}`, "data-tool": ev.name },
               el("summary", { text: `${summary} (${Math.round(ev.duration_ms)} ms)` }), el("pre", { text: body }));
  if (ev.is_error && ev.result && ev.result.hint) d.append(el("div", { class: "note", text: `hint: ${ev.result.hint}` }));
  return d;
}

function addEvent(msg) {
  const ev = msg.event, node = turnNode(msg.turn, msg.source);
  let child = null;
  switch (ev.kind) {
    case "TurnStarted": if (msg.source === "typed") child = line("user", `you: ${ev.text}`); break;
    case "WakeWordHeard": child = line("note", `wake word (score ${ev.score.toFixed(2)})${ev.during_playback ? " while the robot spoke" : ""}`); break;
    case "WakeWordRejected": child = line("note", "wake phrase in the robot's own playback: ignored"); break;
    case "TranscriptReady": child = line("user", `heard: “${ev.text}” (speech-to-text ${Math.round(ev.inference_ms)} ms)`); break;
    case "VoiceTurnStarted": if (ev.mode === "audio") child = line("user", `heard ${ev.audio_s.toFixed(1)} s of audio (sent as audio)`); break;
    case "UtteranceIgnored":
      node.classList.add("ignored");
      child = line("note", `ignored: ${ev.reason.replaceAll("_", " ")}${ev.text ? ` (“${short(ev.text, 80)}”)` : ""}`); break;
    case "FirstTokenReceived": break;
    case "ToolCalled": child = line("call", `→ ${ev.name}(${fmtArgs(ev.arguments)})`, { "data-tool": ev.name }); break;
    case "ToolProgressed": {
      const key = `${msg.turn}:${ev.name}`;
      const text = `… ${ev.name}: ${ev.message || ""}${ev.total ? ` (${Math.round(100 * ev.progress / ev.total)} %)` : ""}`;
      const existing = progressNodes.get(key);
      if (existing) { existing.textContent = text; return; }
      child = line("note", text); progressNodes.set(key, child); break;
    }
    case "ToolReturned": child = resultDetails(ev); break;
    case "SentenceReady": child = line("robot", ev.text); break;
    case "SentenceSpoken": if (ev.kind !== "reply") child = line("robot", `(${ev.kind}) ${ev.text}`); break;
    case "BackendFailed": child = line("warn", `no language model answered: ${short(ev.reason, 120)}`); break;
    case "BargedIn": child = line("warn", "barge-in: the robot stopped talking and listens"); break;
    case "StopHeard": child = line("warn", `STOP (“${ev.text}”): the robot's stop tool, straight, no model`); break;
    case "RobotStopped": child = line(ev.ok ? "note" : "warn", `robot ${ev.ok ? "stopped" : "DID NOT STOP"} ${Math.round(ev.latency_ms)} ms after the end of speech`); break;
    case "TurnFinished": if (!ev.reply && !(ev.calls || []).length) child = line("note", "(no answer)"); break;
    case "VoiceTurnFinished": if (ev.cancelled) child = line("note", "turn cancelled"); break;
    default: break;
  }
  if (child) node.append(child);
  const list = $("#turns");
  if (list.scrollHeight - list.scrollTop - list.clientHeight < 120) list.scrollTop = list.scrollHeight;
}

const STAGES = [["transcript", "seg-stt", "speech-to-text"], ["first_token", "seg-model", "model: first token"],
                ["tool_result", "seg-tool", "tool calls"], ["first_sentence", "seg-model", "model: first sentence"],
                ["first_audio", "seg-speech", "speech: first audio"], ["finished", "seg-rest", "rest of the turn"]];

function latencyBar(marks) {
  const at = (stage) => {
    if (marks[stage] !== undefined) return marks[stage];
    const hits = Object.entries(marks).filter(([k]) => k.startsWith(stage + ":")).map(([, v]) => v);
    return hits.length ? Math.max(...hits) : undefined;
  };
  const points = STAGES.map(([stage, cls, label]) => [at(stage), cls, label]).filter(([t]) => t !== undefined);
  const end = Math.max(...points.map(([t]) => t), 1);
  const bar = el("div", { class: "latency", title: "latency by stage, from the end of speech" });
  let prev = 0;
  const parts = [];
  for (const [t, cls, label] of points.sort((a, b) => a[0] - b[0])) {
    const width = Math.max(0, t - prev);
    if (width > 0) bar.append(el("span", { class: cls, style: `width:${(100 * width) / end}%`, title: `${label}: ${Math.round(width)} ms` }));
    parts.push(`${label} ${Math.round(t)}`);
    prev = Math.max(prev, t);
  }
  return [bar, el("div", { class: "latency-text", text: parts.join(" · ") + " ms" })];
}

function endTurn(msg) {
  const node = turnNode(msg.turn, msg.source);
  if (node.querySelector(".latency")) return;
  if (Object.keys(msg.latency_ms || {}).length) node.append(...latencyBar(msg.latency_ms));
  if (msg.answer) node.append(el("audio", { controls: "", preload: "none", src: msg.answer }));
}

function replayTurns(turns) {
  $("#turns").replaceChildren(); turnNodes.clear(); progressNodes.clear();
  for (const t of turns) {
    turnNode(t.id, t.source);
    for (const ev of t.events) addEvent({ turn: t.id, source: t.source, event: ev });
    if (!t.open) endTurn({ turn: t.id, source: t.source, latency_ms: t.latency_ms, answer: t.answer });
  }
}

// ---------------------------------------------------------------- live events
let retry = 500;
function connectEvents() {
  const ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws/events`);
  ws.onopen = () => { retry = 500; $("#link-state").textContent = "live"; $("#link-state").className = "chip ok"; };
  ws.onclose = () => {
    $("#link-state").textContent = "reconnecting…"; $("#link-state").className = "chip bad";
    setTimeout(connectEvents, retry); retry = Math.min(retry * 2, 8000);
  };
  ws.onmessage = (e) => {
    const msg = JSON.parse(e.data);
    switch (msg.type) {
      case "hello":
        $("#robot-name").textContent = `robot: ${msg.robot_name}`; $("#model-name").textContent = `model: ${msg.model}`;
        showVoice(msg.voice); showState(msg.robot); replayTurns(msg.turns); break;
      case "state": showState(msg.state); break;
      case "event": addEvent(msg); break;
      case "turn_end": endTurn(msg); break;
      case "audit": auditChanged(); break;
      default: break;
    }
  };
}

function showVoice(v) {
  const n = $("#voice-state");
  n.textContent = `voice: ${v.state}`; n.title = v.detail || "";
  n.className = "chip " + (v.state === "ready" ? "ok" : v.state === "failed" || v.state === "off" ? "bad" : "");
}
setInterval(async () => {
  try { const r = await fetch("/api/state?turns=0"); if (r.ok) showVoice((await r.json()).voice); } catch (e) { /* offline */ }
}, 3000);

// ---------------------------------------------------------------- typing
$("#say-form").addEventListener("submit", async (e) => {
  e.preventDefault();
  const input = $("#say-text"), text = input.value.trim();
  if (!text) return;
  input.value = ""; input.disabled = true;
  try {
    const r = await fetch("/api/say", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ text }) });
    if (!r.ok) alert(`the console refused: ${(await r.json().catch(() => ({}))).message || r.status}`);
  } finally { input.disabled = false; input.focus(); }
});

// ---------------------------------------------------------------- the microphone and the speaker
const audio = { ctx: null, ws: null, node: null, stream: null, on: false, nextTime: 0, sources: [], carry: 0 };

function playPcm(buffer) {
  const rate = new DataView(buffer).getUint32(0, true);
  if (rate === 0) { for (const s of audio.sources) { try { s.stop(); } catch (e) { /* ended */ } } audio.sources = []; audio.nextTime = 0; return; }
  const pcm = new Int16Array(buffer, 4);
  const buf = audio.ctx.createBuffer(1, pcm.length, rate), ch = buf.getChannelData(0);
  for (let i = 0; i < pcm.length; i++) ch[i] = pcm[i] / 32768;
  const src = audio.ctx.createBufferSource();
  src.buffer = buf; src.connect(audio.ctx.destination);
  const at = Math.max(audio.ctx.currentTime + 0.05, audio.nextTime);
  src.start(at); audio.nextTime = at + buf.duration;
  robot.robotAudioS = (robot.robotAudioS || 0) + buf.duration;
  audio.sources.push(src); src.onended = () => { audio.sources = audio.sources.filter((s) => s !== src); };
}

function downsample(input, fromRate) {
  // average over each 1/16000 s window (a simple anti-aliasing low-pass), then int16
  const ratio = fromRate / 16000, n = Math.floor((input.length + audio.carry) / ratio);
  const out = new Int16Array(n);
  let pos = -audio.carry;
  for (let i = 0; i < n; i++) {
    const start = Math.max(0, Math.round(pos)), end = Math.min(input.length, Math.round(pos + ratio));
    let sum = 0; for (let j = start; j < end; j++) sum += input[j];
    const v = end > start ? sum / (end - start) : 0;
    out[i] = Math.max(-32768, Math.min(32767, Math.round(v * 32767)));
    pos += ratio;
  }
  audio.carry = input.length - pos;
  return out;
}

async function startMic() {
  if (audio.on) return true;
  try {
    audio.ctx = audio.ctx || new AudioContext();
    await audio.ctx.resume();
    audio.stream = await navigator.mediaDevices.getUserMedia({ audio: { channelCount: 1, echoCancellation: true, noiseSuppression: true } });
    await audio.ctx.audioWorklet.addModule("/static/mic-worklet.js");
    const source = audio.ctx.createMediaStreamSource(audio.stream);
    audio.node = new AudioWorkletNode(audio.ctx, "mic-tap");
    const mute = audio.ctx.createGain(); mute.gain.value = 0;
    source.connect(audio.node); audio.node.connect(mute); mute.connect(audio.ctx.destination);
    audio.ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws/audio`);
    audio.ws.binaryType = "arraybuffer";
    audio.ws.onmessage = (e) => { if (e.data instanceof ArrayBuffer) playPcm(e.data); };
    audio.ws.onclose = (e) => { if (audio.on || e.reason) $("#mic-state").textContent = e.reason || "microphone closed"; stopMic(); };
    let pending = [], pendingLen = 0;
    audio.node.port.onmessage = (e) => {
      const pcm = downsample(e.data, audio.ctx.sampleRate);
      pending.push(pcm); pendingLen += pcm.length;
      let peak = 0; for (let i = 0; i < e.data.length; i++) peak = Math.max(peak, Math.abs(e.data[i]));
      $("#mic-level span").style.width = `${Math.min(100, peak * 200)}%`;
      if (pendingLen >= 1600 && audio.ws.readyState === WebSocket.OPEN) { // every 100 ms
        const chunk = new Int16Array(pendingLen); let o = 0;
        for (const p of pending) { chunk.set(p, o); o += p.length; }
        audio.ws.send(chunk.buffer); pending = []; pendingLen = 0;
        robot.micSent = (robot.micSent || 0) + chunk.length;
      }
    };
    await new Promise((resolve, reject) => { audio.ws.onopen = resolve; audio.ws.onerror = reject; });
    audio.on = true;
    $("#mic-toggle").textContent = "Hands-free: on"; $("#mic-toggle").classList.add("on");
    $("#mic-state").textContent = "listening for the wake word";
    return true;
  } catch (err) {
    $("#mic-state").textContent = `microphone unavailable: ${err.message || err}`;
    stopMic();
    return false;
  }
}

function stopMic() {
  if (audio.on) $("#mic-state").textContent = "microphone off";
  audio.on = false;
  if (audio.node) { audio.node.port.onmessage = null; audio.node.disconnect(); audio.node = null; }
  if (audio.stream) { audio.stream.getTracks().forEach((t) => t.stop()); audio.stream = null; }
  if (audio.ws && audio.ws.readyState <= 1) audio.ws.close();
  audio.ws = null;
  $("#mic-toggle").textContent = "Hands-free: off"; $("#mic-toggle").classList.remove("on");
}

$("#mic-toggle").addEventListener("click", () => (audio.on ? stopMic() : startMic()));
const ptt = $("#ptt");
ptt.addEventListener("pointerdown", async () => {
  ptt.classList.add("held");
  if (await startMic()) { audio.ws.send(JSON.stringify({ type: "ptt" })); $("#mic-state").textContent = "talk now"; }
});
for (const ev of ["pointerup", "pointerleave"]) ptt.addEventListener(ev, () => ptt.classList.remove("held"));

// ---------------------------------------------------------------- tools by hand
let tools = [];
async function loadTools() {
  const r = await fetch("/api/tools");
  tools = (await r.json()).tools;
  const select = $("#tool-select"), filter = $("#audit-tool");
  select.replaceChildren(...tools.map((t) => el("option", { value: t.name, text: t.name + (t.for_model ? "" : " (for people)") })));
  filter.replaceChildren(el("option", { value: "", text: "all tools" }), ...tools.map((t) => el("option", { value: t.name, text: t.name })));
  showTool();
}

function fieldFor(name, schema, required) {
  const label = el("label", { text: `${name}${required ? " *" : ""} ` });
  let input;
  const type = Array.isArray(schema.type) ? schema.type[0] : schema.type;
  if (schema.enum) {
    input = el("select", { name }); for (const v of schema.enum) input.append(el("option", { value: JSON.stringify(v), text: String(v) }));
    input.dataset.kind = "json";
  } else if (type === "boolean") {
    input = el("input", { type: "checkbox", name }); input.dataset.kind = "boolean";
    if (schema.default === true) input.checked = true;
  } else if (type === "number" || type === "integer") {
    input = el("input", { type: "number", name, step: type === "integer" ? "1" : "any" }); input.dataset.kind = "number";
  } else if (type === "string" || type === undefined) {
    input = el("input", { type: "text", name, placeholder: (schema.examples || []).join(", ") }); input.dataset.kind = "string";
    if (schema.examples) {
      const list = el("datalist", { id: `dl-${name}` }); for (const v of schema.examples) list.append(el("option", { value: v }));
      input.setAttribute("list", list.id); label.append(list);
    }
  } else {
    input = el("textarea", { name, rows: 2, placeholder: "JSON" }); input.dataset.kind = "json";
  }
  if (schema.default !== undefined && input.dataset.kind !== "boolean") input.value = input.dataset.kind === "json" ? JSON.stringify(schema.default) : schema.default;
  input.dataset.required = required ? "1" : "";
  label.append(input);
  if (schema.description) label.append(el("div", { class: "note", text: schema.description }));
  return label;
}

function showTool() {
  const tool = tools.find((t) => t.name === $("#tool-select").value);
  const info = $("#tool-info"), form = $("#tool-form");
  info.replaceChildren(); form.replaceChildren();
  if (!tool) return;
  const badges = Object.entries(tool.annotations || {}).filter(([k, v]) => v === true || k === "title")
    .map(([k, v]) => el("span", { class: "badge", text: k === "title" ? v : k.replace("Hint", "") }));
  if (!tool.for_model) badges.push(el("span", { class: "badge people", text: "not offered to the model" }));
  info.append(el("p", { text: tool.description }), el("div", {}, ...badges));
  const props = (tool.input_schema && tool.input_schema.properties) || {}, required = new Set((tool.input_schema || {}).required || []);
  for (const [name, schema] of Object.entries(props)) form.append(fieldFor(name, schema, required.has(name)));
  form.append(el("button", { type: "submit", text: `Call ${tool.name}` }));
}

$("#tool-select").addEventListener("change", showTool);
$("#tool-form").addEventListener("submit", async (e) => {
  e.preventDefault();
  const args = {};
  for (const input of $("#tool-form").querySelectorAll("[name]")) {
    const kind = input.dataset.kind;
    if (kind === "boolean") { args[input.name] = input.checked; continue; }
    if (input.value === "" && !input.dataset.required) continue;
    try { args[input.name] = kind === "number" ? Number(input.value) : kind === "json" ? JSON.parse(input.value) : input.value; }
    catch (err) { $("#tool-result").textContent = `${input.name}: not JSON (${err.message})`; return; }
  }
  const name = $("#tool-select").value;
  $("#tool-result").textContent = `calling ${name}(${fmtArgs(args)}) …`;
  const r = await fetch("/api/call", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ name, arguments: args }) });
  const result = await r.json();
  const image = (result.content || []).find((b) => b.type === "image");
  $("#tool-image").src = image ? `data:${image.mime};base64,${image.data}` : "";
  $("#tool-result").textContent = `${result.is_error ? "ERROR " + (result.error || "") : "ok"} in ${result.duration_ms} ms\n` +
    JSON.stringify(result.structured !== null ? result.structured : result.content, null, 2);
});

// ---------------------------------------------------------------- the audit log
let auditTimer = null;
function auditChanged() { clearTimeout(auditTimer); auditTimer = setTimeout(loadAudit, 200); }
async function loadAudit() {
  const params = new URLSearchParams({ limit: "200" });
  if ($("#audit-tool").value) params.set("tool", $("#audit-tool").value);
  if ($("#audit-errors").checked) params.set("errors", "true");
  const r = await fetch(`/api/audit?${params}`);
  const rows = (await r.json()).records.map((a) => el("tr", { class: a.outcome === "error" ? "err" : "", "data-tool": a.tool },
    el("td", { text: a.time.slice(11, 23) }), el("td", { text: a.source }), el("td", { text: a.tool }),
    el("td", { class: "args", text: fmtArgs(a.arguments) }),
    el("td", { text: a.outcome === "error" ? `${a.error}` : "ok" }), el("td", { text: String(Math.round(a.duration_ms)) })));
  $("#audit tbody").replaceChildren(...rows);
}
$("#audit-tool").addEventListener("change", loadAudit);
$("#audit-errors").addEventListener("change", loadAudit);

connectEvents();
loadTools().then(loadAudit);
