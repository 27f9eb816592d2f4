// Put by server.mjs at the start of every page of docs/three.md's app (the page itself is the
// doc's): records every error the page meets (uncaught exceptions, rejected promises, scripts
// and modules that fail to load or resolve, console.error) and, once the page's WebGL canvas
// shows something other than its clear colour (or after 40 s of the page's time), writes
// <pre id="prt-test">{"errors": [...], "canvas": bool, "width", "height", "lit": fraction of
// pixels brighter than 8/255, "colours": distinct quantised colours}</pre> for --dump-dom.
(() => {
  const errors = [];
  const note = (what) => errors.push(String(what).slice(0, 500));
  addEventListener('error', (e) => {
    if (e.target && e.target !== window && (e.target.src || e.target.href)) note(`failed to load ${e.target.src || e.target.href}`);
    else note(e.message || e.error || 'error event');
  }, true);
  addEventListener('unhandledrejection', (e) => note(`unhandled rejection: ${e.reason && e.reason.message || e.reason}`));
  const consoleError = console.error.bind(console);
  console.error = (...a) => { note(`console.error: ${a.join(' ')}`); consoleError(...a); };
  // The drawing buffer kept after compositing, so that it can be read back between frames.
  const getContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (type, attrs) {
    if (type === 'webgl2' || type === 'webgl') attrs = { ...(attrs || {}), preserveDrawingBuffer: true };
    return getContext.call(this, type, attrs);
  };
  const look = () => {
    const canvas = document.querySelector('canvas');
    if (!canvas) return { canvas: false };
    const gl = canvas.getContext('webgl2') || canvas.getContext('webgl');
    if (!gl) return { canvas: true, gl: false };
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight, px = new Uint8Array(w * h * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let lit = 0;
    const colours = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (Math.max(px[i], px[i + 1], px[i + 2]) > 8) ++lit;
      colours.add((px[i] >> 4) << 8 | (px[i + 1] >> 4) << 4 | (px[i + 2] >> 4));
    }
    return { canvas: true, width: w, height: h, lit: lit / (w * h), colours: colours.size };
  };
  const report = (r) => {
    const pre = document.createElement('pre');
    pre.id = 'prt-test';
    pre.textContent = JSON.stringify({ errors, ...r });
    document.documentElement.appendChild(pre);
  };
  const start = performance.now();
  const poll = () => {
    const r = look();
    if ((r.lit > 0.02 && performance.now() - start > 3000) || performance.now() - start > 40000) report(r);
    else setTimeout(poll, 500);
  };
  addEventListener('load', () => setTimeout(poll, 500));
})();
