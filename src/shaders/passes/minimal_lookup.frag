// The camera pass's yardstick (bench --passes): the least a lookup of the technique can do on
// one map. The receiver in the light's map, each channel layer read once through the pass's
// filter mode (shared filterLayer: one hardware-filtered fetch where the channels average
// linearly, at the level of the footprint from uv's screen derivatives for mip-mapped modes;
// else the taps reduced by hand: the power CDF's min and max, ESM's log space, which hardware
// filtering would average into a wrong visibility); with the summed-area filter (SUMMED_AREA), each
// read channel's mean over the least box the production lookup takes (the blur's width, no
// footprint) from the table, as it reads the table; the technique's own reconstruction
// (shared/technique_dispatch.h), Lambert + ambient of the base colour, one RGBA8 target. No
// normal offset, receiver plane, soft light, cascade, ESM fallback or diagnostics: what the
// production pass (camera.frag) adds to this is its cost over the yardstick. With
// WITH_ESM_FALLBACK, ESM's threshold classification and fallback as well: the yardstick of ESM's
// camera pass where it classifies so (without, of the pass with its classification off).
#if SUMMED_AREA
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "../lib/lookup_access.glsl"
#include "../lib/material.glsl"
#include "../shared/light_depth.h"
#include "../shared/receiver_plane.h"
#include "../shared/shading.h"

#ifndef LIGHT_PERSPECTIVE
#define LIGHT_PERSPECTIVE 0
#endif
#ifndef LAYER_COUNT
#define LAYER_COUNT 1
#endif
// 1: ESM's classification and fallback too (bench --passes' yardstick of ESM's camera pass with
// the threshold classifier).
#ifndef WITH_ESM_FALLBACK
#define WITH_ESM_FALLBACK 0
#endif

in vec3 worldPosition;
in vec3 worldNormal;
in vec2 baseColorTexcoord;

uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromView;
uniform float lightNear;
uniform float lightFar;
uniform vec3 lightDirection;  // directional: the way light travels
uniform vec3 lightPosition;   // spot
uniform float ambient;

layout(location = 0) out vec4 color;

void main() {
  vec3 n = normalize(worldNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 toLight =
      LIGHT_PERSPECTIVE != 0 ? normalize(lightPosition - worldPosition) : -lightDirection;
  float cosine = max(dot(n, toLight), 0.0f);
  vec4 view = lightViewFromWorld * vec4(worldPosition, 1.0f);
  vec4 clip = lightClipFromView * view;
  vec2 uv = clip.xy / clip.w * 0.5f + 0.5f;
  // Clamped once, as the production lookup's (shadowLookup): the range and the reconstruction.
  float receiver =
      clamp(lightLinearDepth(view.xyz, LIGHT_PERSPECTIVE != 0, lightNear, lightFar), 0.0f, 1.0f);
  TechniqueParams params = lookupParams();  // ESM's filter space compiled in, as the pass's
  LookupSources sources;
  sources.cascade = 0;
  float channels[PENUMBRA_CHANNEL_CAPACITY];  // 4 x LAYER_COUNT where the pass defines it
  for (int i = 0; i < PENUMBRA_CHANNEL_CAPACITY; ++i) channels[i] = 0.0f;
#if SUMMED_AREA
  // Only the channels the reconstruction reads, as the production lookup (LVSM: the receiver's
  // layers): each costs sixteen 64-bit reads here, not a share of one fetch.
  SummedAreaBox box = summedAreaBox(uv, vec2(0.0f), vec2(0.0f), lookupSettings(0));
  ivec2 range = receiverChannelRange(penumbraTechnique, params, receiver);
  for (int c = range.x; c <= range.y; ++c) {
    channels[c] = summedAreaBoxMean(sources, c, box, penumbraLookup.shadowMapSize);
  }
#else
  // The footprint from the screen derivatives of uv, as the hardware takes its own.
  vec2 uvDx = dFdx(uv);
  vec2 uvDy = dFdy(uv);
  for (int layer = 0; layer < LAYER_COUNT; ++layer) {
    ivec4 reductions = ivec4(kReduceMean);
    for (int k = 0; k < 4; ++k) {
      reductions[k] = channelReduction(penumbraTechnique, 4 * layer + k, params);
    }
    vec4 v = filterLayer(sources, lookupSettings(0), layer,
                         all(equal(reductions, ivec4(kReduceMean))), reductions,
                         params.esm.exponent, uv, uvDx, uvDy);
    for (int k = 0; k < 4; ++k) channels[4 * layer + k] = v[k];
  }
#endif
  float visibility =
      clamp(reconstructVisibility(penumbraTechnique, channels, receiver, params), 0.0f, 1.0f);
#if WITH_ESM_FALLBACK
  // ESM's threshold classification (ESM paper §3.3) and, where it finds the planar-receiver
  // assumption failed, the fallback in place of the exponential test, both compiled in as the
  // production pass's: the paper's 2x2 test, or penumbra's PCF of the light's depth under the
  // blur's kernel (the production fallback's own loop: with the radius compiled in, the unrolled
  // taps ran for every pixel, 5.5-6.2 ms a frame in three runs against the loop's 4.9 in the
  // three before, both without a receiver plane) on the receiver plane solved from the screen
  // derivatives, the least that keeps curved faces from shading themselves (the production pass
  // takes it from the triangle's plane: the derivatives' solve is ill-conditioned where the
  // camera grazes a surface). The Z-max classifier reads a pyramid the yardstick does not: no
  // classification there.
  vec2 texelPosition = uv * float(penumbraLookup.shadowMapSize);
  vec2 depthPerTexel = solveDepthGradient(vec3(dFdx(texelPosition), dFdx(receiver)),
                                          vec3(dFdy(texelPosition), dFdy(receiver)));
  if (penumbraTechnique == kTechniqueEsm && params.esm.classifier == kEsmClassifyThreshold &&
      esmFailsThreshold(channels[0], receiver, params.esm)) {
    LookupSettings settings = lookupSettings(0);
    if (params.esm.fallback == kEsmFallbackPaper) {
      visibility = esmPaperFallback(sources, settings, params.esm, uv, receiver);
    } else {
      PcfParams pcf = pcfMatchingPrefilter(settings);
      visibility =
          pcfLookup(sources, settings.shadowMapSize, true, uv, receiver, depthPerTexel, pcf);
    }
  }
#endif
  color = vec4(shadeLambert(materialBaseColor(baseColorTexcoord).rgb, ambient, cosine, visibility),
               1.0f);
}
