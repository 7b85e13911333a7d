// Light pass: scene geometry seen from the light.
layout(location = 0) in vec3 position;

uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromView;

out vec3 lightViewPosition;

void main() {
  vec4 view = lightViewFromWorld * vec4(position, 1.0f);
  lightViewPosition = view.xyz;
  gl_Position = lightClipFromView * view;
}
