// A captured pointer drag on the canvas, the one pattern of every drag in the page (the light's
// turn, a probe bake's ball): it starts on a pointerdown `starts(e)` accepts, captures the
// pointer and keeps the event from the orbit controls (capture phase), reports each move's
// offset in pixels since the last, and ends on pointerup or pointercancel.

/** Calls move(dx, dy, e) for each move of a drag that starts(e) accepted. */
export function pointerDrag(canvas, starts, move) {
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => {
    if (!starts(e)) return;
    drag = { x: e.clientX, y: e.clientY, id: e.pointerId };
    canvas.setPointerCapture(e.pointerId);
    e.stopImmediatePropagation();
    e.preventDefault();
  }, { capture: true });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag || e.pointerId !== drag.id) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX, drag.y = e.clientY;
    move(dx, dy, e);
    e.stopImmediatePropagation();
  }, { capture: true });
  const end = (e) => { if (drag && e.pointerId === drag.id) drag = null; };
  canvas.addEventListener('pointerup', end, { capture: true });
  canvas.addEventListener('pointercancel', end, { capture: true });
}
