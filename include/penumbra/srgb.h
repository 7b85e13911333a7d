// The sRGB transfer function of IEC 61966-2-1:1999: linear light to the encoded value a display
// expects. Penumbra shades in linear light (RenderResult::color); writeColorPng encodes it here,
// once, on the way to the file. GLSL never needs it: the GPU reads sRGB textures through
// GL_SRGB8_ALPHA8, and no pass writes encoded colour; the CPU ray tracer decodes them here.
#pragma once

namespace penumbra {

// Linear light in [0,1] (clamped; NaN gives 0) to its sRGB encoding in [0,1]: 12.92 L up to
// L = 0.0031308, 1.055 L^(1/2.4) - 0.055 above.
float srgbFromLinear(float linear);

// The inverse, for an 8-bit sRGB texel as GL_SRGB8_ALPHA8 decodes it (the ray-traced truth's
// textures): encoded / 12.92 up to 0.04045, ((encoded + 0.055) / 1.055)^2.4 above.
float linearFromSrgb(float encoded);

}  // namespace penumbra
