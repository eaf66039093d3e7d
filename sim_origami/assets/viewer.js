// report.html's 3-D view: the MuJoCo run's bodies drawn with WebGL from the JSON in #motion-data (report.py's
// motion_view). Drag turns, the wheel zooms, the slider walks the sweep, the select picks the branch.
// Written for this page (about 200 lines) rather than vendoring a 600 kB library: it draws flat-shaded solids
// and crease lines, nothing more.
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("motion-data").textContent);
  // each branch's poses: base64 of little-endian int16, frames x bodies x 7 (report.py's motion_view): the position's
  // offset from data.centre in units of the branch's scale (m), then the quaternion x y z w in units of 1 / 32767
  const SEVEN = 7 * data.bodies.length;
  data.branches.forEach((b) => {
    const bytes = Uint8Array.from(atob(b.poses), (ch) => ch.charCodeAt(0));
    const ints = new DataView(bytes.buffer);
    const frames = [];
    for (let at = 0; SEVEN > 0 && at + 2 * SEVEN <= bytes.length; at += 2 * SEVEN) {
      const pose = new Float32Array(SEVEN);
      for (let i = 0; i < SEVEN; i++) {
        const v = ints.getInt16(at + 2 * i, true);
        pose[i] = i % 7 < 3 ? data.centre[i % 7] + v * b.scale : v / 32767;
      }
      frames.push(pose);
    }
    b.poses = frames;
  });
  const canvas = document.getElementById("view");
  const slider = document.getElementById("view-frame");
  const play = document.getElementById("view-play");
  const select = document.getElementById("view-branch");
  const label = document.getElementById("view-input");
  // preserveDrawingBuffer: the picture stays readable (a screenshot, a test) after it is shown
  const gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
  if (!gl) {
    document.getElementById("view-note").textContent = "This browser offers no WebGL: the 3-D view is off.";
    return;
  }

  const VERTEX = `
    attribute vec3 p; attribute vec3 n; attribute vec3 c;
    uniform mat4 proj, view, model; varying vec3 vn, vc;
    void main() { vn = (view * model * vec4(n, 0.0)).xyz; vc = c; gl_Position = proj * view * model * vec4(p, 1.0); }`;
  const FRAGMENT = `
    precision mediump float; varying vec3 vn, vc; uniform float lit; uniform vec3 tint;
    void main() {
      float l = 0.35 + 0.65 * abs(dot(normalize(vn), normalize(vec3(0.3, 0.5, 1.0))));
      gl_FragColor = vec4(lit > 0.5 ? vc * l : tint, 1.0);
    }`;
  function shader(type, source) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  const program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER, FRAGMENT));
  gl.linkProgram(program);
  gl.useProgram(program);
  const at = (name) => gl.getAttribLocation(program, name);
  const u = (name) => gl.getUniformLocation(program, name);

  // Every body's triangles, unindexed with their face normal, then every crease's two ends: one buffer.
  const values = [];
  const ranges = data.bodies.map((b) => {
    const first = values.length / 9;
    for (let t = 0; t < b.f.length; t += 3) {
      const [a, bb, cc] = [b.f[t], b.f[t + 1], b.f[t + 2]].map((i) => b.v.slice(3 * i, 3 * i + 3));
      const e1 = [bb[0] - a[0], bb[1] - a[1], bb[2] - a[2]], e2 = [cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]];
      const nrm = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
      const len = Math.hypot(...nrm) || 1;
      // faces looking down the body's z are the paper's back, the rest (top and edges) its front
      const colour = nrm[2] / len < -0.5 ? b.back : b.front;
      for (const p of [a, bb, cc]) values.push(...p, ...nrm.map((x) => x / len), ...colour);
    }
    return [first, values.length / 9 - first];
  });
  // each crease's segments (one, or one on each face of a thin panel)
  const lines = data.creases.map((c) => {
    const first = values.length / 9;
    for (let k = 0; k < c.p.length; k += 3) values.push(...c.p.slice(k, k + 3), 0, 0, 1, 0, 0, 0);
    return [first, c.p.length / 3];
  });
  const buffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(values), gl.STATIC_DRAW);
  [["p", 0], ["n", 3], ["c", 6]].forEach(([name, offset]) => {
    gl.enableVertexAttribArray(at(name));
    gl.vertexAttribPointer(at(name), 3, gl.FLOAT, false, 36, offset * 4);
  });
  gl.enable(gl.DEPTH_TEST);
  gl.enable(gl.POLYGON_OFFSET_FILL);
  gl.polygonOffset(1, 1); // panels a hair behind the crease lines drawn on them

  // 4 x 4 matrices, column-major as WebGL takes them
  function multiply(a, b) {
    const m = new Float32Array(16);
    for (let i = 0; i < 4; i++) for (let j = 0; j < 4; j++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + j] * b[i * 4 + k];
      m[i * 4 + j] = s;
    }
    return m;
  }
  function pose(p, q) { // position and quaternion (x, y, z, w), made unit length again after its rounding
    const norm = Math.hypot(q[0], q[1], q[2], q[3]) || 1;
    const [x, y, z, w] = [q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm];
    return new Float32Array([
      1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
      2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
      2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
      p[0], p[1], p[2], 1]);
  }
  const rotX = (a) => new Float32Array([1, 0, 0, 0, 0, Math.cos(a), Math.sin(a), 0, 0, -Math.sin(a), Math.cos(a), 0, 0, 0, 0, 1]);
  const rotZ = (a) => new Float32Array([Math.cos(a), Math.sin(a), 0, 0, -Math.sin(a), Math.cos(a), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  const shift = (x, y, z) => new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1]);
  function perspective(aspect, near, far) {
    const f = 1 / Math.tan(0.3); // 34 deg field of view
    return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
      0, 0, (2 * far * near) / (near - far), 0]);
  }

  const R = data.radius || 1;
  const camera = { yaw: -0.6, pitch: 1.0, distance: 2.5 * R };
  let branch = 0;
  data.branches.forEach((b, k) => select.add(new Option(b.followed && b.followed !== b.name ? `${b.name} (followed ${b.followed})` : b.name, k)));
  select.disabled = data.branches.length < 2;
  const MOUNTAIN = [0.85, 0.1, 0.1], VALLEY = [0.1, 0.3, 0.9], FLAT = [0.45, 0.45, 0.45];

  function draw() {
    const b = data.branches[branch], frame = Math.min(+slider.value, b.poses.length - 1), poses = b.poses[frame];
    const degrees = (b.input[frame] * 180) / Math.PI;
    label.textContent = `${data.input} = ${degrees.toFixed(2)} deg (frame ${frame + 1} of ${b.poses.length})`;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.uniformMatrix4fv(u("proj"), false, perspective(canvas.width / canvas.height, camera.distance / 100, camera.distance + 4 * R));
    const c = data.centre;
    // z up: the camera looks at the centre from `pitch` off the vertical, turned `yaw` about z
    const view = multiply(shift(0, 0, -camera.distance), multiply(rotX(-camera.pitch), multiply(rotZ(camera.yaw), shift(-c[0], -c[1], -c[2]))));
    gl.uniformMatrix4fv(u("view"), false, view);
    const models = data.bodies.map((_, k) => pose(poses.slice(7 * k, 7 * k + 3), poses.slice(7 * k + 3, 7 * k + 7)));
    gl.uniform1f(u("lit"), 1);
    ranges.forEach(([first, count], k) => {
      gl.uniformMatrix4fv(u("model"), false, models[k]);
      gl.drawArrays(gl.TRIANGLES, first, count);
    });
    gl.uniform1f(u("lit"), 0);
    data.creases.forEach((crease, k) => {
      const side = b.sides[k];
      gl.uniform3fv(u("tint"), side === "M" ? MOUNTAIN : side === "V" ? VALLEY : FLAT);
      gl.uniformMatrix4fv(u("model"), false, models[crease.body]);
      gl.drawArrays(gl.LINES, lines[k][0], lines[k][1]);
    });
  }

  function chooseBranch() {
    branch = +select.value;
    slider.max = data.branches[branch].poses.length - 1;
    draw();
  }
  let timer = null;
  function toggle() {
    if (timer !== null) {
      clearInterval(timer);
      timer = null;
      play.textContent = "play";
      return;
    }
    play.textContent = "pause";
    timer = setInterval(() => {
      slider.value = (+slider.value + 1) % (+slider.max + 1);
      draw();
    }, 40);
  }
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (drag === null) return;
    camera.yaw += (e.clientX - drag[0]) * 0.01;
    camera.pitch = Math.min(Math.PI, Math.max(0, camera.pitch - (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault(); // zoom the view, not the page
    camera.distance = Math.min(20 * R, Math.max(0.3 * R, camera.distance * Math.exp(e.deltaY * 0.001)));
    draw();
  }, { passive: false });
  slider.addEventListener("input", draw);
  select.addEventListener("change", chooseBranch);
  play.addEventListener("click", toggle);
  chooseBranch();
})();
