// Stores one value into an fp16 image: how this device rounds floats to fp16 in image stores
// (Renderer::halfFloatRounding), which the CPU twin of the lookup must round alike.
layout(local_size_x = 1) in;
layout(binding = 0, rgba16f) uniform writeonly image2D target;
uniform float value;

void main() {
  imageStore(target, ivec2(0, 0), vec4(value));
}
