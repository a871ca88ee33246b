#version 450 core
// ISR step 2b (isr.temporal_frames > 1): the gather averaged over frames. The kernels turn every
// frame (gather.comp), so successive gathers use different sender patches, and their running
// mean converges to a gather with many more patches. Each coarse pixel's surface point is
// projected into the previous frame; where that frame's coarse pixel there saw the same point
// (within two coarse pixels' footprint, widened at grazing angles) on the same side of the
// surface (normals within 25 degrees: a thin wall seen from behind is not its front), the mean continues, up to
// uMaxFrames gathers (then it moves as an exponential average of that length); elsewhere
// (disocclusion, off screen, the first frame) it starts again from this frame's gather.
#include "common/screen_pass.glsl"

uniform sampler2D uGather;           // this frame: rgb irradiance, w occlusion
uniform sampler2D uCoarsePosition;   // xyz world position, w hit
uniform sampler2D uCoarseNormal;     // xyz normal, w depth
uniform sampler2D uHistory;          // the previous frame's mean (as uGather)
uniform sampler2D uHistoryPosition;  // the previous frame's points: xyz, w gathers in its mean
uniform sampler2D uHistoryNormal;    // the previous frame's normals (xyz)
uniform mat4 uPreviousViewProjection;
uniform bool uHistoryValid;
uniform int uMaxFrames;
uniform vec3 uEye;
uniform float uPixelAngle;  // a coarse pixel's edge on the image plane at unit distance

layout(rgba32f) writeonly uniform image2D uOutMean;
layout(rgba32f) writeonly uniform image2D uOutPosition;
layout(rgba32f) writeonly uniform image2D uOutNormal;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    vec4 current = texelFetch(uGather, pixel, 0);
    vec4 p = texelFetch(uCoarsePosition, pixel, 0);
    vec3 normal = texelFetch(uCoarseNormal, pixel, 0).xyz;
    imageStore(uOutNormal, pixel, vec4(normal, 0.0));
    if (p.w <= 0.0) {
        imageStore(uOutMean, pixel, current);
        imageStore(uOutPosition, pixel, vec4(0.0));
        return;
    }
    float frames = 0.0;
    vec4 history = vec4(0.0);
    if (uHistoryValid) {
        vec4 clip = uPreviousViewProjection * vec4(p.xyz, 1.0);
        if (clip.w > 0.0) {
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
                ivec2 q = ivec2(uv * vec2(textureSize(uHistoryPosition, 0)));
                vec4 previous = texelFetch(uHistoryPosition, q, 0);
                vec3 toEye = uEye - p.xyz;
                float cosine = abs(dot(normal, normalize(toEye)));
                float tolerance = 2.0 * uPixelAngle * length(toEye) / max(cosine, 0.2);
                bool sameSide = dot(texelFetch(uHistoryNormal, q, 0).xyz, normal) >= 0.9;
                if (previous.w > 0.0 && sameSide && distance(previous.xyz, p.xyz) <= tolerance) {
                    frames = previous.w;
                    history = texelFetch(uHistory, q, 0);
                }
            }
        }
    }
    float n = min(frames + 1.0, float(uMaxFrames));
    imageStore(uOutMean, pixel, mix(history, current, 1.0 / n));
    imageStore(uOutPosition, pixel, vec4(p.xyz, n));
}
