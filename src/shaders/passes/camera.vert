// Camera pass: world-space position and normal for shading and the shadow lookup.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 clipFromWorld;

out vec3 worldPosition;
out vec3 worldNormal;

void main() {
  worldPosition = position;
  worldNormal = normal;
  gl_Position = clipFromWorld * vec4(position, 1.0f);
}
