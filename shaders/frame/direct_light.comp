#version 450 core
// Adds one light sample's reflected radiance (W/(m^2 sr)) to the accumulation target. The light
// is lights[uLight], evaluated by the shared light model (shaders/shared/light_model.h); its
// shadow is the cube map for point and quad lights, the 2D map for spot lights and the cascades
// (frame/sun_shadow.glsl) for directional ones.
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "common/brdf.glsl"
#include "common/scene_data.glsl"
#include "common/gbuffer_textures.glsl"
#include "frame/sun_shadow.glsl"

uniform samplerCube uShadowCube;
uniform sampler2DShadow uShadow2D;

uniform int uLight;
uniform vec2 uQuadSample;       // quad lights: this frame's point of the quad, in [0,1)^2
uniform vec3 uEye;
// Surfaces seen through mirrors and glass (the hybrid method's layers): each pixel's viewer is
// the point its ray left, in uViewOrigin, instead of the eye.
uniform int uViewOriginPerPixel;
uniform sampler2D uViewOrigin;
// The hybrid method traces mirror-like lobes (smoothLobe): its rays find the quad lights' emitting
// geometry there, so this pass leaves that reflection to them.
uniform float uTracedRoughness;
uniform vec3 uShadowEye;        // the cube map's centre (point light; quad sample lifted off the quad)
uniform mat4 uShadowMatrix;     // world -> shadow texture space (spot maps)
uniform float uShadowTexel;     // world size of one shadow texel at unit distance (normal offset)
// The picture's first pixel in the targets (a guard band's width): soft shadows' noise follows
// the picture's pixels, so a band leaves them as they were.
uniform ivec2 uPictureOrigin;

float cubeVisibility(vec3 p, vec3 n) {
    vec3 d = p - uShadowEye;
    float dist = length(d);
    vec3 offset = p + n * (2.0 * uShadowTexel * dist);
    vec3 dir = offset - uShadowEye;
    float stored = texture(uShadowCube, dir).r;
    return length(dir) <= stored * 1.002 ? 1.0 : 0.0;
}

float mapVisibility(vec3 p, vec3 n, float dist) {
    vec3 offset = p + n * (1.5 * uShadowTexel * dist);
    vec4 s = uShadowMatrix * vec4(offset, 1.0);
    s.xyz /= s.w;
    if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0)))) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(uShadow2D, 0));
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) sum += texture(uShadow2D, vec3(s.xy + vec2(x, y) * texel, s.z - 1e-4));
    return sum / 9.0;
}

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) return;
    GBufferSurface g = decodeGBuffer(t);
    Surface s = Surface(g.albedo, g.roughness, g.metallic, g.specular, g.transmission);
    vec3 p = g.position;
    vec3 n = g.normal;
    vec3 viewer = uViewOriginPerPixel != 0 ? texelFetch(uViewOrigin, pixel, 0).xyz : uEye;
    vec3 v = normalize(viewer - p);

    PackedLight light = lights[uLight];
    int kind = light.kind.x;
    // A mirror-like lobe (smoothLobe) under a quad light: one point of the quad a frame would
    // light it with a GGX spike of peak 3e5 at that point alone (fireflies that average out
    // only in the limit); a mirror sees the quad where its reflected ray meets it, every frame.
    // With the hybrid method its rays do that (and the reflection of everything else). Point,
    // spot and directional lights, which no ray can hit, keep their GGX highlight, and so do
    // quad lights on glossy lobes the hybrid traces: one quad point a frame is far less noisy
    // there than rays that must hit the quad, so its rays leave the quad to this pass.
    bool mirror = smoothLobe(g.roughness);
    bool traced = tracedLobe(g.roughness, g.metallic, g.specular, g.transmission, uTracedRoughness);
    bool mirrorSeesQuad = mirror && kind == kLightQuad && !traced;
    IncidentLight incident = evaluateLight(light, p, uQuadSample);
    vec3 l = incident.direction;
    float nl = dot(n, l);
    bool lit = incident.falloff > 0.0 && nl > 0.0;
    float vis = 1.0;
    if (lit || mirrorSeesQuad) {
        if (kind == kLightDirectional) vis = sunVisibility(p, n, pixel - uPictureOrigin);
        else if (kind == kLightSpot) vis = mapVisibility(p, n, incident.distance);
        else if (lit) vis = cubeVisibility(p, n);  // else the quad is behind p: a mirror sees it unshadowed
    }
    vec3 color = vec3(0.0);
    if (lit) {
        vec3 f = mirror && kind == kLightQuad ? surfaceDiffuseAlbedo(g) * kInvPi : evalBrdf(s, n, v, l);
        color = f * incident.irradiance * vis * nl;
    }
    if (mirrorSeesQuad) {
        // The quad's visibility from the frame's point of it stands for the reflected point's.
        vec3 f0 = mix(vec3(g.specular), g.albedo, g.metallic);
        color += (1.0 - g.transmission) * fresnelSchlick(f0, dot(n, v)) * quadRadianceAlong(light, p, reflect(-v, n)) * vis;
    }
    addToTarget(pixel, vec4(color, 1.0));
}
