// The sun's visibility from its cascaded shadow maps (render/frame/sun_cascades.h), filtered by
// percentage-closer soft shadows: a blocker search finds how far above the receiver the casters
// are, the sun's angular radius turns that gap into the penumbra's width, and a PCF kernel of
// that width gives the visibility. Both kernels turn per pixel and per frame
// (shared/disc_samples.h), so frames that accumulate average to a smooth penumbra. Depths are compared against the receiver's plane
// (from its normal), not its centre, so wide kernels on sloped surfaces do not shadow
// themselves.
#ifndef VOXGI_SUN_SHADOW_GLSL
#define VOXGI_SUN_SHADOW_GLSL
#include "shared/disc_samples.h"
#include "shared/sun_shadow.h"

uniform sampler2DArrayShadow uSunShadow;  // the cascades, compared with depth (bilinear PCF)
uniform sampler2DArray uSunDepth;         // the same texture's depths, for the blocker search
uniform sampler2DArray uSunTileDepth;     // the nearest depth of each kSunTileTexels tile
uniform mat4 uCascadeMatrix[kMaxSunMaps];  // world -> map xy, depth in [0, 1]
uniform float uCascadeTexel[kMaxSunMaps];  // world size of a texel (m)
uniform int uCascadeCount;
uniform mat3 uWorldToLight;  // x, y across the maps, z the way sunlight travels
uniform float uDepthRange;   // world length of map depth 0..1 (m)
uniform float uSunTan;       // tan of the sun's angular radius; 0: a sharp sun (1-texel PCF)
uniform int uFrame;

const int kBlockerSamples = 16;
const int kFilterSamples = 32;
// Penumbrae wider than this many texels of the cascade are cut to it (at 2048 texels over the
// first cascade's few metres, tens of centimetres of penumbra).
const float kMaxFilterTexels = float(kSunTileTexels);
const float kNormalOffsetTexels = 1.5;  // the receiver is moved off its surface by this much
const float kDepthBiasTexels = 1.0;     // and compared this much (in depth) in front of itself
const float kMaxReceiverSlope = 8.0;    // depth change per unit across the map, beyond: grazing

// 1 where the sun reaches p (surface normal n), 0 in full shadow.
float sunVisibility(vec3 p, vec3 n, ivec2 pixel) {
    vec3 nl = uWorldToLight * n;
    // Depth change per metre across the map on the receiver's plane.
    vec2 slope = nl.z < -1e-4 ? clamp(-nl.xy / nl.z, -kMaxReceiverSlope, kMaxReceiverSlope) : vec2(0.0);
    float rotation = discRotation(pixel, uFrame);
    float mapSize = float(textureSize(uSunDepth, 0).x);
    for (int c = 0; c < uCascadeCount; ++c) {
        float texel = uCascadeTexel[c];
        vec3 s = (uCascadeMatrix[c] * vec4(p + n * (kNormalOffsetTexels * texel), 1.0)).xyz;
        float reach = (kMaxFilterTexels + 1.0) / mapSize;
        if (c + 1 < uCascadeCount && (any(lessThan(s.xy, vec2(reach))) || any(greaterThan(s.xy, vec2(1.0 - reach)))))
            continue;
        if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0)))) return 1.0;
        // Map depth per texel across, and the comparison's bias, in map depth units.
        vec2 slopePerTexel = slope * (texel / uDepthRange);
        float bias = kDepthBiasTexels * texel / uDepthRange;
        float filterTexels = 1.0;
        if (uSunTan > 0.0) {
            // The blocker search spans what the sun's disc covers between the receiver and the
            // nearest caster of the 3 x 3 tiles around it (which hold every texel the widest
            // kernel reaches): a tight search finds thin casters that sparse samples of a wide
            // one would miss.
            ivec2 tiles = textureSize(uSunTileDepth, 0).xy;
            ivec2 tile = ivec2(s.xy * mapSize) / kSunTileTexels;
            float nearest = 1.0;
            for (int y = -1; y <= 1; ++y)
                for (int x = -1; x <= 1; ++x)
                    nearest = min(nearest, texelFetch(uSunTileDepth, ivec3(clamp(tile + ivec2(x, y), ivec2(0), tiles - 1), c), 0).r);
            float searchTexels = clamp(uSunTan * max(s.z - nearest, 0.0) * uDepthRange / texel, 1.0, kMaxFilterTexels);
            float gapSum = 0.0;
            int blockers = 0;
            for (int i = 0; i < kBlockerSamples; ++i) {
                vec2 o = searchTexels * vogelDisc(i, kBlockerSamples, rotation);
                float receiver = s.z + dot(slopePerTexel, o) - bias;
                float stored = texture(uSunDepth, vec3(s.xy + o / mapSize, float(c))).r;
                if (stored < receiver) {
                    gapSum += receiver - stored;
                    ++blockers;
                }
            }
            // A search that found no caster keeps the 1-texel kernel: its few samples miss thin
            // casters (a pole a few texels wide) that the kernel under the receiver still sees.
            if (blockers > 0) {
                float penumbraWorld = uSunTan * (gapSum / float(blockers)) * uDepthRange;
                filterTexels = clamp(penumbraWorld / texel, 1.0, kMaxFilterTexels);
            }
        }
        float lit = 0.0;
        for (int i = 0; i < kFilterSamples; ++i) {
            vec2 o = filterTexels * vogelDisc(i, kFilterSamples, rotation);
            float receiver = s.z + dot(slopePerTexel, o) - bias;
            lit += texture(uSunShadow, vec4(s.xy + o / mapSize, float(c), receiver));
        }
        return lit / float(kFilterSamples);
    }
    return 1.0;
}
#endif
