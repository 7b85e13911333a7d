// Light pass: scene geometry seen from the light, with texture coordinates for alpha-masked
// casters.
layout(location = 0) in vec3 position;
layout(location = 2) in vec2 texcoord;

uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromView;

out vec3 lightViewPosition;
out vec2 baseColorTexcoord;

void main() {
  vec4 view = lightViewFromWorld * vec4(position, 1.0f);
  lightViewPosition = view.xyz;
  baseColorTexcoord = texcoord;
  gl_Position = lightClipFromView * view;
}
