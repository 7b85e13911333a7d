// Camera pass: world-space position and normal for shading and the shadow lookup, texture
// coordinates for the base colour.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 texcoord;

uniform mat4 clipFromWorld;

out vec3 worldPosition;
out vec3 worldNormal;
out vec2 baseColorTexcoord;

void main() {
  worldPosition = position;
  worldNormal = normal;
  baseColorTexcoord = texcoord;
  gl_Position = clipFromWorld * vec4(position, 1.0f);
}
