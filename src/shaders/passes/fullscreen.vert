// One triangle covering the viewport (from gl_VertexID, no vertex buffer): a fragment per texel of
// the render target, for passes that compute an image texel by texel through the rasteriser.
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0f - 1.0f, 0.0f, 1.0f);
}
