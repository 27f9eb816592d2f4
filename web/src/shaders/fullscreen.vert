// A triangle covering the viewport, from the positions (-1,-1), (3,-1), (-1,3).
precision highp float;
in vec3 position;
void main() { gl_Position = vec4(position.xy, 1.0, 1.0); }
