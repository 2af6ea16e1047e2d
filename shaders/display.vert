#version 330 core
// One triangle covering the viewport (no vertex buffer: positions from the id).
out vec2 uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  // The accumulation's row 0 is the top of the image, GL's is the bottom.
  uv = vec2(p.x, 1.0 - p.y);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
