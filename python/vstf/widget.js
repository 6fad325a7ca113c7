// The front end of vstf.Viewer (anywidget): draws the frame's RGB bytes on
// a canvas and sends the sliders', menu's and boxes' values back; a click
// sends the pixel under it. Everything is computed in the kernel.

function slider(label, min, max, step, value) {
  const name = document.createElement("label");
  name.textContent = label;
  const input = document.createElement("input");
  Object.assign(input, { type: "range", min, max, step, value });
  const shown = document.createElement("span");
  return { name, input, shown };
}

function draw(model, canvas) {
  const w = model.get("width"), h = model.get("height");
  const view = model.get("pixels");
  if (!view || view.byteLength !== w * h * 3) return;
  const bytes = new Uint8Array(view.buffer, view.byteOffset, view.byteLength);
  canvas.width = w;
  canvas.height = h;
  const ctx = canvas.getContext("2d");
  const img = ctx.createImageData(w, h);
  for (let i = 0, j = 0; i < w * h; i++, j += 3) {
    img.data[4 * i] = bytes[j];
    img.data[4 * i + 1] = bytes[j + 1];
    img.data[4 * i + 2] = bytes[j + 2];
    img.data[4 * i + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
  canvas.dataset.frame = String(model.get("frame"));
}

function render({ model, el }) {
  const root = document.createElement("div");
  root.className = "vstf-viewer";
  const canvas = document.createElement("canvas");
  canvas.style.width = `${2 * model.get("width")}px`;
  const controls = document.createElement("div");
  controls.className = "vstf-controls";

  const span = model.get("t_max") - model.get("t_min");
  const time = slider("camera t", model.get("t_min"), model.get("t_max"), span / 400, model.get("t"));
  time.input.className = "vstf-time";
  const speed = slider("speed (c)", 0, model.get("speed_max"), 0.001, model.get("speed"));
  speed.input.className = "vstf-speed";
  speed.input.disabled = !model.get("has_mover");
  for (const s of [time, speed]) controls.append(s.name, s.input, s.shown);

  const menu = document.createElement("select");
  menu.className = "vstf-model";
  for (const m of ["infinite", "classical", "relativistic"]) menu.add(new Option(m, m, false, m === model.get("model")));
  const boxes = document.createElement("span");
  const box = (label, key) => {
    const b = document.createElement("input");
    b.type = "checkbox";
    b.checked = model.get(key);
    b.className = `vstf-${key}`;
    b.addEventListener("change", () => { model.set(key, b.checked); model.save_changes(); });
    const l = document.createElement("label");
    l.append(b, ` ${label} `);
    boxes.append(l);
  };
  box("Doppler", "doppler");
  box("searchlight", "searchlight");
  const modelName = document.createElement("label");
  modelName.textContent = "model";
  controls.append(modelName, menu, boxes);

  const status = document.createElement("div");
  status.className = "vstf-status";
  const debug = document.createElement("div");
  debug.className = "vstf-debug";
  debug.textContent = "click a pixel to see what its ray meets";
  root.append(canvas, controls, status, debug);
  el.append(root);

  const show = () => {
    time.shown.textContent = Number(model.get("t")).toFixed(3);
    speed.shown.textContent = model.get("has_mover") ? Number(model.get("speed")).toFixed(3) : "(no single mover)";
    status.textContent = model.get("status");
  };
  time.input.addEventListener("input", () => { model.set("t", Number(time.input.value)); model.save_changes(); });
  speed.input.addEventListener("input", () => { model.set("speed", Number(speed.input.value)); model.save_changes(); });
  menu.addEventListener("change", () => { model.set("model", menu.value); model.save_changes(); });
  canvas.addEventListener("click", (e) => {
    const r = canvas.getBoundingClientRect();
    const x = Math.floor(((e.clientX - r.left) * model.get("width")) / r.width);
    const y = Math.floor(((e.clientY - r.top) * model.get("height")) / r.height);
    model.set("pixel", [x, y]);
    model.save_changes();
  });
  const showDebug = () => {
    const text = model.get("debug");
    if (!text) return;
    const d = JSON.parse(text);
    const lines = [`pixel ${d.pixel.join(", ")} at camera t = ${d.camera_t}`];
    if (d.object === null) {
      lines.push("its ray meets nothing");
    } else {
      lines.push(`object: ${d.object}`);
      lines.push(`event seen: t = ${d.event.t.toFixed(6)}, x = (${d.event.x.map((v) => v.toFixed(4)).join(", ")})`);
      lines.push(`object's own time there: ${d.proper_time.toFixed(6)}`);
    }
    lines.push(`colour (8-bit): ${d.rgb8.join(", ")}`);
    debug.textContent = lines.join("\n");
  };
  const handlers = [
    ["change:pixels", () => draw(model, canvas)],
    ["change:t change:speed change:status", show],
    ["change:debug", showDebug],
  ];
  for (const [ev, f] of handlers) model.on(ev, f);
  draw(model, canvas);
  show();
  return () => { for (const [ev, f] of handlers) model.off(ev, f); };
}

export default { render };
